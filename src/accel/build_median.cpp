// accel: the median-split BVH build (the report's build), flattened depth-first as it goes, for
// boxes (build_bvh_median) and for a mesh's triangles (build_mesh_accel). The plain
// std::nth_element form of the same tree is tests/accel/median_reference.h.
#include <sys/mman.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <chrono>
#include <cstring>
#include <memory>
#include <new>

#if defined(__AVX512F__)
#include <immintrin.h>
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
    std::vector<BvhNode, OverwriteAllocator<BvhNode>>& nodes;
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
        nodes.push_back(BvhNode{});  // zeroed: count 0 until it is a leaf
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
        nodes.resize(nodes.size() + 2, BvhNode{});
        BvhNode* leaves = nodes.data() + node_index + 1;
        leaves[0].index = begin;
        leaves[0].count = static_cast<uint16_t>(mid - begin);
        leaves[1].index = mid;
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

/// The median-split tree over n >= 1 primitives, without node bounds (finish_nodes sets them):
/// nodes and prim_ids. fill(c2) writes twice every primitive's centroid (its box's lo + hi) to
/// c2[0..2][0 .. n-1], one array per axis.
///
/// Memory: nine arrays of n 4-byte values (the centroids and both buffers of the three axis
/// lists) and a block of 16 bytes per primitive for the radix sort's items, reused for the side
/// stamps after the sorts. The nine arrays are taken from `lent` when the caller lends 36n bytes
/// it will overwrite afterwards (build_mesh_accel lends the triangle-vertex array it fills
/// next), else from the block: fresh pages cost about 1.4 us each on this VM. `phases`, when
/// given, gets the times of the centroids, the sorts and the splits, measured from `clock`.
template <class FillCentroids>
Bvh median_tree(size_t n, const BuildParams& params, FillCentroids&& fill,
                std::byte* lent = nullptr, BuildPhases* phases = nullptr,
                PhaseClock* clock = nullptr) {
    Bvh bvh;
    const uint32_t max_leaf = static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, 65535));
    bvh.prim_ids.resize(n);
    // Leaves hold at least max_leaf / 2 primitives (halving a range > max_leaf), so fewer than
    // 4n / max_leaf + 1 nodes are made.
    bvh.nodes.reserve(4 * n / max_leaf + 1);

    assert(!phases == !clock);
    {  // the temporaries' scope: freeing them is part of the splits' time
        TempBlock block((lent ? 0 : 9 * TempBlock::bytes_for<uint32_t>(n)) +
                        2 * TempBlock::bytes_for<uint64_t>(n));
        // the nine arrays in the lent memory or the block
        std::byte* nine = lent ? lent : reinterpret_cast<std::byte*>(block.take<uint32_t>(9 * n));
        float* centroid2[3];
        uint32_t* lists[2][3];
        for (size_t k = 0; k < 3; ++k) {
            centroid2[k] = begin_array<float>(nine + 4 * n * k, n);
            lists[0][k] = begin_array<uint32_t>(nine + 4 * n * (3 + k), n);
            lists[1][k] = begin_array<uint32_t>(nine + 4 * n * (6 + k), n);
        }
        fill(centroid2);
        if (phases) phases->centroids = clock->lap();
        uint64_t* items = block.take<uint64_t>(n);
        uint64_t* scratch = block.take<uint64_t>(n);
        for (int k = 0; k < 3; ++k) {
            if (n >= (size_t(1) << 16))
                sort_ids_by_key<16>(centroid2[k], n, lists[0][k], items, scratch);
            else
                sort_ids_by_key<8>(centroid2[k], n, lists[0][k], items, scratch);
        }
        if (phases) phases->sorts = clock->lap();
        // the sort's items are done with: their memory holds the side stamps
        uint8_t* side = reinterpret_cast<uint8_t*>(items);  // three bytes of padding for gathers
        std::memset(side, 0, n + 3);                        // stamp 0: no node yet
        Builder b{{centroid2[0], centroid2[1], centroid2[2]},
                  side,
                  {},
                  bvh.prim_ids.data(),
                  bvh.nodes,
                  max_leaf};
        for (int k = 0; k < 3; ++k) {
            b.lists[0][k] = lists[0][k];
            b.lists[1][k] = lists[1][k];
        }
        b.build(0, static_cast<uint32_t>(n), 0u, 0);
    }
    if (phases) phases->splits = clock->lap();
    return bvh;
}

}  // namespace

Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params) {
    if (prim_bounds.empty()) return {};
    const size_t n = prim_bounds.size();
    Bvh bvh = median_tree(n, params, [&](float* const* c2) {
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) c2[k][i] = prim_bounds[i].lo[k] + prim_bounds[i].hi[k];
    });
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
    // asked for ahead (the triangle's indices 64 triangles ahead, its vertices 32 ahead, whose
    // indices are then in cache): far enough to cover a miss to memory, not only to the
    // last-level cache (docs/performance.md, "How the build works": faster at 400k and 1.6M).
    const uint32_t* ids = accel.bvh.prim_ids.data();
    constexpr size_t tri_ahead = 64, vert_ahead = 32;
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
    return accel;
}

}  // namespace raylane
