// accel: the median-split build's top levels (split_top.h): the centroids' key bounds, the stable
// partitions of a node's ids and centroids into two or four ranges, and the recursion.
#include "accel/split_top.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <optional>

#include "accel/select_split.h"
#include "simd/math.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {
namespace {

/// The smallest and largest order_key of a node's centroids on each axis.
struct KeyBounds {
    uint32_t lo[3] = {~0u, ~0u, ~0u};
    uint32_t hi[3] = {0, 0, 0};
};

// The packet loops' helpers are templates on the build's width, instantiated only by the sets
// whose loops run packets (packet_loops: compaction is native).

/// Grows the bounds on axis k by a packet of smallest and a packet of largest keys.
template <int W>
void grow(KeyBounds& b, int k, const vint<W>& lo, const vint<W>& hi) {
    b.lo[k] = std::min(b.lo[k], hmin_u32(lo));
    b.hi[k] = std::max(b.hi[k], hmax_u32(hi));
}

KeyBounds key_bounds(const TopArrays& a, uint32_t begin, uint32_t end) {
    constexpr int W = build_width;
    KeyBounds b;
    for (int k = 0; k < 3; ++k) {
        const float* c = a.c2[k];
        uint32_t i = begin;
        if constexpr (packet_loops) {
            vint<W> lo = broadcast<W>(~0u), hi = broadcast<W>(0u);
            for (; i + W <= end; i += W) {
                const vint<W> key = order_keys(load<W>(c + i));
                lo = min_u32(lo, key);
                hi = max_u32(hi, key);
            }
            grow<W>(b, k, lo, hi);
        }
        for (; i < end; ++i) {
            const uint32_t key = order_key(c[i]);
            b.lo[k] = std::min(b.lo[k], key);
            b.hi[k] = std::max(b.hi[k], key);
        }
    }
    return b;
}

/// The longest axis of the key bounds' extents (as the centroids' extents).
int longest_axis(const KeyBounds& b) {
    float extent[3];
    for (int k = 0; k < 3; ++k) extent[k] = key_value(b.hi[k]) - key_value(b.lo[k]);
    return median_detail::longest_axis(extent);
}

/// Copies primitive i of a top buffer to position `at` of another.
void copy_primitive(const TopArrays& from, uint32_t i, const TopArrays& to, uint32_t at) {
    to.ids[at] = from.ids ? from.ids[i] : i;
    for (int k = 0; k < 3; ++k) to.c2[k][at] = from.c2[k][i];
}

/// Moves the primitives i .. i + build_width - 1 of `from` that `valid` holds to `to`: those of
/// each group go[g] compressed together and stored from *at[g] (no write past the group's end),
/// which then advances.
template <int W>
void store_compressed(const TopArrays& from, const TopArrays& to, uint32_t i, const vmask<W>& valid,
                      const vmask<W>* go, uint32_t* const* at, int groups) {
    const vint<W> ids = from.ids ? load(as_lanes(from.ids + i), valid)
                                 : add(broadcast<W>(i), lane_index<W>());  // positions
    vfloat<W> c2[3];
    for (int k = 0; k < 3; ++k) c2[k] = load(from.c2[k] + i, valid);
    for (int g = 0; g < groups; ++g) {
        if (bits(go[g]) == bits(valid)) {
            // the whole packet in one group (the mesh's order is near spatial order)
            store(as_lanes(to.ids + *at[g]), ids, valid);
            for (int k = 0; k < 3; ++k) store(to.c2[k] + *at[g], c2[k], valid);
            *at[g] += uint32_t(count(valid));
            return;
        }
        if (none(go[g])) continue;
        const int n = compress_store(as_lanes(to.ids + *at[g]), ids, go[g]);
        for (int k = 0; k < 3; ++k) compress_store(to.c2[k] + *at[g], c2[k], go[g]);
        *at[g] += uint32_t(n);
    }
}

/// The valid lanes of the packet from i in a range that ends at `end`.
template <int W>
vmask<W> valid_from(uint32_t i, uint32_t end) {
    return prefix_mask<W>(int(std::min(end - i, uint32_t{W})));
}

/// Stable partition of a top node's ids and centroids, cur[begin, end), into other: the
/// primitives that `split` on `axis` sends to the first child from begin, the rest from mid.
void partition_top(const TopArrays& cur, const TopArrays& other, uint32_t begin, uint32_t mid,
                   uint32_t end, int axis, SplitKey split) {
    constexpr int W = build_width;
    const float* c = cur.c2[axis];
    SplitSweep sweep{split};
    uint32_t l = begin, r = mid, i = begin;
    if constexpr (packet_loops) {
        // a packet at a time: each side's ids and centroids compressed together and stored (no
        // write past a side's end; the last packet's lanes past `end` are inactive)
        for (; i < end; i += W) {
            const vmask<W> valid = valid_from<W>(i, end);
            const vmask<W> go_left = sweep.first(order_keys(load(c + i, valid)), valid);
            const vmask<W> go[2] = {go_left, mask_andnot(valid, go_left)};
            uint32_t* at[2] = {&l, &r};
            store_compressed<W>(cur, other, i, valid, go, at, 2);
        }
    }
    // branch free (the side is unpredictable)
    for (; i < end; ++i) {
        const uint32_t go_left = sweep.first(order_key(c[i]));
        const uint32_t at = r ^ ((l ^ r) & (0u - go_left));
        copy_primitive(cur, i, other, at);
        l += go_left;
        r += go_left ^ 1u;
    }
    assert(l == mid && r == end);
}

/// The key bounds of both children of a top node split by `split` on `axis`, without moving
/// its primitives.
std::array<KeyBounds, 2> child_key_bounds(const TopArrays& cur, uint32_t begin, uint32_t end,
                                          int axis, SplitKey split) {
    constexpr int W = build_width;
    std::array<KeyBounds, 2> b;
    SplitSweep sweep{split};
    uint32_t i = begin;
    if constexpr (packet_loops) {
        vint<W> lo[2][3], hi[2][3];
        for (int side = 0; side < 2; ++side)
            for (int k = 0; k < 3; ++k) {
                lo[side][k] = broadcast<W>(~0u);
                hi[side][k] = broadcast<W>(0u);
            }
        for (; i + W <= end; i += W) {
            vint<W> key[3];
            for (int k = 0; k < 3; ++k) key[k] = order_keys(load<W>(cur.c2[k] + i));
            const vmask<W> go_left = sweep.first(key[axis], vmask<W>(true));
            const vmask<W> go[2] = {go_left, mask_not(go_left)};
            for (int side = 0; side < 2; ++side)
                for (int k = 0; k < 3; ++k) {
                    lo[side][k] = min_u32(lo[side][k], key[k], go[side]);
                    hi[side][k] = max_u32(hi[side][k], key[k], go[side]);
                }
        }
        for (int side = 0; side < 2; ++side)
            for (int k = 0; k < 3; ++k) grow<W>(b[side], k, lo[side][k], hi[side][k]);
    }
    for (; i < end; ++i) {
        uint32_t key[3];
        for (int k = 0; k < 3; ++k) key[k] = order_key(cur.c2[k][i]);
        KeyBounds& side = b[sweep.first(key[axis]) ^ 1u];
        for (int k = 0; k < 3; ++k) {
            side.lo[k] = std::min(side.lo[k], key[k]);
            side.hi[k] = std::max(side.hi[k], key[k]);
        }
    }
    return b;
}

/// Stable partition of a top node's primitives, cur[begin, end), into the ranges of its four
/// grandchildren in other: split by `split` on `axis`, then each child by child[side] on
/// child_axis[side].
void partition_four(const TopArrays& cur, const TopArrays& other, uint32_t begin, uint32_t end,
                    int axis, SplitKey split, const int child_axis[2],
                    const std::array<SplitKey, 2>& child) {
    constexpr int W = build_width;
    const uint32_t count = end - begin, mid = begin + count / 2;
    uint32_t at[4] = {begin, begin + count / 2 / 2, mid, mid + (count - count / 2) / 2};
    [[maybe_unused]] const uint32_t ends[4] = {at[1], at[2], at[3], end};
    const float* c = cur.c2[axis];
    const float* child_c[2] = {cur.c2[child_axis[0]], cur.c2[child_axis[1]]};
    SplitSweep sweep{split}, child_sweep[2] = {{child[0]}, {child[1]}};
    uint32_t i = begin;
    if constexpr (packet_loops) {
        for (; i < end; i += W) {  // a packet at a time, as partition_top
            const vmask<W> valid = valid_from<W>(i, end);
            const vint<W> key = order_keys(load(c + i, valid));
            const vmask<W> first = sweep.first(key, valid);
            vmask<W> go[4];
            for (int s = 0; s < 2; ++s) {
                const vmask<W> among = s == 0 ? first : mask_andnot(valid, first);
                const vint<W> child_key =
                    child_axis[s] == axis ? key : order_keys(load(child_c[s] + i, valid));
                go[2 * s] = child_sweep[s].first(child_key, among);
                go[2 * s + 1] = mask_andnot(among, go[2 * s]);
            }
            uint32_t* const to[4] = {&at[0], &at[1], &at[2], &at[3]};
            store_compressed<W>(cur, other, i, valid, go, to, 4);
        }
    }
    for (; i < end; ++i) {
        const uint32_t s = sweep.first(order_key(c[i])) ^ 1u;
        const uint32_t q = 2 * s + (child_sweep[s].first(order_key(child_c[s][i])) ^ 1u);
        copy_primitive(cur, i, other, at[q]++);
    }
    for (int q = 0; q < 4; ++q) assert(at[q] == ends[q]);
}

}  // namespace

void TopSplitter::build(uint32_t begin, uint32_t end, const TopArrays& cur,
                        const TopArrays& other) const {
    const uint32_t count = end - begin;
    if (count <= subtree_limit) {
        const float* c2[3] = {cur.c2[0] + begin, cur.c2[1] + begin, cur.c2[2] + begin};
        build_subtree(c2, count, begin, cur.ids + begin, mem, out);
        return;
    }
    const uint32_t node_index = static_cast<uint32_t>(out.nodes.size());
    out.nodes.push_back(BvhNode{});
    const int axis = longest_axis(key_bounds(cur, begin, end));
    out.nodes[node_index].axis = static_cast<uint16_t>(axis);
    const uint32_t mid = begin + count / 2;
    const SplitKey split =
        select_split(cur.c2[axis], begin, end, count / 2, histogram, keys, capacity, paths);
    const TopArrays spare{cur.ids ? cur.ids : root_ids, {cur.c2[0], cur.c2[1], cur.c2[2]}};
    if (count / 2 > subtree_limit) {
        // both children are split on their own too: their splits found first, and the
        // four grandchildren's ranges made in one partition (one pass over the node less)
        const std::array<KeyBounds, 2> bounds = child_key_bounds(cur, begin, end, axis, split);
        const int child_axis[2] = {longest_axis(bounds[0]), longest_axis(bounds[1])};
        if (const auto child = select_children(cur, begin, end, axis, split, child_axis, histogram,
                                               keys, capacity)) {
            partition_four(cur, other, begin, end, axis, split, child_axis, *child);
            ++paths.four_way;
            out.lap(&BuildPhases::splits);
            const uint32_t range[5] = {begin, begin + count / 2 / 2, mid,
                                       mid + (count - count / 2) / 2, end};
            for (int side = 0; side < 2; ++side) {
                const uint32_t child_index = static_cast<uint32_t>(out.nodes.size());
                if (side == 1) out.nodes[node_index].index = child_index;
                out.nodes.push_back(BvhNode{});
                out.nodes[child_index].axis = static_cast<uint16_t>(child_axis[side]);
                build(range[2 * side], range[2 * side + 1], other, spare);
                out.nodes[child_index].index = static_cast<uint32_t>(out.nodes.size());
                build(range[2 * side + 1], range[2 * side + 2], other, spare);
            }
            return;
        }
        ++paths.two_way;
    }
    partition_top(cur, other, begin, mid, end, axis, split);
    out.lap(&BuildPhases::splits);
    build(begin, mid, other, spare);  // the first child follows its parent
    out.nodes[node_index].index = static_cast<uint32_t>(out.nodes.size());
    build(mid, end, other, spare);
}

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
