// accel: the median-split BVH build (the report's build), flattened depth-first as it goes.
#include <algorithm>
#include <bit>

#include "accel/bvh.h"

namespace raylane {
namespace {

/// A float's bits mapped to an unsigned key with the same order (negatives flipped).
uint32_t order_key(float f) {
    const uint32_t u = std::bit_cast<uint32_t>(f);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

/// The primitive ids 0 .. n-1 sorted by key: LSD radix sort, three passes of 11 bits. Stable.
std::vector<uint32_t> sorted_ids(std::vector<uint32_t> keys) {
    const size_t n = keys.size();
    std::vector<uint32_t> ids(n), keys2(n), ids2(n);
    for (size_t i = 0; i < n; ++i) ids[i] = static_cast<uint32_t>(i);
    // the three digit histograms in one pass
    static thread_local uint32_t histogram[3][2048];
    for (auto& h : histogram) std::fill(std::begin(h), std::end(h), 0u);
    for (uint32_t k : keys) {
        ++histogram[0][k & 2047u];
        ++histogram[1][(k >> 11) & 2047u];
        ++histogram[2][k >> 22];
    }
    for (int pass = 0, shift = 0; pass < 3; ++pass, shift += 11) {
        uint32_t* offset = histogram[pass];
        uint32_t sum = 0;
        for (int d = 0; d < 2048; ++d) {
            const uint32_t c = offset[d];
            offset[d] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; ++i) {
            const uint32_t pos = offset[(keys[i] >> shift) & 2047u]++;
            keys2[pos] = keys[i];
            ids2[pos] = ids[i];
        }
        keys.swap(keys2);
        ids.swap(ids2);
    }
    return ids;
}

/// The build keeps the primitives of every node sorted three times, once per axis by centroid
/// (three lists, the same ids in each node's range). The median along any axis is then the
/// middle of that axis's list, and the centroid bounds are the ends of the three lists. A split
/// partitions the two other lists stably in one pass, into a second set of buffers (no copy
/// back), so a level costs O(n) and the build O(n log n) after three radix sorts.
struct Builder {
    std::span<const Aabb> prim_bounds;
    std::vector<float> centroid2[3];    ///< lo + hi per axis: twice the centroid
    std::vector<uint32_t> order[2][3];  ///< two buffers: depth d reads order[d % 2]
    std::vector<uint8_t> right;         ///< per primitive: goes to the second child
    std::vector<uint32_t>& prim_ids;
    std::vector<BvhNode>& nodes;
    uint32_t max_leaf;

    static void set_bounds(BvhNode& node, const Aabb& box) {
        for (int k = 0; k < 3; ++k) {
            node.lo[k] = box.lo[k];
            node.hi[k] = box.hi[k];
        }
    }

    /// Emits the node for the lists' range [begin, end) and its subtree in depth-first order;
    /// returns the node's bounds (bottom-up: leaves from their boxes, parents from children).
    Aabb build(uint32_t begin, uint32_t end, int depth) {
        const uint32_t node_index = static_cast<uint32_t>(nodes.size());
        nodes.push_back({});
        const uint32_t count = end - begin;
        std::vector<uint32_t>* cur = order[depth & 1];
        std::vector<uint32_t>* next = order[(depth & 1) ^ 1];
        Aabb bounds;
        if (count <= max_leaf) {
            // leaf: its primitives in leaf order
            for (uint32_t i = begin; i < end; ++i) {
                prim_ids[i] = cur[0][i];
                bounds.grow(prim_bounds[cur[0][i]]);
            }
            BvhNode& node = nodes[node_index];
            set_bounds(node, bounds);
            node.index = begin;
            node.count = static_cast<uint16_t>(count);
            node.axis = 0;
            return bounds;
        }
        // split: object median along the longest axis of the centroid bounds
        vec3 extent;
        for (int k = 0; k < 3; ++k)
            extent[k] = centroid2[k][cur[k][end - 1]] - centroid2[k][cur[k][begin]];
        const int axis = Aabb{vec3(0.0f), extent}.longest_axis();
        const uint32_t mid = begin + count / 2;
        for (uint32_t i = begin; i < end; ++i) right[cur[axis][i]] = i >= mid;
        // the split axis's list is already split at mid; the two others are partitioned
        // stably (both in one pass) into the next buffer
        const int k1 = (axis + 1) % 3, k2 = (axis + 2) % 3;
        std::copy(cur[axis].begin() + begin, cur[axis].begin() + end, next[axis].begin() + begin);
        uint32_t l1 = begin, r1 = mid, l2 = begin, r2 = mid;
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t a = cur[k1][i], b = cur[k2][i];
            const bool ra = right[a], rb = right[b];
            next[k1][ra ? r1 : l1] = a;
            next[k2][rb ? r2 : l2] = b;
            r1 += ra, l1 += !ra, r2 += rb, l2 += !rb;
        }
        bounds.grow(build(begin, mid, depth + 1));  // the first child follows its parent
        const uint32_t second = static_cast<uint32_t>(nodes.size());
        bounds.grow(build(mid, end, depth + 1));
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
    const size_t n = prim_bounds.size();
    const uint32_t max_leaf = static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, 65535));
    bvh.prim_ids.resize(n);
    Builder b{prim_bounds, {}, {}, std::vector<uint8_t>(n), bvh.prim_ids, bvh.nodes, max_leaf};
    for (int k = 0; k < 3; ++k) {
        b.centroid2[k].resize(n);
        std::vector<uint32_t> keys(n);
        for (size_t i = 0; i < n; ++i) {
            b.centroid2[k][i] = prim_bounds[i].lo[k] + prim_bounds[i].hi[k];
            keys[i] = order_key(b.centroid2[k][i]);
        }
        b.order[0][k] = sorted_ids(std::move(keys));
        b.order[1][k].resize(n);
    }
    // Leaves hold at least max_leaf / 2 primitives (halving a range > max_leaf), so fewer than
    // 4n / max_leaf + 1 nodes are made.
    bvh.nodes.reserve(4 * n / max_leaf + 1);
    b.build(0, static_cast<uint32_t>(n), 0);
    return bvh;
}

}  // namespace raylane
