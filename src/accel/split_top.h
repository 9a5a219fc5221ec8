// accel: the median-split build's top levels: the nodes above BuildParams::median_subtree, split
// by selecting their median key and partitioning ids and centroids (split_top.cpp,
// select_split.cpp), down to subtree builds.
#pragma once

#include <cstdint>

#include "accel/build_subtree.h"
#include "accel/bvh.h"
#include "accel/order_key.h"
#include "simd/lanes.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {

/// Keys in the even sample of a node whose two keys around the median bracket it.
inline constexpr uint32_t bracket_samples = 4096;
/// Nodes of this many primitives (65,536) or more are sampled for a bracket of their median;
/// the selects gather every key of a smaller node.
inline constexpr uint32_t sampled_from = 16 * bracket_samples;
/// Counts in the selects' histogram: one per value of 16 bits of a key.
inline constexpr uint32_t histogram_counts = uint32_t(1) << 16;

/// The primitives of the nodes too large for a subtree build, in one of two buffers: the tree's
/// ids, increasing within a node, and their doubled centroids. A node's primitives sit at its
/// range of prim_ids.
struct TopArrays {
    uint32_t* ids;
    float* c2[3];
};

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
    /// The lanes of `among`, the next primitives in order, that go to the first child.
    vmask<build_width> first(const vint<build_width>& key, const vmask<build_width>& among) {
        constexpr int W = build_width;
        const vint<W> split = broadcast<W>(s.key);
        const vmask<W> below = mask_and(among, lt_u32(key, split));
        // the first s.ties of the equal keys
        const vmask<W> taken = keep_first_active(mask_and(among, eq(key, split)), s.ties);
        s.ties -= uint32_t(count(taken));
        return mask_or(below, taken);
    }
};

/// The nodes of more than `subtree_limit` primitives, split without sorted lists: the split key
/// by select_split on the longest axis of the key bounds, and partition_top into the other
/// buffer; or, when both children are above the limit too, their splits found first
/// (child_key_bounds, select_children) and the four grandchildren made by partition_four, one
/// pass over the node's primitives where two levels of partition_top make two. Each node of at
/// most subtree_limit primitives becomes a subtree build on its own compact arrays, which stay
/// in the cache where the whole tree's lists would not. The same tree as one subtree build over
/// all the primitives.
struct TopSplitter {
    const TreeOut& out;
    const SubtreeMemory& mem;
    uint32_t subtree_limit;
    uint32_t* keys;       ///< 2 capacity keys gathered by the selects
    uint32_t capacity;    ///< >= sampled_from: all the keys of a node of fewer
    uint32_t* histogram;  ///< histogram_counts counts
    uint32_t* root_ids;   ///< the ids of the root's buffer, whose root has null ids (positions)
    MedianSplitPaths& paths;

    /// The subtree of the node cur[begin, end), with `other` as the partitions' buffer.
    void build(uint32_t begin, uint32_t end, const TopArrays& cur, const TopArrays& other) const;
};

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
