// accel: the median-split BVH build (the report's build), flattened depth-first as it goes.
#include <algorithm>

#include "accel/bvh.h"

namespace raylane {
namespace {

/// A primitive during the build: twice its centroid (lo + hi; for ordering only) and its
/// caller index. 16 bytes, partitioned in place; boxes are looked up by id.
struct PrimRef {
    float centroid2[3];
    uint32_t id;
};

template <int axis>
void partition_at_median(PrimRef* begin, PrimRef* mid, PrimRef* end) {
    std::nth_element(begin, mid, end, [](const PrimRef& a, const PrimRef& b) {
        return a.centroid2[axis] < b.centroid2[axis];
    });
}

struct Builder {
    std::span<const Aabb> prim_bounds;
    std::vector<PrimRef>& refs;
    std::vector<BvhNode>& nodes;
    uint32_t max_leaf;

    static void set_bounds(BvhNode& node, const Aabb& box) {
        for (int k = 0; k < 3; ++k) {
            node.lo[k] = box.lo[k];
            node.hi[k] = box.hi[k];
        }
    }

    /// Emits the node for refs[begin, end) and its subtree in depth-first order; returns the
    /// node's bounds (computed bottom-up: leaves from their boxes, parents from their children).
    Aabb build(uint32_t begin, uint32_t end) {
        const uint32_t node_index = static_cast<uint32_t>(nodes.size());
        nodes.push_back({});
        const uint32_t count = end - begin;
        Aabb bounds;
        if (count <= max_leaf) {
            // leaf
            for (uint32_t i = begin; i < end; ++i) bounds.grow(prim_bounds[refs[i].id]);
            BvhNode& node = nodes[node_index];
            set_bounds(node, bounds);
            node.index = begin;
            node.count = static_cast<uint16_t>(count);
            node.axis = 0;
            return bounds;
        }
        // split: object median along the longest axis of the centroid bounds
        vec3 c_lo(infinity), c_hi(-infinity);
        for (uint32_t i = begin; i < end; ++i) {
            const vec3 c(refs[i].centroid2[0], refs[i].centroid2[1], refs[i].centroid2[2]);
            c_lo = glm::min(c_lo, c);
            c_hi = glm::max(c_hi, c);
        }
        const int axis = Aabb{c_lo, c_hi}.longest_axis();
        const uint32_t mid = begin + count / 2;
        PrimRef* base = refs.data();
        if (axis == 0) partition_at_median<0>(base + begin, base + mid, base + end);
        if (axis == 1) partition_at_median<1>(base + begin, base + mid, base + end);
        if (axis == 2) partition_at_median<2>(base + begin, base + mid, base + end);
        bounds.grow(build(begin, mid));  // the first child follows its parent
        const uint32_t second = static_cast<uint32_t>(nodes.size());
        bounds.grow(build(mid, end));
        BvhNode& node = nodes[node_index];
        set_bounds(node, bounds);
        node.index = second;
        node.count = 0;
        node.axis = static_cast<uint16_t>(axis);
        return bounds;
    }
};

}  // namespace

Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params) {
    Bvh bvh;
    if (prim_bounds.empty()) return bvh;
    const uint32_t max_leaf = static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, 65535));
    std::vector<PrimRef> refs(prim_bounds.size());
    for (size_t i = 0; i < prim_bounds.size(); ++i) {
        const Aabb& b = prim_bounds[i];
        refs[i] = {{b.lo.x + b.hi.x, b.lo.y + b.hi.y, b.lo.z + b.hi.z}, static_cast<uint32_t>(i)};
    }
    // Leaves hold at least max_leaf / 2 primitives (halving a range > max_leaf), so fewer than
    // 4n / max_leaf + 1 nodes are made.
    bvh.nodes.reserve(4 * prim_bounds.size() / max_leaf + 1);
    Builder{prim_bounds, refs, bvh.nodes, max_leaf}.build(0, static_cast<uint32_t>(refs.size()));
    bvh.prim_ids.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) bvh.prim_ids[i] = refs[i].id;
    return bvh;
}

}  // namespace raylane
