// fuzz: libFuzzer target for the OBJ reader (io/load_obj.h), from memory. Seeds:
// tests/fuzz/corpus/obj/; run by scripts/fuzz.sh. Sibling of fuzz_ply.cpp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "io/load_obj.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        raylane::fuzz::check_mesh(raylane::load_obj_from_memory(text, "fuzz.obj"));
    } catch (const raylane::InputError&) {
        // Expected for bad input; any other exception escapes and is a finding.
    }
    return 0;
}
