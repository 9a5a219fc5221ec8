// raylane/instruction_sets.h: the packet path's instruction sets (sse4.2 at 4 lanes, avx2 at 8,
// avx512 at 16). One library carries every set; the widest this CPU runs is used unless the
// environment variable RAYLANE_ISA or use_instruction_set chooses another.
#pragma once

#include <string>
#include <vector>

namespace raylane {

/// The sets compiled into the library, narrowest first: "sse4.2", "avx2", "avx512".
std::vector<std::string> compiled_instruction_sets();
/// The sets this CPU runs, narrowest first (the library uses those that are also compiled in).
std::vector<std::string> cpu_instruction_sets();
/// The set in use, e.g. "avx2".
std::string instruction_set();
/// Lanes per packet of the set in use: 4, 8 or 16.
int packet_width();
/// Uses `name` from now on, for every thread. Throws Error naming the sets that can run when
/// this CPU does not run it, it is not compiled in, or no such set exists.
void use_instruction_set(const std::string& name);

}  // namespace raylane
