// fuzz: libFuzzer target for the PLY reader (io/load_ply.h), ascii and binary, from memory.
// Seeds: tests/fuzz/corpus/ply/; run by scripts/fuzz.sh. Sibling of fuzz_obj.cpp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "io/load_ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try {
        raylane::fuzz::check_mesh(raylane::load_ply_from_memory(bytes, "fuzz.ply"));
    } catch (const raylane::InputError&) {
        // Expected for bad input; any other exception escapes and is a finding.
    }
    return 0;
}
