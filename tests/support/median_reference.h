// tests/support: a straightforward std::nth_element median-split BVH written from the spec of
// build_bvh_median (src/accel/build_median.cpp must build the identical tree, bit for bit).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/bvh.h"

namespace raylane::test {

/// The spec, with its tie rule made explicit:
/// - a primitive's centroid on axis k is represented by c2 = lo[k] + hi[k] (twice the centroid,
///   one float add, no rounding of a halving); primitives are ordered on axis k by the float's
///   bits mapped to a total order (-0 before +0, NaNs with the sign bit below everything, other
///   NaNs above everything), ties broken by the smaller primitive index;
/// - a node of more than max_leaf primitives splits on the longest axis of its centroid bounds
///   (extent = c2 of the last minus c2 of the first primitive in that order; Aabb::longest_axis,
///   so x wins ties over y over z); its first child gets the count / 2 first primitives in that
///   order, the second child the rest;
/// - a leaf lists its primitives in the order along x; nodes are depth first (first child right
///   after its parent), a leaf's index is its first position in prim_ids, an interior node's
///   index its second child, axis 0 for leaves;
/// - bounds are grown bottom up with Aabb::grow: a leaf from its primitives in leaf order, a
///   parent from its first then its second child (so of equal -0 / +0 bounds the first seen
///   in leaf order is kept).
class MedianReference {
  public:
    static uint32_t order_key(float f) {
        const uint32_t u = std::bit_cast<uint32_t>(f);
        return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
    }

    static Bvh build(std::span<const Aabb> boxes, int max_leaf_size) {
        MedianReference r(boxes, max_leaf_size);
        if (!boxes.empty()) r.build_node(0, static_cast<uint32_t>(boxes.size()));
        return std::move(r.bvh_);
    }

  private:
    MedianReference(std::span<const Aabb> boxes, int max_leaf_size)
        : boxes_(boxes), max_leaf_(static_cast<uint32_t>(std::clamp(max_leaf_size, 1, 65535))) {
        for (int k = 0; k < 3; ++k)
            for (const Aabb& b : boxes) c2_[k].push_back(b.lo[k] + b.hi[k]);
        for (uint32_t i = 0; i < boxes.size(); ++i) ids_.push_back(i);
        bvh_.prim_ids.resize(boxes.size());
    }

    bool less(int axis, uint32_t a, uint32_t b) const {
        const uint32_t ka = order_key(c2_[axis][a]), kb = order_key(c2_[axis][b]);
        return ka < kb || (ka == kb && a < b);
    }

    Aabb build_node(uint32_t begin, uint32_t end) {
        const size_t index = bvh_.nodes.size();
        bvh_.nodes.push_back({});
        const auto first = ids_.begin() + begin, last = ids_.begin() + end;
        Aabb bounds;
        BvhNode node{};
        if (end - begin <= max_leaf_) {
            std::sort(first, last, [&](uint32_t a, uint32_t b) { return less(0, a, b); });
            for (uint32_t i = begin; i < end; ++i) {
                bvh_.prim_ids[i] = ids_[i];
                bounds.grow(boxes_[ids_[i]]);
            }
            node.index = begin;
            node.count = static_cast<uint16_t>(end - begin);
        } else {
            vec3 extent;
            for (int k = 0; k < 3; ++k) {
                auto by_k = [&](uint32_t a, uint32_t b) { return less(k, a, b); };
                const auto [lo, hi] = std::minmax_element(first, last, by_k);
                extent[k] = c2_[k][*hi] - c2_[k][*lo];
            }
            const int axis = Aabb{vec3(0.0f), extent}.longest_axis();
            const uint32_t mid = begin + (end - begin) / 2;
            std::nth_element(first, ids_.begin() + mid, last,
                             [&](uint32_t a, uint32_t b) { return less(axis, a, b); });
            bounds.grow(build_node(begin, mid));
            node.index = static_cast<uint32_t>(bvh_.nodes.size());
            bounds.grow(build_node(mid, end));
            node.axis = static_cast<uint16_t>(axis);
        }
        for (int k = 0; k < 3; ++k) {
            node.lo[k] = bounds.lo[k];
            node.hi[k] = bounds.hi[k];
        }
        bvh_.nodes[index] = node;
        return bounds;
    }

    std::span<const Aabb> boxes_;
    uint32_t max_leaf_;
    std::vector<float> c2_[3];
    std::vector<uint32_t> ids_;
    Bvh bvh_;
};

}  // namespace raylane::test
