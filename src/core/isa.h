// core: the instruction sets the packet path is compiled for, which of them this CPU runs, and
// the one in use. Width-dependent code (simd/ and every file that includes it) is compiled once
// per set, each copy in its own namespace (raylane::isa_sse42, isa_avx2, isa_avx512); the rest of
// the program is compiled for x86-64-v2 and calls the set in use through RAYLANE_DISPATCH.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace raylane {

/// An instruction set of the packet path: sse4.2 (x86-64-v2, W = 4), avx2 (x86-64-v3: AVX2,
/// FMA, BMI; W = 8), avx512 (x86-64-v4: AVX-512 F, CD, BW, DQ, VL; W = 16).
enum class Isa : uint8_t { sse42, avx2, avx512 };

/// Every set, narrowest first.
inline constexpr Isa all_isas[] = {Isa::sse42, Isa::avx2, Isa::avx512};

/// The name --isa and RAYLANE_ISA take: "sse4.2", "avx2", "avx512".
const char* isa_name(Isa isa);
/// The packet width of the set's renderer and queries: 4, 8 or 16.
int isa_width(Isa isa);

/// Whether this build holds the set's code (a build may leave sets out: RAYLANE_ISAS).
bool isa_compiled(Isa isa);
/// Whether this CPU and operating system run the set: its instructions (cpuid) and, for avx2 and
/// avx512, the registers' state saved by the operating system (XCR0).
bool cpu_runs(Isa isa);
/// The sets compiled in that this CPU runs, narrowest first (empty on a CPU below x86-64-v2).
std::vector<Isa> runnable_isas();

/// The set in use: the one forced by use_isa, else the one RAYLANE_ISA names, else the widest
/// runnable set. Throws InputError when RAYLANE_ISA names no set this machine runs.
Isa active_isa();
/// Uses `isa` from now on, for every thread. Throws InputError naming the runnable sets when this
/// build or CPU cannot run it.
void use_isa(Isa isa);
/// The set a name (--isa, RAYLANE_ISA, the Python module's argument) gives: use_isa(parse) or an
/// InputError "<source>: unknown instruction set '<name>' (this machine runs: sse4.2, avx2)".
/// An empty name leaves the choice as it is (RAYLANE_ISA, else the widest).
void use_isa_named(std::string_view name, std::string_view source);

/// One line each: the sets compiled in, those this CPU runs, and the one in use with its width,
/// e.g. "instruction sets: sse4.2 avx2 avx512 (compiled), sse4.2 avx2 (this CPU), avx2 in use
/// (W = 8)".
std::string isa_summary();

/// The runnable sets' names, "sse4.2, avx2, avx512", for messages.
std::string runnable_isa_names();

}  // namespace raylane

// ---- dispatch -----------------------------------------------------------------------------------
// RAYLANE_HAS_SSE42, RAYLANE_HAS_AVX2, RAYLANE_HAS_AVX512 (1 or 0) say which sets the build
// compiled (CMakeLists.txt, RAYLANE_ISAS).

#if RAYLANE_HAS_SSE42
#define RAYLANE_IF_SSE42(...) __VA_ARGS__
#else
#define RAYLANE_IF_SSE42(...)
#endif
#if RAYLANE_HAS_AVX2
#define RAYLANE_IF_AVX2(...) __VA_ARGS__
#else
#define RAYLANE_IF_AVX2(...)
#endif
#if RAYLANE_HAS_AVX512
#define RAYLANE_IF_AVX512(...) __VA_ARGS__
#else
#define RAYLANE_IF_AVX512(...)
#endif

/// X(namespace) for every set compiled in: declares each set's copy of a function, e.g.
/// `#define DECLARE(ns) namespace raylane::ns { int f(); }` then RAYLANE_FOR_EACH_ISA(DECLARE).
#define RAYLANE_FOR_EACH_ISA(X) \
    RAYLANE_IF_SSE42(X(isa_sse42)) RAYLANE_IF_AVX2(X(isa_avx2)) RAYLANE_IF_AVX512(X(isa_avx512))

/// `return ns::call;` for the set in use (active_isa()): the body of a dispatching function.
#define RAYLANE_DISPATCH(call)                                                               \
    switch (::raylane::active_isa()) {                                                       \
        RAYLANE_IF_SSE42(case ::raylane::Isa::sse42 : return ::raylane::isa_sse42::call;)    \
        RAYLANE_IF_AVX2(case ::raylane::Isa::avx2 : return ::raylane::isa_avx2::call;)       \
        RAYLANE_IF_AVX512(case ::raylane::Isa::avx512 : return ::raylane::isa_avx512::call;) \
        default:                                                                             \
            break;                                                                           \
    }                                                                                        \
    ::raylane::isa_unreachable()

namespace raylane {
/// Called when active_isa() returned a set that is not compiled in (cannot happen: use_isa
/// refuses those); aborts with a message.
[[noreturn]] void isa_unreachable();
}  // namespace raylane
