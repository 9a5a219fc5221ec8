// accel: the median-split build's subtree builder (build_subtree.h): the primitive ids sorted once
// per axis, then each node split at the middle of its longest axis's list.
#include "accel/build_subtree.h"

#include <algorithm>
#include <cassert>
#include <cstring>

#include "accel/order_key.h"
#include "accel/radix_sort.h"
#include "simd/array_packets.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {
namespace {

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
    uint8_t* side;              ///< by id, gather_u8_padding bytes of padding for gather_u8
    uint32_t* lists[2][3];      ///< lists[b][k]: buffer b of the axis-k list
    uint32_t* prim_ids;         ///< the subtree's part of the tree's prim_ids
    std::vector<BvhNode, OverwriteAllocator<BvhNode>>& nodes;
    uint32_t max_leaf;
    uint32_t leaf_base;  ///< the subtree's first position in the tree's prim_ids

    /// Stable partition of in[begin, end) into out: ids whose side stamp differs from `stamp`
    /// first (from out + begin), the others from out + mid.
    void partition(const uint32_t* in, uint32_t* out, uint32_t begin, uint32_t mid, uint32_t end,
                   uint8_t stamp) const {
        constexpr int W = build_width;
        uint32_t left = begin, right = mid;
        uint32_t i = begin;
        if constexpr (packet_loops) {
            // a packet of ids at a time: their side bytes gathered, each side's ids compressed
            // together and stored (no write past a side's end; the last packet's lanes past
            // `end` are inactive)
            const vint<W> s = broadcast<W>(int32_t{stamp});
            for (; i < end; i += W) {
                const vmask<W> valid = prefix_mask<W>(int(std::min(end - i, uint32_t{W})));
                const vint<W> ids = load(as_lanes(in + i), valid);
                const vmask<W> go_right = mask_and(valid, eq(gather_u8(side, ids, valid), s));
                right += uint32_t(compress_store(as_lanes(out + right), ids, go_right));
                left += uint32_t(
                    compress_store(as_lanes(out + left), ids, mask_andnot(valid, go_right)));
            }
        }
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

}  // namespace

void build_subtree(const float* const* c2, uint32_t m, uint32_t base, const uint32_t* ids,
                   const SubtreeMemory& mem, const TreeOut& out) {
    for (int k = 0; k < 3; ++k) sort_ids_by_key(c2[k], m, mem.lists[0][k], mem.items, mem.scratch);
    out.lap(&BuildPhases::sorts);
    // the sort's items are done with: their memory holds the side stamps, padded for gather_u8
    uint8_t* side = reinterpret_cast<uint8_t*>(mem.items);
    std::memset(side, 0, size_t(m) + gather_u8_padding);  // stamp 0: no node yet
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

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
