// bench: the instruction sets a benchmark program races (core/isa.h): every set this build and
// CPU run, or the one RAYLANE_ISA names. Each set-dependent benchmark uses its set itself
// (use_isa before its timed loop); the others run on the set in use.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/isa.h"

namespace raylane::bench {

/// Chooses the sets to race: the one RAYLANE_ISA names, else every set this build and CPU run
/// (narrowest first). On a name it cannot use, or a CPU that runs no set, prints one line
/// "<program>: <reason>" on stderr and returns false: the program exits with status 2.
bool choose_isas(const char* program);

/// Google Benchmark's own main after choose_isas, for the programs without --summary.
int run_plain_benchmarks(int argc, char** argv);

/// The sets choose_isas chose, narrowest first.
const std::vector<Isa>& raced_isas();

/// The set in use for the benchmarks that do not race every set: RAYLANE_ISA's, else the widest
/// this CPU runs (the one `raylane` uses).
Isa isa_in_use();

/// "avx2 (W = 8)".
std::string isa_label(Isa isa);

/// One line per set compiled in but not raced, and why, after a blank line (nothing when every
/// set is raced): "avx512 (W = 16): not raced (this CPU does not run it)", or "(RAYLANE_ISA
/// names avx2)".
void print_isas_not_raced(std::ostream& out);

}  // namespace raylane::bench
