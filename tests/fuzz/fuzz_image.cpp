// fuzz: libFuzzer target for the image reader (io/load_image.h: PNG, JPEG, Radiance HDR through
// stb_image), from memory. Seeds: tests/fuzz/corpus/image/; run by scripts/fuzz.sh.
//
// A header of a few bytes may declare any size up to max_image_texels, and the reader then
// decodes that many texels by design (a JPEG or HDR body that ends early decodes as black). Under
// the sanitizers that takes seconds, so inputs declaring more than fuzz_max_texels but no more
// than the reader's limit are skipped; larger ones still run (the reader rejects them from the
// header).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "io/load_image.h"

namespace {

constexpr int64_t fuzz_max_texels = int64_t{1} << 18;

unsigned byte_at(std::string_view s, size_t i) {
    return i < s.size() ? static_cast<unsigned char>(s[i]) : 0u;
}
int64_t be16(std::string_view s, size_t i) {
    return int64_t{byte_at(s, i)} << 8 | byte_at(s, i + 1);
}
int64_t be32(std::string_view s, size_t i) { return be16(s, i) << 16 | be16(s, i + 2); }

/// The first number after `key` in `s`, or 0.
int64_t number_after(std::string_view s, std::string_view key) {
    size_t at = s.find(key);
    if (at == std::string_view::npos) return 0;
    int64_t v = 0;
    for (at += key.size(); at < s.size() && s[at] >= '0' && s[at] <= '9' && v < (1 << 30); ++at)
        v = v * 10 + (s[at] - '0');
    return v;
}

/// Width x height as the header declares it, as far as this quick look can tell; 0 if unknown.
int64_t declared_texels(std::string_view s) {
    if (s.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8)) {
        const int64_t width = be32(s, 16), height = be32(s, 20);  // each below 2^32
        return height == 0 || width <= INT64_MAX / height ? width * height : INT64_MAX;
    }
    if (s.substr(0, 2) == "#?") {  // each number below 2^34, the product checked
        const int64_t height = number_after(s, "-Y "), width = number_after(s, "+X ");
        return height == 0 || width <= INT64_MAX / height ? width * height : INT64_MAX;
    }
    if (byte_at(s, 0) != 0xFF) return 0;
    // JPEG: markers up to the first start of frame (SOF0-15 except DHT, JPG and DAC)
    size_t i = 1;
    while (i + 1 < s.size()) {
        if (byte_at(s, i) != 0xFF) {
            ++i;
            continue;
        }
        const unsigned marker = byte_at(s, i + 1);
        if (marker == 0xFF || marker == 0x00 || marker == 0x01 || marker == 0xD8 ||
            (marker >= 0xD0 && marker <= 0xD7)) {
            i += marker == 0xFF ? 1 : 2;
            continue;
        }
        if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 &&
            marker != 0xCC) {
            return be16(s, i + 5) * be16(s, i + 7);
        }
        const auto length = static_cast<size_t>(be16(s, i + 2));
        i += 2 + (length < 2 ? 2 : length);
    }
    return 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const int64_t texels = declared_texels(bytes);
    if (texels > fuzz_max_texels && texels <= raylane::max_image_texels) return -1;
    // Both encodings without a format byte in front of the file: the length's parity picks one.
    const auto encoding =
        size % 2 == 0 ? raylane::ImageEncoding::linear : raylane::ImageEncoding::srgb;
    try {
        raylane::fuzz::check_texture(
            raylane::load_texture_from_memory(bytes, "fuzz.image", encoding));
    } catch (const raylane::InputError&) {
        // Expected for bad input; any other exception escapes and is a finding.
    }
    return 0;
}
