// render: a render's progress line on stderr (percent done, time spent, time left), which
// for_each_tile (tiles.h) and the MPI render advance tile by tile.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>

namespace raylane {

/// True when stderr is a terminal (progress is shown only then).
bool stderr_is_terminal();

/// Prints "label: N%, T s, ~R s left" on stderr when the percentage changes (only when stderr
/// is a terminal and `enabled`): the time since it was made and, from 2 % on, an estimate of
/// the time left from the pace so far.
struct Progress {
    const char* label;
    size_t total;
    bool enabled;
    std::atomic<size_t> done{0};
    std::atomic<int> shown{-1};
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    void step();
    void finish();
};

}  // namespace raylane
