// bench: the instruction sets a benchmark program races (isa_sets.h).
#include "support/isa_sets.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>

namespace raylane::bench {

namespace {

std::vector<Isa>& chosen() {
    static std::vector<Isa> sets;
    return sets;
}

}  // namespace

int run_plain_benchmarks(int argc, char** argv) {
    if (!choose_isas(argv[0])) return 2;  // a RAYLANE_ISA it cannot use
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

bool choose_isas(const char* program) {
    try {
        const char* env = std::getenv("RAYLANE_ISA");
        if (env && *env) {
            use_isa_named(env, "RAYLANE_ISA");
            chosen() = {active_isa()};
        } else {
            chosen() = runnable_isas();
            if (chosen().empty()) active_isa();  // throws: this CPU runs none of the sets
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return false;
    }
    return true;
}

const std::vector<Isa>& raced_isas() { return chosen(); }

Isa isa_in_use() { return chosen().back(); }

std::string isa_label(Isa isa) {
    return std::string(isa_name(isa)) + " (W = " + std::to_string(isa_width(isa)) + ")";
}

void print_isas_not_raced(std::ostream& out) {
    bool first = true;
    for (Isa isa : all_isas) {
        if (!isa_compiled(isa) || std::count(chosen().begin(), chosen().end(), isa) > 0) continue;
        out << (first ? "\n" : "") << isa_label(isa) << ": not raced ("
            << (cpu_runs(isa) ? "RAYLANE_ISA names " + std::string(isa_name(isa_in_use()))
                              : std::string("this CPU does not run it"))
            << ")\n";
        first = false;
    }
}

}  // namespace raylane::bench
