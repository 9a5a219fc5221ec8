// api: raylane/version.h and raylane/instruction_sets.h, over core/isa.h.
#include "raylane/version.h"

#include <string>
#include <vector>

#include "api/guard.h"
#include "core/isa.h"
#include "raylane/instruction_sets.h"

namespace raylane {

const char* version() { return RAYLANE_VERSION; }

std::vector<std::string> compiled_instruction_sets() {
    std::vector<std::string> names;
    for (Isa isa : all_isas)
        if (isa_compiled(isa)) names.emplace_back(isa_name(isa));
    return names;
}

std::vector<std::string> cpu_instruction_sets() {
    std::vector<std::string> names;
    for (Isa isa : all_isas)
        if (cpu_runs(isa)) names.emplace_back(isa_name(isa));
    return names;
}

std::string instruction_set() {
    return guarded([] { return std::string(isa_name(active_isa())); });
}

int packet_width() {
    return guarded([] { return isa_width(active_isa()); });
}

void use_instruction_set(const std::string& name) {
    guarded([&] {
        if (name.empty())
            throw Error(
                "use_instruction_set: unknown instruction set '' (sets: sse4.2, avx2, avx512; "
                "this machine runs: " +
                runnable_isa_names() + ")");
        use_isa_named(name, "use_instruction_set");
    });
}

}  // namespace raylane
