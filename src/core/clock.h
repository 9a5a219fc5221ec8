// core: wall-clock time in seconds, for the timings the commands and the Python module print.
#pragma once

#include <chrono>

namespace raylane {

/// Seconds on the steady clock (an arbitrary origin: only differences mean anything).
inline double now_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

/// Milliseconds since `start_seconds` (a now_seconds() value).
inline double elapsed_ms(double start_seconds) { return 1000.0 * (now_seconds() - start_seconds); }

}  // namespace raylane
