// simd: the namespace of one instruction set's copy of the width-dependent code. Everything that
// includes simd/ is compiled once per set (CMakeLists.txt, RAYLANE_ISA_SOURCES) with that set's
// flags and RAYLANE_ISA_NS naming its namespace: raylane::isa_sse42, isa_avx2 or isa_avx512.
// The rest of the program is compiled for the baseline and calls a set through core/isa.h.
#pragma once

#if !defined(RAYLANE_ISA_NS)
#error \
    "width-dependent code (simd/, *_packet.h) is compiled once per instruction set: list this source in RAYLANE_ISA_SOURCES (CMakeLists.txt) or call it through core/isa.h"
#endif

namespace raylane {
inline namespace RAYLANE_ISA_NS {}
}  // namespace raylane
