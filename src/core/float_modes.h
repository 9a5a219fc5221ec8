// core: the floating-point modes the renderers and the batch queries run in: flush-to-zero and
// denormals-are-zero (numerics.md §0.2), set per thread, and the guard that puts back a thread's
// own modes when a call into the library returns.
#pragma once

#include <xmmintrin.h>

namespace raylane {

/// MXCSR's flush-to-zero (bit 15) and denormals-are-zero (bit 6) bits.
inline constexpr unsigned flush_to_zero_bits = 0x8040u;

/// Sets flush-to-zero and denormals-are-zero for the calling thread (numerics.md §0.2).
inline void enable_flush_to_zero() { _mm_setcsr(_mm_getcsr() | flush_to_zero_bits); }

/// The calling thread's floating-point modes (MXCSR) when it is made, put back when it goes: for
/// a thread the caller owns (Python's, a TBB worker of the caller's arena) that the library sets
/// flush-to-zero on.
class KeepFloatModes {
  public:
    KeepFloatModes() = default;
    ~KeepFloatModes() { _mm_setcsr(saved_); }
    KeepFloatModes(const KeepFloatModes&) = delete;
    KeepFloatModes& operator=(const KeepFloatModes&) = delete;

  private:
    unsigned saved_ = _mm_getcsr();
};

}  // namespace raylane
