// accel: the median-split build's selects (select_split.h): radix selects of the median key among
// the keys that an even sample brackets, and a radix select of all the keys as the fallback.
#include "accel/select_split.h"

#include <algorithm>
#include <bit>

#include "accel/order_key.h"
#include "simd/lanes.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {
namespace {

/// The k-th smallest (from 0) of m keys and how many of the keys are smaller, for keys that are
/// all within [lo, hi]: a radix select, select_digit_bits of the keys' offset from lo at a time
/// from the top of the range's width, each round counting the keys within the bucket the last
/// one chose.
struct Selected {
    uint32_t key, below;
};

/// Bits of the keys' offsets that select_key counts per round: a histogram of 2,048 counts
/// (8 KiB on the stack), three rounds for keys that span all 32 bits.
constexpr int select_digit_bits = 11;

Selected select_key(const uint32_t* keys, uint32_t m, uint32_t k, uint32_t lo, uint32_t hi) {
    uint32_t below = 0;
    for (;;) {
        const int shift = std::max(int(std::bit_width(hi - lo)) - select_digit_bits, 0);
        uint32_t count[1u << select_digit_bits] = {};
        for (uint32_t i = 0; i < m; ++i) {
            const uint32_t offset = keys[i] - lo;  // wraps for keys below lo
            if (offset <= hi - lo) ++count[offset >> shift];
        }
        uint32_t d = 0;
        while (count[d] <= k) {
            k -= count[d];
            below += count[d++];
        }
        lo += d << shift;
        if (shift == 0) return {lo, below};
        // the bucket's end; it may wrap past 2^32, which the offsets' arithmetic (mod 2^32)
        // absorbs: no key below the caller's lo is among the keys
        hi = lo + ((1u << shift) - 1u);
    }
}

/// The split key of the `left` smallest keys of a node, from the m keys of the node within a
/// bracket and the count `below` of the keys under it; nothing when the bracket does not hold
/// the median.
std::optional<SplitKey> median_of_bracket(const uint32_t* keys, uint32_t m, uint32_t below,
                                          uint32_t left, uint32_t lo, uint32_t hi) {
    if (left < below || left >= below + m) return std::nullopt;
    const Selected s = select_key(keys, m, left - below, lo, hi);
    return SplitKey{s.key, left - below - s.below};
}

/// A bracket of keys [lo, hi] that holds the `left`-th smallest of `count` keys, from an even
/// sample of them: all keys for a node of fewer than sampled_from, or when the sample holds no
/// more than twice the margin.
struct Bracket {
    uint32_t lo = 0, hi = ~0u;
};

Bracket bracket_of_sample(const uint32_t* sample, uint32_t samples, uint32_t left, uint32_t count) {
    constexpr uint32_t margin = 128;  // samples on each side of the median's place in the sample
    if (count < sampled_from || samples <= 2 * margin) return {};
    const uint32_t at = uint32_t(uint64_t(left) * samples / count);
    return {select_key(sample, samples, std::max(at, margin) - margin, 0, ~0u).key,
            select_key(sample, samples, std::min(at + margin, samples - 1), 0, ~0u).key};
}

/// Gathers the keys of a node within a bracket, and counts the keys under it. add() takes the
/// keys in order; false once more than `capacity` would be gathered.
struct BracketGather {
    Bracket b;
    uint32_t* keys;
    uint32_t capacity;
    uint32_t m = 0, below = 0;

    bool add(uint32_t key) {
        below += key < b.lo;
        if (key < b.lo || key > b.hi) return true;
        if (m == capacity) return false;
        keys[m++] = key;
        return true;
    }
    /// The lanes `among` of a packet of keys.
    bool add(const vint<build_width>& key, const vmask<build_width>& among) {
        constexpr int W = build_width;
        const vint<W> lo = broadcast<W>(b.lo), hi = broadcast<W>(b.hi);
        below += uint32_t(count(mask_and(among, lt_u32(key, lo))));
        const vmask<W> in = mask_and(mask_and(among, le_u32(lo, key)), le_u32(key, hi));
        const uint32_t t = uint32_t(count(in));
        if (m + t > capacity) return false;
        compress_store(as_lanes(keys + m), key, in);
        m += t;
        return true;
    }
    /// The split key of the `left` smallest keys of the node, as median_of_bracket.
    std::optional<SplitKey> median(uint32_t left) const {
        return median_of_bracket(keys, m, below, left, b.lo, b.hi);
    }
};

/// select_split's fallback: a radix select, the histogram of the keys' high halves, then of the
/// low halves of the keys in the median's bucket.
SplitKey radix_select(const float* c, uint32_t begin, uint32_t end, uint32_t left,
                      uint32_t* histogram) {
    constexpr int half = 16;  // bits in each half of a key
    static_assert(histogram_counts == uint32_t(1) << half);
    std::fill_n(histogram, histogram_counts, 0u);
    for (uint32_t i = begin; i < end; ++i) ++histogram[order_key(c[i]) >> half];
    uint32_t below = 0, high = 0;
    while (below + histogram[high] <= left) below += histogram[high++];
    std::fill_n(histogram, histogram_counts, 0u);
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t key = order_key(c[i]);
        if ((key >> half) == high) ++histogram[key & (histogram_counts - 1)];
    }
    uint32_t low = 0;
    while (below + histogram[low] <= left) below += histogram[low++];
    return {high << half | low, left - below};
}

}  // namespace

SplitKey select_split(const float* c, uint32_t begin, uint32_t end, uint32_t left,
                      uint32_t* histogram, uint32_t* keys, uint32_t capacity,
                      MedianSplitPaths& paths) {
    constexpr int W = build_width;
    const uint32_t count = end - begin;
    uint32_t* sample = histogram;
    const uint32_t samples = count >= sampled_from ? bracket_samples : 0;
    for (uint32_t j = 0; j < samples; ++j)
        sample[j] = order_key(c[begin + j * (count / bracket_samples)]);
    BracketGather g{bracket_of_sample(sample, samples, left, count), keys, capacity};
    bool fits = true;
    uint32_t i = begin;
    if constexpr (packet_loops)
        for (; fits && i + W <= end; i += W)
            fits = g.add(order_keys(load<W>(c + i)), vmask<W>(true));
    for (; fits && i < end; ++i) fits = g.add(order_key(c[i]));
    if (fits)
        if (const auto s = g.median(left)) {
            ++paths.bracketed;
            return *s;
        }
    ++paths.radix;
    return radix_select(c, begin, end, left, histogram);
}

std::optional<std::array<SplitKey, 2>> select_children(const TopArrays& cur, uint32_t begin,
                                                       uint32_t end, int axis, SplitKey split,
                                                       const int child_axis[2], uint32_t* sample,
                                                       uint32_t* keys, uint32_t capacity) {
    constexpr int W = build_width;
    const uint32_t count = end - begin;
    const uint32_t size[2] = {count / 2, count - count / 2};
    const float* c = cur.c2[axis];
    const float* child_c[2] = {cur.c2[child_axis[0]], cur.c2[child_axis[1]]};
    // the sample: 2 bracket_samples primitives of the node, the keys equal to the split skipped
    // (their side depends on their order)
    uint32_t* taken[2] = {sample, sample + 2 * bracket_samples};
    uint32_t samples[2] = {0, 0};
    if (count >= 2 * sampled_from) {
        const uint32_t step = count / (2 * bracket_samples);
        for (uint32_t j = 0; j < 2 * bracket_samples; ++j) {
            const uint32_t p = begin + j * step, key = order_key(c[p]);
            if (key == split.key) continue;
            const int side = key < split.key ? 0 : 1;
            taken[side][samples[side]++] = order_key(child_c[side][p]);
        }
    }
    BracketGather g[2] = {
        {bracket_of_sample(taken[0], samples[0], size[0] / 2, size[0]), keys, capacity},
        {bracket_of_sample(taken[1], samples[1], size[1] / 2, size[1]), keys + capacity, capacity}};
    // a bracket of every key (too few samples, most keys equal to the split; or samples at
    // both ends of the keys) gathers the child's every key: too many for the buffer
    for (int side = 0; side < 2; ++side)
        if (g[side].b.lo == 0 && g[side].b.hi == ~0u && size[side] > capacity) return std::nullopt;
    SplitSweep sweep{split};
    bool fits = true;
    uint32_t i = begin;
    if constexpr (packet_loops) {
        for (; fits && i + W <= end; i += W) {
            const vint<W> key = order_keys(load<W>(c + i));
            const vmask<W> go_left = sweep.first(key, vmask<W>(true));
            vint<W> child_key[2];
            for (int side = 0; side < 2; ++side)
                child_key[side] =
                    child_axis[side] == axis ? key : order_keys(load<W>(child_c[side] + i));
            fits = g[0].add(child_key[0], go_left) && g[1].add(child_key[1], mask_not(go_left));
        }
    }
    for (; fits && i < end; ++i) {
        const uint32_t side = sweep.first(order_key(c[i])) ^ 1u;
        fits = g[side].add(order_key(child_c[side][i]));
    }
    if (!fits) return std::nullopt;
    std::array<SplitKey, 2> child;
    for (int side = 0; side < 2; ++side) {
        const auto s = g[side].median(size[side] / 2);
        if (!s) return std::nullopt;
        child[side] = *s;
    }
    return child;
}

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
