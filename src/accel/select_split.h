// accel: the median-split build's selects: the split key of a top node, and of both its children
// before it is partitioned (select_split.cpp), for the top splitter.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "accel/split_top.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {

/// The split of the node c[begin, end) that gives its first child `left` primitives. The keys
/// between two keys of an even sample that bracket the median (all keys, in a node of fewer
/// than sampled_from) are gathered into `keys` and the median found among them; when they are
/// more than `capacity` or the median is outside, a radix select with `histogram`
/// (histogram_counts counts). `paths` counts which way it went.
SplitKey select_split(const float* c, uint32_t begin, uint32_t end, uint32_t left,
                      uint32_t* histogram, uint32_t* keys, uint32_t capacity,
                      MedianSplitPaths& paths);

/// The splits of both children of a top node split by `split` on `axis`, each on its own axis
/// child_axis[side], as select_split would find them once the node is partitioned, but from the
/// node's unpartitioned primitives: an even sample of the node's keys, each on its side by
/// key, brackets each child's median, and one sweep gathers both children's keys within their
/// brackets into keys[0 .. capacity) and keys[capacity .. 2 capacity). Nothing when a bracket
/// holds more than `capacity` keys or misses its child's median. `sample` holds 4
/// bracket_samples keys.
std::optional<std::array<SplitKey, 2>> select_children(const TopArrays& cur, uint32_t begin,
                                                       uint32_t end, int axis, SplitKey split,
                                                       const int child_axis[2], uint32_t* sample,
                                                       uint32_t* keys, uint32_t capacity);

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
