// accel: the median-split BVH build (the report's build), flattened depth-first as it goes.
// The plain std::nth_element form of the same tree is tests/accel/median_reference.h.
#include <algorithm>
#include <bit>
#include <cassert>
#include <cstring>
#include <memory>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "accel/bvh.h"

namespace raylane {
namespace {

template <class T>
std::unique_ptr<T[]> uninitialized(size_t n) {
    return std::make_unique_for_overwrite<T[]>(n);
}

/// A float's bits mapped to an unsigned key with the same order (negatives flipped; -0 sorts
/// before +0).
uint32_t order_key(float f) {
    const uint32_t u = std::bit_cast<uint32_t>(f);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

/// Sorts the ids 0 .. n-1 by key (keys[id]), stably (equal keys in id order), into `out`:
/// LSD radix sort of (key << 32 | id) items in passes of `digit_bits` bits, skipping the
/// digits every key shares. Wide digits make fewer passes; narrow ones keep the histograms
/// small for small n. `items` and `scratch` hold n items each.
template <int digit_bits>
void sort_ids_by_key(const uint32_t* keys, size_t n, uint32_t* out,
                     std::unique_ptr<uint64_t[]>& items, std::unique_ptr<uint64_t[]>& scratch) {
    constexpr int passes = (32 + digit_bits - 1) / digit_bits;
    constexpr uint32_t digit_mask = (1u << digit_bits) - 1u;
    auto histogram = std::make_unique<uint32_t[]>(size_t(passes) << digit_bits);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t key = keys[i];
        for (int p = 0; p < passes; ++p)
            ++histogram[(size_t(p) << digit_bits) + ((key >> (digit_bits * p)) & digit_mask)];
        items[i] = uint64_t(key) << 32 | i;
    }
    int last = -1;  // the last pass that moves anything writes the ids to `out`
    for (int p = 0; p < passes; ++p) {
        const uint32_t* count = histogram.get() + (size_t(p) << digit_bits);
        if (count[(keys[0] >> (digit_bits * p)) & digit_mask] != n) last = p;
    }
    if (last < 0) {  // all keys equal: id order
        for (size_t i = 0; i < n; ++i) out[i] = static_cast<uint32_t>(i);
        return;
    }
    for (int p = 0; p <= last; ++p) {
        uint32_t* offset = histogram.get() + (size_t(p) << digit_bits);
        const uint32_t shift = 32 + digit_bits * static_cast<uint32_t>(p);
        if (offset[(items[0] >> shift) & digit_mask] == n) continue;  // one digit: no-op pass
        uint32_t sum = 0;
        for (uint32_t d = 0; d <= digit_mask; ++d) {
            const uint32_t c = offset[d];
            offset[d] = sum;
            sum += c;
        }
        const uint64_t* in = items.get();
        if (p == last) {
            for (size_t i = 0; i < n; ++i)
                out[offset[(in[i] >> shift) & digit_mask]++] = static_cast<uint32_t>(in[i]);
            return;
        }
        uint64_t* to = scratch.get();
        for (size_t i = 0; i < n; ++i) to[offset[(in[i] >> shift) & digit_mask]++] = in[i];
        items.swap(scratch);
    }
}

/// The build keeps the primitive ids of every node sorted three times, once per axis by
/// centroid (three lists, the same ids in each node's range). The median along any axis is
/// then the middle of that axis's list, and the centroid bounds are the ends of the three
/// lists. A split stamps the second half of the split axis's list in a byte per primitive
/// (side[id] = depth + 1: no other node of this depth holds the primitive, and its deeper nodes
/// come later) and partitions the two other lists by that stamp, stably, into their second
/// buffers; the split axis's list stays where it is. A level costs O(n) and the build
/// O(n log n) after three radix sorts. Reads by id (centroids, sides) follow the mesh's order,
/// which is close to spatial order in scanned and subdivided meshes.
struct Builder {
    const float* centroid2[3];  ///< per axis, by id: lo + hi (twice the centroid)
    uint8_t* side;              ///< by id, three bytes of padding for 32-bit gathers
    uint32_t* lists[2][3];      ///< lists[b][k]: buffer b of the axis-k list
    uint32_t* prim_ids;
    std::vector<BvhNode>& nodes;
    uint32_t max_leaf;

    /// Stable partition of in[begin, end) into out: ids whose side stamp differs from `stamp`
    /// first (from out + begin), the others from out + mid.
    void partition(const uint32_t* in, uint32_t* out, uint32_t begin, uint32_t mid, uint32_t end,
                   uint8_t stamp) const {
        uint32_t left = begin, right = mid;
        uint32_t i = begin;
#if defined(__AVX512F__)
        // sixteen ids at a time: gather their side bytes, compress each side's ids together and
        // store them with a mask (no write past a side's end)
        const __m512i byte = _mm512_set1_epi32(0xff), s = _mm512_set1_epi32(stamp);
        for (; i < end; i += 16) {
            const uint32_t n = std::min(end - i, 16u);
            const __mmask16 valid = __mmask16((1u << n) - 1u);
            const __m512i ids = _mm512_maskz_loadu_epi32(valid, in + i);
            const __m512i sides =
                _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), valid, ids, side, 1);
            const __mmask16 go_right =
                _mm512_mask_cmpeq_epi32_mask(valid, _mm512_and_si512(sides, byte), s);
            const uint32_t nr = static_cast<uint32_t>(std::popcount(unsigned(go_right)));
            const uint32_t nl = n - nr;
            _mm512_mask_storeu_epi32(out + right, __mmask16((1u << nr) - 1u),
                                     _mm512_maskz_compress_epi32(go_right, ids));
            _mm512_mask_storeu_epi32(out + left, __mmask16((1u << nl) - 1u),
                                     _mm512_maskz_compress_epi32(valid & ~go_right, ids));
            right += nr;
            left += nl;
        }
#endif
        // branch free: the side is random, a branch would mispredict half the time
        for (; i < end; ++i) {
            const uint32_t id = in[i];
            const uint32_t r = side[id] == stamp;
            out[left ^ ((left ^ right) & (0u - r))] = id;
            right += r;
            left += r ^ 1u;
        }
        assert(left == mid && right == end);
    }

    /// Emits the node for the lists' range [begin, end) and its subtree in depth-first order,
    /// without bounds (finish_nodes sets them). Bit k of `where` says which buffer holds the
    /// axis-k list.
    void build(uint32_t begin, uint32_t end, unsigned where, uint8_t depth) {
        const uint32_t node_index = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        const uint32_t count = end - begin;
        const uint32_t* cur[3] = {lists[where & 1u][0], lists[(where >> 1) & 1u][1],
                                  lists[(where >> 2) & 1u][2]};
        if (count <= max_leaf) {
            // leaf: its primitives in the order along x
            std::memcpy(prim_ids + begin, cur[0] + begin, count * sizeof(uint32_t));
            nodes[node_index].index = begin;
            nodes[node_index].count = static_cast<uint16_t>(count);
            return;
        }
        // split: object median along the longest axis of the centroid bounds
        float extent[3];
        for (int k = 0; k < 3; ++k)
            extent[k] = centroid2[k][cur[k][end - 1]] - centroid2[k][cur[k][begin]];
        // Aabb::longest_axis without branches (the axis is unpredictable):
        // (x >= y && x >= z) ? 0 : (y >= z ? 1 : 2)
        const unsigned x_wins = unsigned(extent[0] >= extent[1]) & unsigned(extent[0] >= extent[2]);
        const int axis = int((x_wins ^ 1u) * (2u - unsigned(extent[1] >= extent[2])));
        const uint32_t mid = begin + count / 2;
        nodes[node_index].axis = static_cast<uint16_t>(axis);
        const bool leaf_children = count <= 2 * max_leaf;
        if (leaf_children && axis == 0) {
            // both children are leaves and the x list is already split
            std::memcpy(prim_ids + begin, cur[0] + begin, count * sizeof(uint32_t));
        } else {
            const uint8_t stamp = static_cast<uint8_t>(depth + 1);
            for (uint32_t i = mid; i < end; ++i) side[cur[axis][i]] = stamp;
            if (leaf_children) {
                // only the leaves' x order is needed, straight into prim_ids
                partition(cur[0], prim_ids, begin, mid, end, stamp);
            } else {
                unsigned child_where = where;
                for (int j = 1; j <= 2; ++j) {
                    const int k = (axis + j) % 3;
                    const unsigned b = (where >> k) & 1u;
                    partition(cur[k], lists[b ^ 1u][k], begin, mid, end, stamp);
                    child_where ^= 1u << k;
                }
                build(begin, mid, child_where, stamp);  // the first child follows its parent
                nodes[node_index].index = static_cast<uint32_t>(nodes.size());
                build(mid, end, child_where, stamp);
                return;
            }
        }
        nodes.resize(nodes.size() + 2);
        BvhNode* leaves = nodes.data() + node_index + 1;
        leaves[0].index = begin;
        leaves[0].count = static_cast<uint16_t>(mid - begin);
        leaves[1].index = mid;
        leaves[1].count = static_cast<uint16_t>(end - mid);
        nodes[node_index].index = node_index + 2;
    }
};

/// Sets every node's bounds, bottom up (children follow their parent, so a backward sweep sees
/// them first): a leaf's from its primitives in leaf order, a parent's from its first then its
/// second child, as Aabb::grow would in a recursive build.
void finish_nodes(std::vector<BvhNode>& nodes, const uint32_t* prim_ids,
                  std::span<const Aabb> prim_bounds) {
    for (size_t i = nodes.size(); i-- > 0;) {
        BvhNode& node = nodes[i];
        Aabb box;
        if (node.is_leaf()) {
            for (uint32_t p = node.index; p < node.index + node.count; ++p)
                box.grow(prim_bounds[prim_ids[p]]);
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

}  // namespace

Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params) {
    Bvh bvh;
    if (prim_bounds.empty()) return bvh;
    const size_t n = prim_bounds.size();
    const uint32_t max_leaf = static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, 65535));
    bvh.prim_ids.resize(n);
    // Leaves hold at least max_leaf / 2 primitives (halving a range > max_leaf), so fewer than
    // 4n / max_leaf + 1 nodes are made.
    bvh.nodes.reserve(4 * n / max_leaf + 1);

    std::unique_ptr<float[]> centroid2[3];
    for (auto& c : centroid2) c = uninitialized<float>(n);
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) centroid2[k][i] = prim_bounds[i].lo[k] + prim_bounds[i].hi[k];
    std::unique_ptr<uint32_t[]> lists[2][3];
    {
        auto keys = uninitialized<uint32_t>(n);
        auto items = uninitialized<uint64_t>(n), scratch = uninitialized<uint64_t>(n);
        for (int k = 0; k < 3; ++k) {
            for (size_t i = 0; i < n; ++i) keys[i] = order_key(centroid2[k][i]);
            lists[0][k] = uninitialized<uint32_t>(n);
            lists[1][k] = uninitialized<uint32_t>(n);
            if (n >= (size_t(1) << 16))
                sort_ids_by_key<16>(keys.get(), n, lists[0][k].get(), items, scratch);
            else
                sort_ids_by_key<8>(keys.get(), n, lists[0][k].get(), items, scratch);
        }
    }
    auto side = std::make_unique<uint8_t[]>(n + 3);  // stamp 0: no node yet
    Builder b{{centroid2[0].get(), centroid2[1].get(), centroid2[2].get()},
              side.get(),
              {},
              bvh.prim_ids.data(),
              bvh.nodes,
              max_leaf};
    for (int k = 0; k < 3; ++k) {
        b.lists[0][k] = lists[0][k].get();
        b.lists[1][k] = lists[1][k].get();
    }
    b.build(0, static_cast<uint32_t>(n), 0u, 0);
    finish_nodes(bvh.nodes, bvh.prim_ids.data(), prim_bounds);
    return bvh;
}

}  // namespace raylane
