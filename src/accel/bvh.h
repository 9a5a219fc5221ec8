// accel: the flattened binary BVH shared by both traversal paths, and the two-level scene
// acceleration structure (a BVH per mesh, a top-level BVH over bounded objects).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "accel/wide_bvh.h"
#include "core/aabb.h"
#include "core/pages.h"
#include "raylane/scene.h"  // BvhBuild
#include "scene/scene.h"

namespace raylane {

/// One node, 32 bytes, in depth-first order: an interior node's first child is the next node,
/// `index` is its second child. A leaf (count > 0) holds primitives index .. index + count - 1
/// in leaf order. `axis` is the split axis of an interior node (near child first by sign).
struct alignas(32) BvhNode {
    float lo[3];
    uint32_t index;
    float hi[3];
    uint16_t count;
    uint16_t axis;
    bool is_leaf() const { return count != 0; }
    Aabb bounds() const { return {vec3(lo[0], lo[1], lo[2]), vec3(hi[0], hi[1], hi[2])}; }
};
static_assert(sizeof(BvhNode) == 32 && alignof(BvhNode) == 32);

/// A flattened BVH. prim_ids maps leaf order to the caller's primitive index. Its arrays, and a
/// mesh's vertices in leaf order, are written once by the build: OverwriteAllocator leaves
/// them unwritten when they are made (nodes are added as BvhNode{}) and gives megabytes
/// huge pages.
struct Bvh {
    std::vector<BvhNode, OverwriteAllocator<BvhNode>> nodes;
    std::vector<uint32_t, OverwriteAllocator<uint32_t>> prim_ids;
};

// How the BVHs are built, BvhBuild (median split or binned SAH), is the public API's
// (raylane/scene.h).

/// BuildParams::median_subtree's default, 2^17 (131,072) primitives.
inline constexpr uint32_t default_median_subtree = uint32_t(1) << 17;

struct BuildParams {
    int max_leaf_size = 4;  ///< leaves hold at most this many primitives (1 .. 65535)
    BvhBuild method = BvhBuild::median;
    /// Median split: a node of more primitives than this is split on its own, and each subtree
    /// of at most this many is built in arrays of its own, about 52 bytes per primitive (6.8 MB
    /// at the default, 2^17, which built the 400k and 1.6M dragons fastest on the development
    /// machine: BM_BuildMedianSubtree). Any value (from 1) gives the same tree.
    uint32_t median_subtree = default_median_subtree;
};

/// The build parameters a --bvh value (or the Python module's bvh argument) names: "sah" for
/// binned SAH, anything else the median split.
BuildParams build_params(std::string_view bvh);

/// How a median-split build found the splits of its nodes above BuildParams::median_subtree.
/// Every way gives the same tree; tests use the counts to check that each way was taken.
/// `bracketed` and `radix` count the nodes that select their own split (not the children whose
/// splits a four-way step found); `four_way` and `two_way` count the nodes whose children are
/// both above the limit too.
struct MedianSplitPaths {
    uint32_t bracketed = 0;  ///< median found among the keys a sample bracketed
    uint32_t radix = 0;      ///< the bracket held too many keys or missed: a radix select
    uint32_t four_way = 0;   ///< both children's splits found first, four grandchildren made
    uint32_t two_way = 0;    ///< a child's bracket held too many keys or missed its median: the
                             ///< two children made, each then split on its own
};

/// Median split (the report's build): split along the longest axis of the centroid bounds at the
/// median centroid (ties by primitive index), equal halves, until a node has <= max_leaf_size
/// primitives. The primitive ids are radix sorted by centroid once per axis, and a node splits
/// at the middle of its longest axis's list, partitioning the other two lists stably; a node of
/// more than BuildParams::median_subtree primitives instead finds its median key by a radix
/// select and partitions its primitives, and each node of at most that many becomes such a
/// sorted build of its own. O(n log n); the same tree as std::nth_element's
/// (tests/accel/median_reference.h). `paths`, when given, gets the counts above.
Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params,
                     MedianSplitPaths* paths = nullptr);

/// Entries of a traversal stack: no tree is deeper (a median-split tree over 2^32 primitives is
/// 32 levels deep; the SAH build halves at the median from depth 31 on).
inline constexpr int traversal_stack_size = 64;

/// Entries of a wide tree's traversal stack: each of at most traversal_stack_size levels pushes
/// at most wide_arity - 1 slots, and the last one wide_arity.
inline constexpr int wide_stack_size = traversal_stack_size * (wide_arity - 1) + 1;

/// Binned SAH (16 bins per axis, the cheapest split of the three axes; a node visit costs three
/// primitive tests), a leaf when that is cheaper and the node holds at most max_leaf_size
/// primitives. From depth 31 on it halves at the median, so the tree stays within
/// traversal_stack_size. Same node layout and order rules as build_bvh_median.
Bvh build_bvh_sah(std::span<const Aabb> prim_bounds, const BuildParams& params);

/// Triangle vertices in BVH leaf order, ready for the watertight test (36 bytes each).
struct TriangleVerts {
    vec3 a, b, c;
};

/// Where a median-split mesh build's time went, in milliseconds of wall time, phase by phase in
/// the order they run. build_mesh_accel fills it (the SAH build leaves it zero); `raylane info`
/// prints it, and `bench_build --summary` each phase's growth with the number of triangles.
struct BuildPhases {
    double centroids = 0.0;  ///< the arrays made, each triangle's centroid (O(n))
    double sorts = 0.0;      ///< the three radix sorts of the centroids (O(n))
    double splits = 0.0;     ///< the median splits, level by level (O(n log n)), temporaries freed
    double vertices = 0.0;   ///< the vertices gathered in leaf order (O(n))
    double boxes = 0.0;      ///< the node bounds, bottom up (O(n))
    double collapse = 0.0;   ///< the wide tree collapsed from the binary one, leaves packed (O(n))
};

/// Adds b's phases to a's (a total over several builds).
inline BuildPhases& operator+=(BuildPhases& a, const BuildPhases& b) {
    a.centroids += b.centroids;
    a.sorts += b.sorts;
    a.splits += b.splits;
    a.vertices += b.vertices;
    a.boxes += b.boxes;
    a.collapse += b.collapse;
    return a;
}

struct MeshAccel {
    Bvh bvh;       ///< the binary tree: the scalar path's
    WideBvh wide;  ///< collapsed from bvh, same leaves: the packet path's
    std::vector<TriangleVerts, OverwriteAllocator<TriangleVerts>>
        verts;           ///< verts[k] is triangle bvh.prim_ids[k] of the mesh
    BuildPhases phases;  ///< how long the build's phases took
};

/// Both levels. Objects with infinite extent (planes) are kept out of the top-level BVH and
/// tested one by one from `unbounded`.
struct Accel {
    Bvh top;
    std::vector<Aabb> object_bounds;  ///< world-space bounds per object (empty for planes)
    std::vector<uint32_t> unbounded;  ///< object indices tested outside the BVH
    std::vector<MeshAccel> meshes;    ///< one per SceneData::meshes entry
};

/// A mesh's BVH (params.method: median split or SAH) and its vertices in leaf order.
MeshAccel build_mesh_accel(const MeshData& mesh, const BuildParams& params);
/// build_mesh_accel's SAH form (build_sah.cpp).
MeshAccel build_mesh_accel_sah(const MeshData& mesh, const BuildParams& params);
Accel build_accel(const SceneData& scene, const BuildParams& params);

/// World-space bounds of one object (a transformed shape's box covers its 8 corners).
Aabb object_bounds(const SceneData& scene, const Object& object);

/// Statistics `raylane info` prints.
struct BvhStats {
    size_t nodes = 0, leaves = 0, prims = 0;
    int max_leaf_depth = 0;
    double mean_leaf_depth = 0.0;
    double sah_cost = 0.0;  ///< with C_node = 1, C_prim = 1, relative to the root's area
    size_t bytes = 0;       ///< nodes + prim_ids
};
BvhStats compute_stats(const Bvh& bvh);

/// Checks the invariants: every primitive in exactly one leaf, children inside their parents,
/// leaves no larger than max_leaf_size, leaf boxes contain their primitives. Returns an empty
/// string when all hold, else the first violation.
std::string check_bvh(const Bvh& bvh, std::span<const Aabb> prim_bounds, int max_leaf_size);

}  // namespace raylane
