// api: raylane/version.h and raylane/instruction_sets.h, over core/isa.h.
#include "raylane/version.h"

#include <string>
#include <vector>

#include "api/guard.h"
#include "core/isa.h"
#include "raylane/instruction_sets.h"

namespace raylane {

const char* version() { return RAYLANE_VERSION; }

void check_range(const char* name, long long value, long long lo, long long hi) {
    if (value >= lo && value <= hi) return;
    std::string m = name;
    m.append(": ").append(std::to_string(value)).append(" is outside ");
    throw Error(m.append(std::to_string(lo)).append(" .. ").append(std::to_string(hi)));
}

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
