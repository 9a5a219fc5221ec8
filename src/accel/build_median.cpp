// accel: the median-split BVH build (the report's build), flattened depth-first as it goes.
#include <algorithm>
#include <cassert>

#include "accel/bvh.h"

namespace raylane {
namespace {

/// A primitive during the build: its box and its caller index (32 bytes, sorted in place).
struct PrimRef {
    Aabb box;
    uint32_t id;
    float centroid(int axis) const { return box.lo[axis] + box.hi[axis]; }  // 2x, order only
};

struct Builder {
    std::vector<PrimRef>& refs;
    std::vector<BvhNode>& nodes;
    int max_leaf;

    static void set_bounds(BvhNode& node, const Aabb& box) {
        for (int k = 0; k < 3; ++k) {
            node.lo[k] = box.lo[k];
            node.hi[k] = box.hi[k];
        }
    }

    // Emits the node for refs[begin, end) and its subtree in depth-first order.
    void build(uint32_t begin, uint32_t end) {
        Aabb bounds, centroids;
        for (uint32_t i = begin; i < end; ++i) {
            bounds.grow(refs[i].box);
            centroids.grow(refs[i].box.center());
        }
        const uint32_t node_index = static_cast<uint32_t>(nodes.size());
        nodes.push_back({});
        set_bounds(nodes[node_index], bounds);
        const uint32_t count = end - begin;
        if (count <= static_cast<uint32_t>(max_leaf)) {
            nodes[node_index].index = begin;
            nodes[node_index].count = static_cast<uint16_t>(count);
            nodes[node_index].axis = 0;
            return;
        }
        // split: object median along the longest axis of the centroid bounds
        const int axis = centroids.longest_axis();
        const uint32_t mid = begin + count / 2;
        std::nth_element(refs.begin() + begin, refs.begin() + mid, refs.begin() + end,
                         [axis](const PrimRef& a, const PrimRef& b) {
                             return a.centroid(axis) < b.centroid(axis);
                         });
        nodes[node_index].count = 0;
        nodes[node_index].axis = static_cast<uint16_t>(axis);
        build(begin, mid);  // first child follows its parent
        nodes[node_index].index = static_cast<uint32_t>(nodes.size());
        build(mid, end);
    }
};

}  // namespace

Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params) {
    Bvh bvh;
    if (prim_bounds.empty()) return bvh;
    const int max_leaf = std::clamp(params.max_leaf_size, 1, 65535);
    std::vector<PrimRef> refs(prim_bounds.size());
    for (size_t i = 0; i < prim_bounds.size(); ++i)
        refs[i] = {prim_bounds[i], static_cast<uint32_t>(i)};
    // A median-split tree over n primitives has fewer than 2n / max_leaf * 2 nodes.
    bvh.nodes.reserve(4 * prim_bounds.size() / static_cast<size_t>(max_leaf) + 1);
    Builder{refs, bvh.nodes, max_leaf}.build(0, static_cast<uint32_t>(refs.size()));
    bvh.prim_ids.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) bvh.prim_ids[i] = refs[i].id;
    return bvh;
}

}  // namespace raylane
