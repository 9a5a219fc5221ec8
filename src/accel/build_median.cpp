// accel: the median-split BVH build (the report's build), flattened depth-first as it goes, for
// boxes (build_bvh_median) and for a mesh's triangles (build_mesh_accel): the build's memory, the
// top splitter or one subtree build, then the node bounds. Compiled once per instruction set;
// accel/dispatch.cpp calls the set in use. The plain std::nth_element form of the
// same tree is tests/accel/median_reference.h.
#include <algorithm>
#include <cassert>
#include <limits>
#include <memory>

#include "accel/build_arena.h"
#include "accel/build_subtree.h"
#include "accel/bvh.h"
#include "accel/split_top.h"

namespace raylane::RAYLANE_ISA_NS {
namespace {

using median_detail::begin_array;
using median_detail::build_subtree;
using median_detail::PhaseClock;
using median_detail::SubtreeMemory;
using median_detail::TempBlock;
using median_detail::TopArrays;
using median_detail::TopSplitter;
using median_detail::TreeOut;

/// Leaves hold at most this many primitives whatever BuildParams::max_leaf_size asks:
/// BvhNode::count has 16 bits.
constexpr int max_leaf_limit = std::numeric_limits<uint16_t>::max();

/// Sets every node's bounds, bottom up (children follow their parent, so a backward sweep sees
/// them first): a leaf's from grow_leaf(box, first, count) over its primitives in leaf order, a
/// parent's from its first then its second child, as Aabb::grow would in a recursive build.
template <class GrowLeaf>
void finish_nodes(std::vector<BvhNode, OverwriteAllocator<BvhNode>>& nodes, GrowLeaf&& grow_leaf) {
    for (size_t i = nodes.size(); i-- > 0;) {
        BvhNode& node = nodes[i];
        Aabb box;
        if (node.is_leaf()) {
            grow_leaf(box, node.index, node.count);
        } else {
            box.grow(nodes[i + 1].bounds());
            box.grow(nodes[node.index].bounds());
        }
        for (int k = 0; k < 3; ++k) {
            node.lo[k] = box.lo[k];
            node.hi[k] = box.hi[k];
        }
    }
}

/// The median-split tree over n >= 1 primitives, without node bounds (finish_nodes sets them):
/// nodes and prim_ids. fill(c2) writes twice every primitive's centroid (its box's lo + hi) to
/// c2[0..2][0 .. n-1], one array per axis.
///
/// Up to params.median_subtree primitives, one subtree build. Its memory: nine arrays of n
/// 4-byte values (the centroids and both buffers of the three axis lists) and a block of 16
/// bytes per primitive for the radix sort's items, reused for the side stamps after the sorts.
/// Above, TopSplitter: two buffers of n ids and centroids (eight arrays), the subtree builds'
/// lists and items for median_subtree primitives, the selects' keys (2 max(median_subtree,
/// sampled_from)) and a histogram of histogram_counts. The arrays of n are taken from `lent`
/// when the caller lends 36n bytes it will overwrite afterwards (build_mesh_accel lends the
/// triangle-vertex array it fills next), else from the block: fresh 4 KiB pages are a large
/// part of a first build's time, and lent memory's pages are faulted in once for both uses.
/// `phases`, when given, gets the times of the centroids, the sorts and the splits, measured from
/// `clock`. `paths`, when given, gets the ways the top nodes were split.
template <class FillCentroids>
Bvh median_tree(size_t n, const BuildParams& params, FillCentroids&& fill,
                std::byte* lent = nullptr, BuildPhases* phases = nullptr,
                PhaseClock* clock = nullptr, MedianSplitPaths* paths = nullptr) {
    Bvh bvh;
    const uint32_t max_leaf =
        static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, max_leaf_limit));
    bvh.prim_ids.resize(n);
    // Leaves hold at least max_leaf / 2 primitives (halving a range > max_leaf), so fewer than
    // 4n / max_leaf + 1 nodes are made.
    bvh.nodes.reserve(4 * n / max_leaf + 1);

    assert(!phases == !clock);
    const TreeOut out{bvh.nodes, bvh.prim_ids.data(), max_leaf, phases, clock};
    const size_t limit = std::max<size_t>(params.median_subtree, max_leaf);  // a leaf is a subtree
    if (n <= limit) {  // the temporaries' scope: freeing them is part of the splits' time
        TempBlock block((lent ? 0 : 9 * TempBlock::bytes_for<uint32_t>(n)) +
                        2 * TempBlock::bytes_for<uint64_t>(n));
        // the nine arrays in the lent memory or the block
        std::byte* nine = lent ? lent : reinterpret_cast<std::byte*>(block.take<uint32_t>(9 * n));
        float* centroid2[3];
        SubtreeMemory mem{};
        for (size_t k = 0; k < 3; ++k) {
            centroid2[k] = begin_array<float>(nine + 4 * n * k, n);
            mem.lists[0][k] = begin_array<uint32_t>(nine + 4 * n * (3 + k), n);
            mem.lists[1][k] = begin_array<uint32_t>(nine + 4 * n * (6 + k), n);
        }
        fill(centroid2);
        out.lap(&BuildPhases::centroids);
        mem.items = block.take<uint64_t>(n);
        mem.scratch = block.take<uint64_t>(n);
        build_subtree(centroid2, static_cast<uint32_t>(n), 0, nullptr, mem, out);
    } else {
        // the keys that select_split and select_children gather: all of a node's when it has
        // fewer than sampled_from
        const size_t capacity = std::max<size_t>(limit, median_detail::sampled_from);
        MedianSplitPaths ignored;
        TempBlock block((lent ? 0 : 8 * TempBlock::bytes_for<uint32_t>(n)) +
                        6 * TempBlock::bytes_for<uint32_t>(limit) +
                        TempBlock::bytes_for<uint32_t>(2 * capacity) +
                        TempBlock::bytes_for<uint64_t>(limit) +
                        TempBlock::bytes_for<uint64_t>(limit) +
                        TempBlock::bytes_for<uint32_t>(median_detail::histogram_counts));
        // the two buffers' eight arrays in the lent memory or the block
        std::byte* eight = lent ? lent : reinterpret_cast<std::byte*>(block.take<uint32_t>(8 * n));
        TopArrays buffers[2];
        for (size_t b = 0; b < 2; ++b) {
            buffers[b].ids = begin_array<uint32_t>(eight + 4 * n * (4 * b), n);
            for (size_t k = 0; k < 3; ++k)
                buffers[b].c2[k] = begin_array<float>(eight + 4 * n * (4 * b + 1 + k), n);
        }
        fill(buffers[0].c2);
        out.lap(&BuildPhases::centroids);
        SubtreeMemory mem{};
        for (int b = 0; b < 2; ++b)
            for (int k = 0; k < 3; ++k) mem.lists[b][k] = block.take<uint32_t>(limit);
        mem.items = block.take<uint64_t>(limit);
        mem.scratch = block.take<uint64_t>(limit);
        const TopSplitter top{out,
                              mem,
                              static_cast<uint32_t>(limit),
                              block.take<uint32_t>(2 * capacity),
                              static_cast<uint32_t>(capacity),
                              block.take<uint32_t>(median_detail::histogram_counts),
                              buffers[0].ids,
                              paths ? *paths : ignored};
        // the root's ids are its positions: not written, read as such
        const TopArrays root{nullptr, {buffers[0].c2[0], buffers[0].c2[1], buffers[0].c2[2]}};
        top.build(0, static_cast<uint32_t>(n), root, buffers[1]);
    }
    out.lap(&BuildPhases::splits);
    return bvh;
}

}  // namespace

Bvh build_bvh_median_isa(std::span<const Aabb> prim_bounds, const BuildParams& params,
                         MedianSplitPaths* paths) {
    if (prim_bounds.empty()) return {};
    const size_t n = prim_bounds.size();
    Bvh bvh = median_tree(
        n, params,
        [&](float* const* c2) {
            for (size_t i = 0; i < n; ++i)
                for (int k = 0; k < 3; ++k) c2[k][i] = prim_bounds[i].lo[k] + prim_bounds[i].hi[k];
        },
        nullptr, nullptr, nullptr, paths);
    const uint32_t* ids = bvh.prim_ids.data();
    finish_nodes(bvh.nodes, [&](Aabb& box, uint32_t first, uint32_t count) {
        for (uint32_t p = first; p < first + count; ++p) box.grow(prim_bounds[ids[p]]);
    });
    return bvh;
}

/// The mesh's form of build_bvh_median_isa with no array of triangle boxes: the centroids come
/// straight from the vertices (the box Aabb::grow makes of a triangle's three vertices), and
/// the leaf boxes from the vertices in leaf order, read in sequence, instead of the boxes
/// gathered by id. The same min and max of the same numbers in the same order, so the same
/// tree bit for bit (tests/accel/build_median_golden_test.cpp).
MeshAccel build_mesh_accel_isa(const MeshData& mesh, const BuildParams& params) {
    MeshAccel accel;
    const size_t n = mesh.tris.size();
    if (n == 0) return accel;
    if (params.method == BvhBuild::sah) return build_mesh_accel_sah(mesh, params);
    PhaseClock clock;  // the centroids' phase includes making the arrays the build fills
    const uvec3* tris = mesh.tris.data();
    const vec3* positions = mesh.positions.data();
    // the vertex array, 36 bytes per triangle, is lent to the build as its nine arrays before
    // it gets the vertices: no pages are faulted in twice
    static_assert(sizeof(TriangleVerts) == 9 * sizeof(uint32_t));
    accel.verts.resize(n);
    std::byte* lent = reinterpret_cast<std::byte*>(accel.verts.data());
    accel.bvh = median_tree(
        n, params,
        [&](float* const* c2) {
            for (size_t i = 0; i < n; ++i) {
                Aabb box;
                box.grow(positions[tris[i].x]);
                box.grow(positions[tris[i].y]);
                box.grow(positions[tris[i].z]);
                for (int k = 0; k < 3; ++k) c2[k][i] = box.lo[k] + box.hi[k];
            }
        },
        lent, &accel.phases, &clock);
    // vertices in leaf order (made anew in the lent memory): a gather by id, its addresses
    // asked for ahead (the triangle's indices 128 triangles ahead, its vertices 64 ahead, whose
    // indices are then in cache): far enough to cover a miss to memory, not only to the
    // last-level cache, which the meshes of 400k triangles and more outgrow.
    const uint32_t* ids = accel.bvh.prim_ids.data();
    constexpr size_t tri_ahead = 128, vert_ahead = 64;
    for (size_t k = 0; k < n; ++k) {
        if (k + tri_ahead < n) __builtin_prefetch(&tris[ids[k + tri_ahead]]);
        if (k + vert_ahead < n) {
            const uvec3 ahead = tris[ids[k + vert_ahead]];
            __builtin_prefetch(&positions[ahead.x]);
            __builtin_prefetch(&positions[ahead.y]);
            __builtin_prefetch(&positions[ahead.z]);
        }
        const uvec3 t = tris[ids[k]];
        std::construct_at(&accel.verts[k],
                          TriangleVerts{positions[t.x], positions[t.y], positions[t.z]});
    }
    accel.phases.vertices = clock.lap();
    const TriangleVerts* verts = accel.verts.data();
    finish_nodes(accel.bvh.nodes, [&](Aabb& box, uint32_t first, uint32_t count) {
        for (uint32_t p = first; p < first + count; ++p) {
            box.grow(verts[p].a);
            box.grow(verts[p].b);
            box.grow(verts[p].c);
        }
    });
    accel.phases.boxes = clock.lap();
    accel.wide = collapse_to_wide(accel.bvh);
    pack_leaf_triangles(accel.wide, accel.verts);
    accel.phases.collapse = clock.lap();
    return accel;
}

}  // namespace raylane::RAYLANE_ISA_NS
