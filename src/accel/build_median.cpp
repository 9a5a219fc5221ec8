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

/// Moves the k-th smallest (by centroid on `axis`) to a[k], smaller ones before it and larger
/// ones after it: a quickselect (Hoare, 1961) with a median-of-three pivot. Each partition is
/// out of place and branch-free (every element is written to both ends of `scratch`, one cursor
/// advances), so neither mispredicted branches nor store-to-load chains slow it down.
template <int axis>
void select_kth(PrimRef* a, size_t n, size_t k, PrimRef* scratch) {
    size_t lo = 0, hi = n;
    while (hi - lo > 16) {
        const float x = a[lo].centroid2[axis], y = a[lo + (hi - lo) / 2].centroid2[axis];
        const float z = a[hi - 1].centroid2[axis];
        const float pivot = std::max(std::min(x, y), std::min(std::max(x, y), z));
        // partition: [lo, j) < pivot <= [j, hi)
        size_t left = 0, right = hi - lo - 1;
        for (size_t i = lo; i < hi; ++i) {
            const PrimRef v = a[i];
            const bool less = v.centroid2[axis] < pivot;
            scratch[left] = v;
            scratch[right] = v;
            left += less;
            right -= !less;
        }
        std::copy(scratch, scratch + (hi - lo), a + lo);
        size_t j = lo + left;
        if (j == lo) {
            // the pivot is the minimum: gather the elements equal to it at the front
            left = 0;
            right = hi - lo - 1;
            for (size_t i = lo; i < hi; ++i) {
                const PrimRef v = a[i];
                const bool equal = v.centroid2[axis] == pivot;
                scratch[left] = v;
                scratch[right] = v;
                left += equal;
                right -= !equal;
            }
            std::copy(scratch, scratch + (hi - lo), a + lo);
            j = lo + left;
            if (k < j) return;  // a[k] equals the pivot, which is the k-th smallest
        }
        if (k < j)
            hi = j;
        else
            lo = j;
    }
    // small ranges: insertion sort
    for (size_t i = lo + 1; i < hi; ++i) {
        const PrimRef v = a[i];
        size_t j = i;
        for (; j > lo && a[j - 1].centroid2[axis] > v.centroid2[axis]; --j) a[j] = a[j - 1];
        a[j] = v;
    }
}

/// Moves the k-th smallest to a[k] as select_kth does, but first narrows the search with one
/// histogram of the keys over [c_lo, c_hi] (256 bins): elements of lower bins go before the
/// median's bin, higher bins after it, so quickselect only runs inside one small bin.
template <int axis>
void select_kth_binned(PrimRef* a, size_t n, size_t k, float c_lo, float c_hi, PrimRef* scratch) {
    constexpr int bins = 256;
    const float extent = c_hi - c_lo;
    if (!(extent > 0.0f)) return;  // all keys equal: every order is a median split
    const float scale = static_cast<float>(bins) * 0.9999f / extent;
    auto bin_of = [&](const PrimRef& r) {
        const int b = static_cast<int>((r.centroid2[axis] - c_lo) * scale);
        return std::clamp(b, 0, bins - 1);  // monotonic in the key, so bins are ordered
    };
    // histogram
    uint32_t count[bins] = {};
    for (size_t i = 0; i < n; ++i) ++count[bin_of(a[i])];
    // the median's bin m: [0, below) lies in lower bins, [below, below + count[m]) in m
    size_t below = 0;
    int m = 0;
    while (below + count[m] <= k) below += count[m++];
    // partition: lower bins, the median's bin, higher bins (out of place, then copied back)
    size_t cursor[3] = {0, below, below + count[m]};
    for (size_t i = 0; i < n; ++i) {
        const int b = bin_of(a[i]);
        const int region = (b > m) + (b >= m);
        scratch[cursor[region]++] = a[i];
    }
    std::copy(scratch, scratch + n, a);
    select_kth<axis>(a + below, count[m], k - below, scratch);
}

struct Builder {
    std::span<const Aabb> prim_bounds;
    std::vector<PrimRef>& refs;
    std::vector<PrimRef>& scratch;
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
        // split: object median along the longest axis of the centroid bounds (the median element at
        // mid, smaller centroids before it, larger after)
        vec3 c_lo(infinity), c_hi(-infinity);
        for (uint32_t i = begin; i < end; ++i) {
            const vec3 c(refs[i].centroid2[0], refs[i].centroid2[1], refs[i].centroid2[2]);
            c_lo = glm::min(c_lo, c);
            c_hi = glm::max(c_hi, c);
        }
        const int axis = Aabb{c_lo, c_hi}.longest_axis();
        const uint32_t mid = begin + count / 2;
        PrimRef* a = refs.data() + begin;
        PrimRef* tmp = scratch.data();
        const float lo = c_lo[axis], hi = c_hi[axis];
        if (axis == 0) select_kth_binned<0>(a, count, count / 2, lo, hi, tmp);
        if (axis == 1) select_kth_binned<1>(a, count, count / 2, lo, hi, tmp);
        if (axis == 2) select_kth_binned<2>(a, count, count / 2, lo, hi, tmp);
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
    std::vector<PrimRef> scratch(refs.size());
    Builder{prim_bounds, refs, scratch, bvh.nodes, max_leaf}.build(
        0, static_cast<uint32_t>(refs.size()));
    bvh.prim_ids.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) bvh.prim_ids[i] = refs[i].id;
    return bvh;
}

}  // namespace raylane
