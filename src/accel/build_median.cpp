// accel: the median-split BVH build (the report's build), flattened depth-first as it goes, for
// boxes (build_bvh_median) and for a mesh's triangles (build_mesh_accel). The plain
// std::nth_element form of the same tree is tests/accel/median_reference.h.
#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <chrono>
#include <cstring>
#include <memory>
#include <new>
#include <optional>

#if defined(__AVX512F__)
#include <immintrin.h>
// GCC 12's AVX-512 headers start many intrinsics from _mm512_undefined_epi32(), which its
// -Wmaybe-uninitialized then reports inside the header
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
#endif

#include "accel/bvh.h"

namespace raylane {
namespace {

/// One block for all of a build's temporaries, carved in order by take(). Fresh pages are most
/// of what a first build pays for on this VM (docs/performance.md, "Loading and building"), so
/// a block of 2 MiB or more is huge pages (map_pages: one fault per 2 MiB, and few TLB misses
/// in the radix sort's scatter), one of 1–2 MiB an anonymous mapping whose 4 KiB pages the
/// kernel faults in with one call (MAP_POPULATE), a smaller one the heap's. Given back when the
/// build ends (unmap_pages keeps the newest huge-page blocks for the next build).
class TempBlock {
  public:
    explicit TempBlock(size_t bytes) : size_(bytes) {
        if (bytes >= large_block_bytes) {
            base_ = map_pages(bytes);
        } else if (bytes >= populated_from && !sanitized) {
            void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE,
                           MAP_PRIVATE | MAP_ANONYMOUS | MAP_POPULATE, -1, 0);
            if (p == MAP_FAILED) throw std::bad_alloc();
            base_ = static_cast<std::byte*>(p);
        } else {
            base_ = static_cast<std::byte*>(::operator new(bytes, std::align_val_t(64)));
        }
    }
    ~TempBlock() {
        if (size_ >= large_block_bytes)
            unmap_pages(base_, size_);
        else if (size_ >= populated_from && !sanitized)
            munmap(base_, size_);
        else
            ::operator delete(base_, std::align_val_t(64));
    }
    TempBlock(const TempBlock&) = delete;
    TempBlock& operator=(const TempBlock&) = delete;

    /// The next n elements of type T, 64-byte aligned (the caller sized the block for them).
    template <class T>
    T* take(size_t n) {
        T* p = reinterpret_cast<T*>(base_ + used_);
        used_ += (n * sizeof(T) + 63) & ~size_t(63);
        assert(used_ <= size_);
        return p;
    }
    /// Bytes take() uses for n elements of T.
    template <class T>
    static size_t bytes_for(size_t n) {
        return (n * sizeof(T) + 63) & ~size_t(63);
    }

  private:
    static constexpr size_t populated_from = size_t(1) << 20;
#if defined(RAYLANE_ADDRESS_SANITIZER)
    static constexpr bool sanitized = true;  // the sanitizer's allocator: red zones (pages.h)
#else
    static constexpr bool sanitized = false;
#endif
    std::byte* base_ = nullptr;
    size_t size_ = 0, used_ = 0;
};

/// Starts the lifetime of n objects of the trivial type T at p (no code) and returns them.
template <class T>
T* begin_array(std::byte* p, size_t n) {
    T* a = reinterpret_cast<T*>(p);
    std::uninitialized_default_construct_n(a, n);
    return a;
}

/// A float's bits mapped to an unsigned key with the same order (negatives flipped; -0 sorts
/// before +0).
uint32_t order_key(float f) {
    const uint32_t u = std::bit_cast<uint32_t>(f);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

#if defined(__AVX512F__)
/// order_key of sixteen floats.
__m512i order_keys(__m512 f) {
    const __m512i bits = _mm512_castps_si512(f);
    const __mmask16 negative = _mm512_cmplt_epi32_mask(bits, _mm512_setzero_si512());
    return _mm512_xor_si512(bits, _mm512_mask_mov_epi32(_mm512_set1_epi32(int(0x80000000u)),
                                                        negative, _mm512_set1_epi32(-1)));
}
#endif

/// Sorts the ids 0 .. n-1 by order_key(values[id]), stably (equal keys in id order), into
/// `out`: LSD radix sort of (key << 32 | id) items in passes of `digit_bits` bits, skipping the
/// digits every key shares. Wide digits make fewer passes; narrow ones keep the histograms
/// small for small n. The first pass that moves anything makes the items from the values as it
/// scatters them (no array of items is written and read back first), and the last writes the
/// ids alone. `items` and `scratch` hold n items each.
template <int digit_bits>
void sort_ids_by_key(const float* values, size_t n, uint32_t* out, uint64_t* items,
                     uint64_t* scratch) {
    constexpr int passes = (32 + digit_bits - 1) / digit_bits;
    constexpr uint32_t digit_mask = (1u << digit_bits) - 1u;
    auto histogram = std::make_unique<uint32_t[]>(size_t(passes) << digit_bits);
    for (size_t i = 0; i < n; ++i) {
        const uint32_t key = order_key(values[i]);
        for (int p = 0; p < passes; ++p)
            ++histogram[(size_t(p) << digit_bits) + ((key >> (digit_bits * p)) & digit_mask)];
    }
    // the passes that move anything: those where not every key has key0's digit
    const uint32_t key0 = order_key(values[0]);
    bool moves[passes] = {};
    int first = -1, last = -1;
    for (int p = 0; p < passes; ++p) {
        const uint32_t* count = histogram.get() + (size_t(p) << digit_bits);
        moves[p] = count[(key0 >> (digit_bits * p)) & digit_mask] != n;
        if (moves[p] && first < 0) first = p;
        if (moves[p]) last = p;
    }
    if (last < 0) {  // all keys equal: id order
        for (size_t i = 0; i < n; ++i) out[i] = static_cast<uint32_t>(i);
        return;
    }
    for (int p = first; p <= last; ++p) {
        if (!moves[p]) continue;
        uint32_t* offset = histogram.get() + (size_t(p) << digit_bits);
        uint32_t sum = 0;
        for (uint32_t d = 0; d <= digit_mask; ++d) {
            const uint32_t c = offset[d];
            offset[d] = sum;
            sum += c;
        }
        const uint32_t shift = digit_bits * static_cast<uint32_t>(p);
        if (p == first) {
            // from the values: keys recomputed (cheaper than an array of items written and read)
            for (size_t i = 0; i < n; ++i) {
                const uint32_t key = order_key(values[i]);
                const uint32_t d = (key >> shift) & digit_mask;
                if (p == last)
                    out[offset[d]++] = static_cast<uint32_t>(i);
                else
                    scratch[offset[d]++] = uint64_t(key) << 32 | i;
            }
        } else if (p == last) {
            for (size_t i = 0; i < n; ++i)
                out[offset[(items[i] >> (32 + shift)) & digit_mask]++] =
                    static_cast<uint32_t>(items[i]);
        } else {
            for (size_t i = 0; i < n; ++i)
                scratch[offset[(items[i] >> (32 + shift)) & digit_mask]++] = items[i];
        }
        std::swap(items, scratch);
    }
}

/// Aabb::longest_axis of the extents without branches (the axis is unpredictable):
/// (x >= y && x >= z) ? 0 : (y >= z ? 1 : 2).
int longest_axis(const float extent[3]) {
    const unsigned x_wins = unsigned(extent[0] >= extent[1]) & unsigned(extent[0] >= extent[2]);
    return int((x_wins ^ 1u) * (2u - unsigned(extent[1] >= extent[2])));
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
    uint32_t* prim_ids;         ///< the subtree's part of the tree's prim_ids
    std::vector<BvhNode, OverwriteAllocator<BvhNode>>& nodes;
    uint32_t max_leaf;
    uint32_t leaf_base;  ///< the subtree's first position in the tree's prim_ids

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
        nodes.push_back(BvhNode{});  // zeroed: count 0 until it is a leaf
        const uint32_t count = end - begin;
        const uint32_t* cur[3] = {lists[where & 1u][0], lists[(where >> 1) & 1u][1],
                                  lists[(where >> 2) & 1u][2]};
        if (count <= max_leaf) {
            // leaf: its primitives in the order along x
            std::memcpy(prim_ids + begin, cur[0] + begin, count * sizeof(uint32_t));
            nodes[node_index].index = leaf_base + begin;
            nodes[node_index].count = static_cast<uint16_t>(count);
            return;
        }
        // split: object median along the longest axis of the centroid bounds
        float extent[3];
        for (int k = 0; k < 3; ++k)
            extent[k] = centroid2[k][cur[k][end - 1]] - centroid2[k][cur[k][begin]];
        const int axis = longest_axis(extent);
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
        nodes.resize(nodes.size() + 2, BvhNode{});
        BvhNode* leaves = nodes.data() + node_index + 1;
        leaves[0].index = leaf_base + begin;
        leaves[0].count = static_cast<uint16_t>(mid - begin);
        leaves[1].index = leaf_base + mid;
        leaves[1].count = static_cast<uint16_t>(end - mid);
        nodes[node_index].index = node_index + 2;
    }
};

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

/// Wall time between laps, for BuildPhases.
class PhaseClock {
  public:
    /// Milliseconds since the clock was made or last lapped.
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        return ms;
    }

  private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// The float whose order_key is `key`.
float key_value(uint32_t key) {
    return std::bit_cast<float>((key & 0x80000000u) ? (key & 0x7fffffffu) : ~key);
}

/// Where a build puts the tree (nodes appended in depth-first order, primitive ids by leaf
/// position) and, when asked for, its phases' times.
struct TreeOut {
    std::vector<BvhNode, OverwriteAllocator<BvhNode>>& nodes;
    uint32_t* prim_ids;
    uint32_t max_leaf;
    BuildPhases* phases;  ///< null, or given with clock
    PhaseClock* clock;

    /// Adds the time since the last lap to the phase.
    void lap(double BuildPhases::*phase) const {
        if (phases) phases->*phase += clock->lap();
    }
};

/// A subtree build's temporaries: both buffers of the three axis lists, and the radix sort's
/// items and scratch (the items' memory holds the side stamps after the sorts).
struct SubtreeMemory {
    uint32_t* lists[2][3];
    uint64_t* items;
    uint64_t* scratch;
};

/// The median-split subtree of m >= 1 primitives whose doubled centroids are c2[k][0 .. m-1]:
/// three radix sorts, then Builder. Its nodes are appended to out.nodes and its primitives
/// written to out.prim_ids[base .. base + m): ids[i] is the tree's id of primitive i (ids in
/// increasing order, so that ties break as in the whole tree's order), or i itself when `ids`
/// is null.
void build_subtree(const float* const* c2, uint32_t m, uint32_t base, const uint32_t* ids,
                   const SubtreeMemory& mem, const TreeOut& out) {
    for (int k = 0; k < 3; ++k) {
        if (m >= (1u << 16))
            sort_ids_by_key<16>(c2[k], m, mem.lists[0][k], mem.items, mem.scratch);
        else
            sort_ids_by_key<8>(c2[k], m, mem.lists[0][k], mem.items, mem.scratch);
    }
    out.lap(&BuildPhases::sorts);
    // the sort's items are done with: their memory holds the side stamps
    uint8_t* side = reinterpret_cast<uint8_t*>(mem.items);  // three bytes of padding for gathers
    std::memset(side, 0, size_t(m) + 3);                    // stamp 0: no node yet
    Builder b{{c2[0], c2[1], c2[2]}, side, {}, out.prim_ids + base, out.nodes, out.max_leaf, base};
    for (int k = 0; k < 3; ++k) {
        b.lists[0][k] = mem.lists[0][k];
        b.lists[1][k] = mem.lists[1][k];
    }
    b.build(0, m, 0u, 0);
    if (ids)
        for (uint32_t i = base; i < base + m; ++i) out.prim_ids[i] = ids[out.prim_ids[i]];
    out.lap(&BuildPhases::splits);
}

/// The primitives of the nodes too large for a subtree build, in one of two buffers: the tree's
/// ids, increasing within a node, and their doubled centroids. A node's primitives sit at its
/// range of prim_ids.
struct TopArrays {
    uint32_t* ids;
    float* c2[3];
};

/// The smallest and largest order_key of a node's centroids on each axis.
struct KeyBounds {
    uint32_t lo[3] = {~0u, ~0u, ~0u};
    uint32_t hi[3] = {0, 0, 0};
};

#if defined(__AVX512F__)
/// Grows the bounds on axis k by sixteen lanes of smallest and largest keys.
void grow(KeyBounds& b, int k, __m512i lo, __m512i hi) {
    // (not _mm512_reduce_min_epu32: GCC 12's header warns of an uninitialised variable)
    alignas(64) uint32_t los[16], his[16];
    _mm512_store_si512(los, lo);
    _mm512_store_si512(his, hi);
    for (int j = 0; j < 16; ++j) {
        b.lo[k] = std::min(b.lo[k], los[j]);
        b.hi[k] = std::max(b.hi[k], his[j]);
    }
}
#endif

KeyBounds key_bounds(const TopArrays& a, uint32_t begin, uint32_t end) {
    KeyBounds b;
    for (int k = 0; k < 3; ++k) {
        const float* c = a.c2[k];
        uint32_t i = begin;
#if defined(__AVX512F__)
        __m512i lo = _mm512_set1_epi32(-1), hi = _mm512_setzero_si512();
        for (; i + 16 <= end; i += 16) {
            const __m512i key = order_keys(_mm512_loadu_ps(c + i));
            lo = _mm512_min_epu32(lo, key);
            hi = _mm512_max_epu32(hi, key);
        }
        grow(b, k, lo, hi);
#endif
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
    return longest_axis(extent);
}

/// Copies primitive i of a top buffer to position `at` of another.
void copy_primitive(const TopArrays& from, uint32_t i, const TopArrays& to, uint32_t at) {
    to.ids[at] = from.ids ? from.ids[i] : i;
    for (int k = 0; k < 3; ++k) to.c2[k][at] = from.c2[k][i];
}

#if defined(__AVX512F__)
/// Moves the primitives i .. i + 15 of `from` that `valid` holds to `to`: those of each group
/// go[g] compressed together and stored from *at[g] with a mask (no write past the group's
/// end), which then advances.
void store_compressed(const TopArrays& from, const TopArrays& to, uint32_t i, __mmask16 valid,
                      const __mmask16* go, uint32_t* const* at, int groups) {
    const __m512i lane = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
    __m512i v[4];
    v[0] = from.ids ? _mm512_maskz_loadu_epi32(valid, from.ids + i)
                    : _mm512_add_epi32(_mm512_set1_epi32(int(i)), lane);
    for (int k = 0; k < 3; ++k)
        v[1 + k] = _mm512_castps_si512(_mm512_maskz_loadu_ps(valid, from.c2[k] + i));
    uint32_t* dest[4] = {to.ids, reinterpret_cast<uint32_t*>(to.c2[0]),
                         reinterpret_cast<uint32_t*>(to.c2[1]),
                         reinterpret_cast<uint32_t*>(to.c2[2])};
    for (int g = 0; g < groups; ++g) {
        if (go[g] == valid) {
            // the whole chunk in one group (the mesh's order is near spatial order)
            for (int a = 0; a < 4; ++a) _mm512_mask_storeu_epi32(dest[a] + *at[g], valid, v[a]);
            *at[g] += uint32_t(std::popcount(unsigned(valid)));
            return;
        }
        if (!go[g]) continue;
        const uint32_t n = uint32_t(std::popcount(unsigned(go[g])));
        const __mmask16 store = __mmask16((1u << n) - 1u);
        for (int a = 0; a < 4; ++a)
            _mm512_mask_storeu_epi32(dest[a] + *at[g], store,
                                     _mm512_maskz_compress_epi32(go[g], v[a]));
        *at[g] += n;
    }
}
#endif

/// The split key and tie count of a top node: its first child gets the `left` smallest keys of
/// its primitives, of equal keys the first ones in order, that is the keys below `key` and the
/// first `ties` equal to it.
struct SplitKey {
    uint32_t key, ties;
};

/// Which child of a split each primitive of a node goes to, swept in the node's order (the
/// equal keys' first `ties` go first).
struct SplitSweep {
    SplitKey s;

    /// 1 when the primitive of this key goes to the first child.
    uint32_t first(uint32_t key) {
        const uint32_t equal = key == s.key;
        const uint32_t go = uint32_t(key < s.key) | (equal & uint32_t(s.ties != 0));
        s.ties -= equal & go;
        return go;
    }
#if defined(__AVX512F__)
    /// The lanes of `among`, the next primitives in order, that go to the first child.
    __mmask16 first(__m512i key, __mmask16 among) {
        const __m512i split = _mm512_set1_epi32(int(s.key));
        const __mmask16 below = _mm512_mask_cmplt_epu32_mask(among, key, split);
        uint32_t taken = _mm512_mask_cmpeq_epi32_mask(among, key, split);
        if (uint32_t(std::popcount(taken)) > s.ties)  // the first s.ties of the equal keys
            taken = _pdep_u32((1u << s.ties) - 1u, taken);
        s.ties -= uint32_t(std::popcount(taken));
        return __mmask16(below | taken);
    }
#endif
};

/// The k-th smallest (from 0) of m keys and how many of the keys are smaller, for keys that are
/// all within [lo, hi]: a radix select, 11 bits of the keys' offset from lo at a time from the
/// top of the range's width, each round counting the keys within the bucket the last one chose.
struct Selected {
    uint32_t key, below;
};

Selected select_key(const uint32_t* keys, uint32_t m, uint32_t k, uint32_t lo, uint32_t hi) {
    constexpr int digit_bits = 11;
    uint32_t below = 0;
    for (;;) {
        const int shift = std::max(int(std::bit_width(hi - lo)) - digit_bits, 0);
        uint32_t count[1u << digit_bits] = {};
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
/// sample of them: all keys for a node of fewer than 65,536, or when the sample holds no more
/// than twice the margin.
struct Bracket {
    uint32_t lo = 0, hi = ~0u;
};

constexpr uint32_t bracket_samples = 4096;

Bracket bracket_of_sample(const uint32_t* sample, uint32_t samples, uint32_t left, uint32_t count) {
    constexpr uint32_t margin = 128;
    if (count < 16 * bracket_samples || samples <= 2 * margin) return {};
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
#if defined(__AVX512F__)
    /// The lanes `among` of sixteen keys.
    bool add(__m512i key, __mmask16 among) {
        const __m512i lo = _mm512_set1_epi32(int(b.lo)), hi = _mm512_set1_epi32(int(b.hi));
        below += uint32_t(std::popcount(unsigned(_mm512_mask_cmplt_epu32_mask(among, key, lo))));
        const __mmask16 in =
            _mm512_mask_cmple_epu32_mask(_mm512_mask_cmpge_epu32_mask(among, key, lo), key, hi);
        const uint32_t t = uint32_t(std::popcount(unsigned(in)));
        if (m + t > capacity) return false;
        _mm512_mask_storeu_epi32(keys + m, __mmask16((1u << t) - 1u),
                                 _mm512_maskz_compress_epi32(in, key));
        m += t;
        return true;
    }
#endif
    /// The split key of the `left` smallest keys of the node, as median_of_bracket.
    std::optional<SplitKey> median(uint32_t left) const {
        return median_of_bracket(keys, m, below, left, b.lo, b.hi);
    }
};

/// select_split's fallback: a radix select, the 16 high bits' histogram, then the low bits'
/// of the median's bucket.
SplitKey radix_select(const float* c, uint32_t begin, uint32_t end, uint32_t left,
                      uint32_t* histogram) {
    std::fill_n(histogram, 1u << 16, 0u);
    for (uint32_t i = begin; i < end; ++i) ++histogram[order_key(c[i]) >> 16];
    uint32_t below = 0, high = 0;
    while (below + histogram[high] <= left) below += histogram[high++];
    std::fill_n(histogram, 1u << 16, 0u);
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t key = order_key(c[i]);
        if ((key >> 16) == high) ++histogram[key & 0xffffu];
    }
    uint32_t low = 0;
    while (below + histogram[low] <= left) below += histogram[low++];
    return {high << 16 | low, left - below};
}

/// The split of the node c[begin, end) that gives its first child `left` primitives. The keys
/// between two keys of an even sample that bracket the median (all keys, in a node of fewer
/// than 65,536) are gathered into `keys` and the median found among them; when they are more
/// than `capacity` or the median is outside, radix_select.
SplitKey select_split(const float* c, uint32_t begin, uint32_t end, uint32_t left,
                      uint32_t* histogram, uint32_t* keys, uint32_t capacity,
                      MedianSplitPaths& paths) {
    const uint32_t count = end - begin;
    uint32_t* sample = histogram;
    const uint32_t samples = count >= 16 * bracket_samples ? bracket_samples : 0;
    for (uint32_t j = 0; j < samples; ++j)
        sample[j] = order_key(c[begin + j * (count / bracket_samples)]);
    BracketGather g{bracket_of_sample(sample, samples, left, count), keys, capacity};
    bool fits = true;
    uint32_t i = begin;
#if defined(__AVX512F__)
    for (; fits && i + 16 <= end; i += 16) fits = g.add(order_keys(_mm512_loadu_ps(c + i)), 0xffff);
#endif
    for (; fits && i < end; ++i) fits = g.add(order_key(c[i]));
    if (fits)
        if (const auto s = g.median(left)) {
            ++paths.bracketed;
            return *s;
        }
    ++paths.radix;
    return radix_select(c, begin, end, left, histogram);
}

/// Stable partition of a top node's ids and centroids, cur[begin, end), into other: the
/// primitives that `split` on `axis` sends to the first child from begin, the rest from mid.
void partition_top(const TopArrays& cur, const TopArrays& other, uint32_t begin, uint32_t mid,
                   uint32_t end, int axis, SplitKey split) {
    const float* c = cur.c2[axis];
    SplitSweep sweep{split};
    uint32_t l = begin, r = mid, i = begin;
#if defined(__AVX512F__)
    // sixteen at a time: each side's ids and centroids compressed together and stored with a
    // mask (no write past a side's end)
    for (; i < end; i += 16) {
        const uint32_t n = std::min(end - i, 16u);
        const __mmask16 valid = __mmask16((1u << n) - 1u);
        const __mmask16 go_left =
            sweep.first(order_keys(_mm512_maskz_loadu_ps(valid, c + i)), valid);
        const __mmask16 go[2] = {go_left, __mmask16(valid & ~go_left)};
        uint32_t* at[2] = {&l, &r};
        store_compressed(cur, other, i, valid, go, at, 2);
    }
#endif
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
    std::array<KeyBounds, 2> b;
    SplitSweep sweep{split};
    uint32_t i = begin;
#if defined(__AVX512F__)
    __m512i lo[2][3], hi[2][3];
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 3; ++k) {
            lo[side][k] = _mm512_set1_epi32(-1);
            hi[side][k] = _mm512_setzero_si512();
        }
    for (; i + 16 <= end; i += 16) {
        __m512i key[3];
        for (int k = 0; k < 3; ++k) key[k] = order_keys(_mm512_loadu_ps(cur.c2[k] + i));
        const __mmask16 go_left = sweep.first(key[axis], 0xffff);
        const __mmask16 go[2] = {go_left, __mmask16(~go_left)};
        for (int side = 0; side < 2; ++side)
            for (int k = 0; k < 3; ++k) {
                lo[side][k] = _mm512_mask_min_epu32(lo[side][k], go[side], lo[side][k], key[k]);
                hi[side][k] = _mm512_mask_max_epu32(hi[side][k], go[side], hi[side][k], key[k]);
            }
    }
    for (int side = 0; side < 2; ++side)
        for (int k = 0; k < 3; ++k) grow(b[side], k, lo[side][k], hi[side][k]);
#endif
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

/// The splits of both children of a top node split by `split` on `axis`, each on its own axis
/// child_axis[side], as select_split would find them once the node is partitioned, but from the
/// node's unpartitioned primitives: an even sample of the node's keys, each on its side by
/// key, brackets each child's median, and one sweep gathers both children's keys within their
/// brackets into keys[0 .. capacity) and keys[capacity .. 2 capacity). Nothing when a bracket
/// holds more than `capacity` keys or misses its child's median.
std::optional<std::array<SplitKey, 2>> select_children(const TopArrays& cur, uint32_t begin,
                                                       uint32_t end, int axis, SplitKey split,
                                                       const int child_axis[2], uint32_t* sample,
                                                       uint32_t* keys, uint32_t capacity) {
    const uint32_t count = end - begin;
    const uint32_t size[2] = {count / 2, count - count / 2};
    const float* c = cur.c2[axis];
    const float* child_c[2] = {cur.c2[child_axis[0]], cur.c2[child_axis[1]]};
    // the sample: 2 bracket_samples primitives of the node, the keys equal to the split skipped
    // (their side depends on their order)
    uint32_t* taken[2] = {sample, sample + 2 * bracket_samples};
    uint32_t samples[2] = {0, 0};
    if (count >= 32 * bracket_samples) {
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
#if defined(__AVX512F__)
    for (; fits && i + 16 <= end; i += 16) {
        const __m512i key = order_keys(_mm512_loadu_ps(c + i));
        const __mmask16 go_left = sweep.first(key, 0xffff);
        __m512i child_key[2];
        for (int side = 0; side < 2; ++side)
            child_key[side] =
                child_axis[side] == axis ? key : order_keys(_mm512_loadu_ps(child_c[side] + i));
        fits = g[0].add(child_key[0], go_left) && g[1].add(child_key[1], __mmask16(~go_left));
    }
#endif
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

/// Stable partition of a top node's primitives, cur[begin, end), into the ranges of its four
/// grandchildren in other: split by `split` on `axis`, then each child by child[side] on
/// child_axis[side].
void partition_four(const TopArrays& cur, const TopArrays& other, uint32_t begin, uint32_t end,
                    int axis, SplitKey split, const int child_axis[2],
                    const std::array<SplitKey, 2>& child) {
    const uint32_t count = end - begin, mid = begin + count / 2;
    uint32_t at[4] = {begin, begin + count / 2 / 2, mid, mid + (count - count / 2) / 2};
    [[maybe_unused]] const uint32_t ends[4] = {at[1], at[2], at[3], end};
    const float* c = cur.c2[axis];
    const float* child_c[2] = {cur.c2[child_axis[0]], cur.c2[child_axis[1]]};
    SplitSweep sweep{split}, child_sweep[2] = {{child[0]}, {child[1]}};
    uint32_t i = begin;
#if defined(__AVX512F__)
    for (; i < end; i += 16) {
        const uint32_t n = std::min(end - i, 16u);
        const __mmask16 valid = __mmask16((1u << n) - 1u);
        const __m512i key = order_keys(_mm512_maskz_loadu_ps(valid, c + i));
        const __mmask16 first = sweep.first(key, valid);
        __mmask16 go[4];
        for (int s = 0; s < 2; ++s) {
            const __mmask16 among = s == 0 ? first : __mmask16(valid & ~first);
            const __m512i child_key =
                child_axis[s] == axis ? key
                                      : order_keys(_mm512_maskz_loadu_ps(valid, child_c[s] + i));
            go[2 * s] = child_sweep[s].first(child_key, among);
            go[2 * s + 1] = __mmask16(among & ~go[2 * s]);
        }
        uint32_t* const to[4] = {&at[0], &at[1], &at[2], &at[3]};
        store_compressed(cur, other, i, valid, go, to, 4);
    }
#endif
    for (; i < end; ++i) {
        const uint32_t s = sweep.first(order_key(c[i])) ^ 1u;
        const uint32_t q = 2 * s + (child_sweep[s].first(order_key(child_c[s][i])) ^ 1u);
        copy_primitive(cur, i, other, at[q]++);
    }
    for (int q = 0; q < 4; ++q) assert(at[q] == ends[q]);
}

/// The nodes of more than `subtree_limit` primitives, split without sorted lists: the split key
/// by select_split on the longest axis of the key bounds, and partition_top into the other
/// buffer; or, when both children are above the limit too, their splits found first
/// (child_key_bounds, select_children) and the four grandchildren made by partition_four, one
/// pass over the node's primitives where two levels of partition_top make two. Each node of at
/// most subtree_limit primitives becomes a subtree build on its own compact arrays, which stay
/// in the cache where the whole tree's lists would not (docs/performance.md, "How the build
/// works"). The same tree as one subtree build over all the primitives.
struct TopSplitter {
    const TreeOut& out;
    const SubtreeMemory& mem;
    uint32_t subtree_limit;
    uint32_t* keys;       ///< 2 capacity keys gathered by the selects
    uint32_t capacity;    ///< >= 65,536: all the keys of a node of fewer
    uint32_t* histogram;  ///< 65,536 counts
    uint32_t* root_ids;   ///< the ids of the root's buffer, whose root has null ids (positions)
    MedianSplitPaths& paths;

    /// The subtree of the node cur[begin, end).
    void build(uint32_t begin, uint32_t end, const TopArrays& cur, const TopArrays& other) const {
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
            if (const auto child = select_children(cur, begin, end, axis, split, child_axis,
                                                   histogram, keys, capacity)) {
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
};

/// The median-split tree over n >= 1 primitives, without node bounds (finish_nodes sets them):
/// nodes and prim_ids. fill(c2) writes twice every primitive's centroid (its box's lo + hi) to
/// c2[0..2][0 .. n-1], one array per axis.
///
/// Up to params.median_subtree primitives, one subtree build. Its memory: nine arrays of n
/// 4-byte values (the centroids and both buffers of the three axis lists) and a block of 16
/// bytes per primitive for the radix sort's items, reused for the side stamps after the sorts.
/// Above, TopSplitter: two buffers of n ids and centroids (eight arrays), the subtree builds'
/// lists and items for median_subtree primitives, the selects' keys (2 max(median_subtree,
/// 65,536)) and a histogram of 65,536 counts. The arrays of n are taken from `lent`
/// when the caller lends 36n bytes it will overwrite afterwards (build_mesh_accel lends the
/// triangle-vertex array it fills next), else from the block: fresh pages cost about 1.4 us each
/// on this VM. `phases`, when given, gets the times of the centroids, the sorts and the splits,
/// measured from `clock`. `paths`, when given, gets the ways the top nodes were split.
template <class FillCentroids>
Bvh median_tree(size_t n, const BuildParams& params, FillCentroids&& fill,
                std::byte* lent = nullptr, BuildPhases* phases = nullptr,
                PhaseClock* clock = nullptr, MedianSplitPaths* paths = nullptr) {
    Bvh bvh;
    const uint32_t max_leaf = static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, 65535));
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
        // fewer than 65,536
        const size_t capacity = std::max<size_t>(limit, 1u << 16);
        MedianSplitPaths ignored;
        TempBlock block((lent ? 0 : 8 * TempBlock::bytes_for<uint32_t>(n)) +
                        6 * TempBlock::bytes_for<uint32_t>(limit) +
                        TempBlock::bytes_for<uint32_t>(2 * capacity) +
                        TempBlock::bytes_for<uint64_t>(limit) +
                        TempBlock::bytes_for<uint64_t>(limit) +
                        TempBlock::bytes_for<uint32_t>(size_t(1) << 16));
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
                              block.take<uint32_t>(size_t(1) << 16),
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

Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params,
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

/// The mesh's form of build_bvh_median with no array of triangle boxes: the centroids come
/// straight from the vertices (the box Aabb::grow makes of a triangle's three vertices), and
/// the leaf boxes from the vertices in leaf order, read in sequence, instead of the boxes
/// gathered by id. The same min and max of the same numbers in the same order, so the same
/// tree bit for bit (tests/accel/build_median_golden_test.cpp).
MeshAccel build_mesh_accel(const Mesh& mesh, const BuildParams& params) {
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
    // last-level cache (docs/performance.md, "How the build works": faster at 400k and 1.6M).
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
    accel.phases.collapse = clock.lap();
    return accel;
}

}  // namespace raylane
