// core: which instruction sets this CPU runs (cpuid, XCR0) and the one in use (core/isa.h).
#include "core/isa.h"

#include <cpuid.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"

namespace raylane {
namespace {

struct CpuidRegs {
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
};

/// cpuid leaf `leaf`, sub-leaf `sub`; zeros when the CPU has no such leaf.
CpuidRegs cpuid(unsigned leaf, unsigned sub) {
    CpuidRegs r;
    if (!__get_cpuid_count(leaf, sub, &r.eax, &r.ebx, &r.ecx, &r.edx)) return {};
    return r;
}

bool bit(unsigned reg, int b) { return (reg >> b) & 1u; }

/// The register state the operating system saves (XCR0): 0 when it does not use XSAVE.
uint64_t xcr0() {
    if (!bit(cpuid(1, 0).ecx, 27)) return 0;  // OSXSAVE
    unsigned lo = 0, hi = 0;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    return (uint64_t(hi) << 32) | lo;
}

/// The features each level of the x86-64 psABI requires (what -march=x86-64-vN lets the compiler
/// emit), tested one by one.
struct CpuLevels {
    bool v2 = false, v3 = false, v4 = false;
};

CpuLevels read_cpu_levels() {
    const CpuidRegs l1 = cpuid(1, 0), l7 = cpuid(7, 0), e1 = cpuid(0x80000001u, 0);
    CpuLevels levels;
    // x86-64-v2: CMPXCHG16B, LAHF-SAHF, POPCNT, SSE3, SSE4.1, SSE4.2, SSSE3
    levels.v2 = bit(l1.ecx, 13) && bit(e1.ecx, 0) && bit(l1.ecx, 23) && bit(l1.ecx, 0) &&
                bit(l1.ecx, 19) && bit(l1.ecx, 20) && bit(l1.ecx, 9);
    // x86-64-v3: AVX, AVX2, BMI1, BMI2, F16C, FMA, LZCNT, MOVBE, XSAVE; the OS saves the SSE and
    // AVX state (XCR0 bits 1 and 2)
    const uint64_t xcr = xcr0();
    levels.v3 = levels.v2 && bit(l1.ecx, 28) && bit(l7.ebx, 5) && bit(l7.ebx, 3) &&
                bit(l7.ebx, 8) && bit(l1.ecx, 29) && bit(l1.ecx, 12) && bit(e1.ecx, 5) &&
                bit(l1.ecx, 22) && bit(l1.ecx, 26) && (xcr & 0x6) == 0x6;
    // x86-64-v4: AVX512F, AVX512BW, AVX512CD, AVX512DQ, AVX512VL; the OS saves the opmask and ZMM
    // state too (XCR0 bits 5, 6 and 7)
    levels.v4 = levels.v3 && bit(l7.ebx, 16) && bit(l7.ebx, 30) && bit(l7.ebx, 28) &&
                bit(l7.ebx, 17) && bit(l7.ebx, 31) && (xcr & 0xe6) == 0xe6;
    return levels;
}

const CpuLevels& cpu_levels() {
    static const CpuLevels levels = read_cpu_levels();
    return levels;
}

/// -1 until the set is chosen, then the Isa's value.
std::atomic<int> chosen{-1};

bool parse(std::string_view name, Isa& out) {
    for (Isa isa : all_isas)
        if (name == isa_name(isa)) {
            out = isa;
            return true;
        }
    // sse4.2 as other tools spell it (xsimd's sse4_2)
    if (name == "sse42" || name == "sse4_2") {
        out = Isa::sse42;
        return true;
    }
    return false;
}

/// Why `isa` cannot be used here, or empty when it can.
std::string refusal(Isa isa) {
    if (!isa_compiled(isa))
        return std::string("this build has no ") + isa_name(isa) +
               " code (runs: " + runnable_isa_names() + ")";
    if (!cpu_runs(isa))
        return std::string("this CPU does not run ") + isa_name(isa) +
               " (runs: " + runnable_isa_names() + ")";
    return {};
}

Isa widest_runnable() {
    const std::vector<Isa> sets = runnable_isas();
    if (sets.empty())
        throw InputError(
            "this CPU does not run any instruction set of the packet path (it needs at least "
            "x86-64-v2: SSE4.2 and POPCNT)");
    return sets.back();
}

}  // namespace

const char* isa_name(Isa isa) {
    switch (isa) {
        case Isa::sse42:
            return "sse4.2";
        case Isa::avx2:
            return "avx2";
        case Isa::avx512:
            return "avx512";
    }
    return "?";
}

int isa_width(Isa isa) {
    switch (isa) {
        case Isa::sse42:
            return 4;
        case Isa::avx2:
            return 8;
        case Isa::avx512:
            return 16;
    }
    return 1;
}

bool isa_compiled(Isa isa) {
    switch (isa) {
        case Isa::sse42:
            return RAYLANE_HAS_SSE42 != 0;
        case Isa::avx2:
            return RAYLANE_HAS_AVX2 != 0;
        case Isa::avx512:
            return RAYLANE_HAS_AVX512 != 0;
    }
    return false;
}

bool cpu_runs(Isa isa) {
    const CpuLevels& levels = cpu_levels();
    switch (isa) {
        case Isa::sse42:
            return levels.v2;
        case Isa::avx2:
            return levels.v3;
        case Isa::avx512:
            return levels.v4;
    }
    return false;
}

std::vector<Isa> runnable_isas() {
    std::vector<Isa> sets;
    for (Isa isa : all_isas)
        if (isa_compiled(isa) && cpu_runs(isa)) sets.push_back(isa);
    return sets;
}

std::string runnable_isa_names() {
    std::string names;
    for (Isa isa : runnable_isas())
        names += (names.empty() ? "" : ", ") + std::string(isa_name(isa));
    return names.empty() ? "none" : names;
}

Isa active_isa() {
    const int c = chosen.load(std::memory_order_acquire);
    if (c >= 0) return static_cast<Isa>(c);
    const char* env = std::getenv("RAYLANE_ISA");
    if (env && *env)
        use_isa_named(env, "RAYLANE_ISA");
    else
        use_isa(widest_runnable());
    return static_cast<Isa>(chosen.load(std::memory_order_acquire));
}

void use_isa(Isa isa) {
    const std::string why = refusal(isa);
    if (!why.empty()) throw InputError(std::string(isa_name(isa)) + ": " + why);
    chosen.store(static_cast<int>(isa), std::memory_order_release);
}

void use_isa_named(std::string_view name, std::string_view source) {
    if (name.empty()) return;
    Isa isa{};
    if (!parse(name, isa))
        throw InputError(
            std::string(source) + ": unknown instruction set '" + std::string(name) +
            "' (sets: sse4.2, avx2, avx512; this machine runs: " + runnable_isa_names() + ")");
    const std::string why = refusal(isa);
    if (!why.empty()) throw InputError(std::string(source) + ": " + std::string(name) + ": " + why);
    use_isa(isa);
}

std::string isa_summary() {
    std::string compiled, runs;
    for (Isa isa : all_isas) {
        if (isa_compiled(isa)) compiled += std::string(compiled.empty() ? "" : " ") + isa_name(isa);
        if (cpu_runs(isa)) runs += std::string(runs.empty() ? "" : " ") + isa_name(isa);
    }
    const Isa in_use = active_isa();
    return "instruction sets: " + compiled + " (compiled), " + (runs.empty() ? "none" : runs) +
           " (this CPU), " + isa_name(in_use) +
           " in use (W = " + std::to_string(isa_width(in_use)) + ")";
}

void isa_unreachable() {
    std::fprintf(stderr,
                 "raylane: internal error: the instruction set in use is not compiled in\n");
    std::abort();
}

}  // namespace raylane
