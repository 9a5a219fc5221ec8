// accel: the median-split build's subtree builder: a node of at most BuildParams::median_subtree
// primitives built down to its leaves from three sorted lists (build_subtree.cpp), and where a
// build puts its tree.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "accel/bvh.h"
#include "simd/namespace.h"

namespace raylane::RAYLANE_ISA_NS::median_detail {

/// Aabb::longest_axis of the extents without branches (the axis is unpredictable):
/// (x >= y && x >= z) ? 0 : (y >= z ? 1 : 2).
inline int longest_axis(const float extent[3]) {
    const unsigned x_wins = unsigned(extent[0] >= extent[1]) & unsigned(extent[0] >= extent[2]);
    return int((x_wins ^ 1u) * (2u - unsigned(extent[1] >= extent[2])));
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
/// items and scratch (the items' memory holds the side stamps after the sorts). Each array holds
/// as many elements as the subtree has primitives.
struct SubtreeMemory {
    uint32_t* lists[2][3];
    uint64_t* items;
    uint64_t* scratch;
};

/// The median-split subtree of m >= 1 primitives whose doubled centroids are c2[k][0 .. m-1]:
/// three radix sorts, then the splits in sorted lists. Its nodes are appended to out.nodes,
/// without bounds, and its primitives written to out.prim_ids[base .. base + m): ids[i] is the
/// tree's id of primitive i (ids in increasing order, so that ties break as in the whole tree's
/// order), or i itself when `ids` is null.
void build_subtree(const float* const* c2, uint32_t m, uint32_t base, const uint32_t* ids,
                   const SubtreeMemory& mem, const TreeOut& out);

}  // namespace raylane::RAYLANE_ISA_NS::median_detail
