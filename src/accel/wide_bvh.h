// accel: the packet path's wide tree, collapsed from the binary BVH that the scalar path
// traverses (bvh.h). Same leaves in the same leaf order, so both trees index one array of
// primitive ids; the wide tree keeps its leaves' triangles in SoA (WideBvh::tris).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/pages.h"

namespace raylane {

struct Bvh;
struct TriangleVerts;

/// Children per wide node (N, the arity; style.md): 8 boxes make one 8-wide test.
inline constexpr int wide_arity = 8;

/// A binary subtree of at most this many primitives is one leaf of the wide tree: its leaves'
/// ranges are consecutive in leaf order, so the merged leaf is their union.
inline constexpr uint32_t wide_leaf_size = 8;

/// One wide node, 256 bytes: up to wide_arity children, their boxes as structures of arrays
/// (lo[axis][slot], hi[axis][slot]: one vector load per plane tests every child at once).
/// Slots 0 .. children - 1 are used, in the binary tree's depth-first order; an unused slot's
/// box is empty (lo = +inf, hi = -inf), so no ray enters it. A leaf slot (count > 0) holds the
/// triangles `child` .. child + count - 1 in leaf order (indices into Bvh::prim_ids; their
/// coordinates from WideBvh::tris[9 child] on); an interior slot (count = 0) holds the index of its
/// wide node, which comes after its parent (depth-first, the first interior child right after it).
struct alignas(64) WideNode {
    float lo[3][wide_arity];
    float hi[3][wide_arity];
    uint32_t child[wide_arity];
    uint16_t count[wide_arity];
    uint8_t children = 0;
    bool is_leaf(int slot) const { return count[slot] != 0; }
};
static_assert(sizeof(WideNode) == 256 && alignof(WideNode) == 64);

/// Where a slot leads: a wide node (count 0, child its index) or a leaf's triangles child ..
/// child + count - 1. The default is the root node.
struct WideRef {
    uint32_t child = 0;
    uint32_t count = 0;
};

/// Floats of zeros after the last leaf's triangles in WideBvh::tris, so that a vector load of
/// up to 16 floats from any leaf's arrays stays inside.
inline constexpr size_t wide_tris_pad = 16;

/// A flattened wide tree; node 0 is the root. Empty for an empty binary tree.
struct WideBvh {
    std::vector<WideNode, OverwriteAllocator<WideNode>> nodes;
    /// The leaves' triangles for the watertight test, in SoA groups in leaf order: the leaf of
    /// triangles f .. f + n - 1 is the 9 n floats from tris[9 f] on, the arrays a.x a.y a.z b.x
    /// b.y b.z c.x c.y c.z of n floats each; wide_tris_pad zeros follow the last leaf. A
    /// zero-area triangle's coordinates are NaN, so the packet path needs no zero-area test.
    /// Filled by pack_leaf_triangles; only the packet path reads it.
    std::vector<float, OverwriteAllocator<float>> tris;
};

/// The wide tree of a binary BVH: each wide node adopts binary nodes, the interior one of
/// largest surface area first, until it has wide_arity children or only leaves are left. Its
/// leaves are the binary tree's leaves, and the subtrees of at most wide_leaf_size primitives
/// merged into one leaf each. A tree of one leaf gives one wide node with one child.
WideBvh collapse_to_wide(const Bvh& bvh);

/// Fills wide.tris from the vertices in leaf order (verts[k]: triangle k of the leaf order, the
/// binary tree's MeshAccel::verts): each leaf's triangles as SoA groups.
void pack_leaf_triangles(WideBvh& wide, std::span<const TriangleVerts> verts);

/// Checks the wide tree against the binary tree it was collapsed from: the wide leaves tile the
/// leaf order (every primitive in exactly one leaf), each one binary leaf or consecutive binary
/// leaves of at most wide_leaf_size primitives; every child box is inside its parent's slot;
/// every node has 1 .. wide_arity children (2 or more but for a root over a single leaf);
/// unused slots are empty; every node but the root is reached exactly once and after its
/// parent. Returns an empty string when all hold, else the first violation.
std::string check_wide_bvh(const WideBvh& wide, const Bvh& bvh);

/// Statistics `raylane info` prints for the wide tree.
struct WideStats {
    size_t nodes = 0, leaves = 0, prims = 0;
    double mean_children = 0.0;  ///< used slots per wide node
    size_t bytes = 0;            ///< the wide nodes and the leaves' triangles (ids are shared)
};
WideStats compute_wide_stats(const WideBvh& wide);

}  // namespace raylane
