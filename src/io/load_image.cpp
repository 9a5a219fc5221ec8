// io: image files -> Texture (load_image.h). The header and the file's completeness are checked
// here before stb_image decodes anything; stb's allocations are capped by the header's size.
#include "io/load_image.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <system_error>

#include "core/error.h"
#include "io/read_file.h"
#include "io/stb_image.h"

namespace raylane {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& reason) {
    throw InputError(name + ": " + reason);
}

std::string stb_reason() {
    const char* reason = stbi_failure_reason();
    return reason != nullptr ? reason : "unknown error";
}

/// Sets stb_allocation_limit for the current scope.
struct AllocationBudget {
    size_t saved = stb_allocation_limit;
    explicit AllocationBudget(size_t bytes) { stb_allocation_limit = bytes; }
    ~AllocationBudget() { stb_allocation_limit = saved; }
    AllocationBudget(const AllocationBudget&) = delete;
    AllocationBudget& operator=(const AllocationBudget&) = delete;
};

/// Frees stb_image's output.
struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

uint8_t byte_at(std::string_view bytes, size_t i) { return static_cast<uint8_t>(bytes[i]); }

uint32_t big_endian32(std::string_view bytes, size_t i) {
    return static_cast<uint32_t>(byte_at(bytes, i)) << 24 |
           static_cast<uint32_t>(byte_at(bytes, i + 1)) << 16 |
           static_cast<uint32_t>(byte_at(bytes, i + 2)) << 8 | byte_at(bytes, i + 3);
}

/// Zero, negative and over-limit sizes, from the header's numbers.
void check_size(const std::string& name, int64_t width, int64_t height) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width <= 0 || height <= 0) fail(name, "image has no pixels (" + size + ")");
    if (width > max_image_side || height > max_image_side || width * height > max_image_texels)
        fail(name, "image is " + size +
                       ", over the limit (a side > 32768 or width*height > 2^26 "
                       "texels)");
}

bool is_png(std::string_view bytes) {
    return bytes.size() >= 8 && bytes.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8);
}
/// Where a JPEG's first segment starts (after SOI, which stb accepts after 0xff fill bytes),
/// or 0 when the bytes are no JPEG.
size_t jpeg_start(std::string_view bytes) {
    if (bytes.empty() || byte_at(bytes, 0) != 0xff) return 0;
    size_t i = 1;
    while (i < bytes.size() && byte_at(bytes, i) == 0xff) ++i;
    return i < bytes.size() && byte_at(bytes, i) == 0xd8 ? i + 1 : 0;
}

/// PNG: the IHDR size is read here, before stb, whose own probe refuses large sizes with a
/// message that does not say what the limit is. Then the chunks are walked (length, type, data,
/// CRC) to reject an empty IDAT before any IDAT with data: stb_image 2.27 then copies zero bytes
/// to a null buffer (undefined behaviour; found by fuzzing under UBSan).
void check_png_header(const std::string& name, std::string_view bytes) {
    // signature (8), IHDR length (4), "IHDR" (4), width (4), height (4)
    if (bytes.size() < 24 || bytes.substr(12, 4) != "IHDR") return;  // stb reports it
    check_size(name, big_endian32(bytes, 16), big_endian32(bytes, 20));
    for (size_t pos = 8; pos + 8 <= bytes.size();) {
        const size_t length = big_endian32(bytes, pos);
        const std::string_view type = bytes.substr(pos + 4, 4);
        if (type == "IDAT") {
            if (length == 0) fail(name, "corrupt PNG: empty IDAT chunk before the image data");
            return;  // stb has a buffer from here on
        }
        if (type == "IEND" || length > bytes.size()) return;  // stb reports what is wrong
        pos += 12 + length;
    }
}

/// JPEG: walks the marker segments the way stb_image 2.27 reads them (bytes between segments
/// skipped, 0xff fill bytes, entropy-coded data up to the next marker other than a stuffed
/// ff 00 or a restart) and rejects two files stb mis-handles:
/// - no end-of-image marker: stb decodes a cut-off file without complaint, the missing scan
///   data reading as zeros;
/// - a Huffman table (DHT) of more than 256 codes: stb writes past its 257-entry size list
///   (fixed in stb_image 2.28; found by the mutation test under UBSan).
/// - a scan whose components use a Huffman table no DHT defined: stb decodes with its zeroed
///   table and shifts by more than 31 bits (undefined behaviour; found by fuzzing under UBSan).
///   A baseline scan uses its components' DC and AC tables; a progressive scan the DC table in
///   a first DC pass (Ss = 0, Ah = 0), the AC table in an AC pass (Ss > 0).
/// EOIs inside APPn segments (an EXIF thumbnail) are skipped with their segment.
void check_jpeg(const std::string& name, std::string_view bytes, size_t start) {
    const size_t size = bytes.size();
    auto byte_or_0 = [&](size_t i) { return i < size ? byte_at(bytes, i) : uint8_t{0}; };
    size_t pos = start;
    uint32_t defined = 0;  // bit 4 * class + id of every Huffman table a DHT defined so far
    bool progressive = false;
    for (;;) {
        while (pos < size && byte_at(bytes, pos) != 0xff) ++pos;          // padding stb skips too
        while (pos + 1 < size && byte_at(bytes, pos + 1) == 0xff) ++pos;  // fill bytes
        if (pos + 1 >= size) fail(name, "truncated JPEG (no end-of-image marker)");
        const uint8_t marker = byte_at(bytes, pos + 1);
        pos += 2;
        if (marker == 0xd9) return;                                          // EOI
        if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd8)) continue;  // no length field
        if (pos + 2 > size) fail(name, "truncated JPEG (no end-of-image marker)");
        const size_t length = size_t{byte_at(bytes, pos)} << 8 | byte_at(bytes, pos + 1);
        const size_t end = pos + length;  // the segment, its length field included
        if (marker == 0xc4) {  // DHT: tables of (class/id, 16 counts, sum-of-counts values)
            // as stb: a table starts wherever the segment has bytes left, and its counts may
            // run past the segment (past the end of the file they read as 0)
            for (size_t table = pos + 2; table < end;) {
                size_t codes = 0;
                for (size_t i = 1; i <= 16 && table + i < size; ++i)
                    codes += byte_at(bytes, table + i);
                if (codes > 256)
                    fail(name, "corrupt JPEG: Huffman table of " + std::to_string(codes) +
                                   " codes (at most 256)");
                const uint8_t th = byte_or_0(table);
                if (th >> 4 <= 1 && (th & 15) <= 3) defined |= 1u << ((th >> 4) * 4 + (th & 15));
                table += 17 + codes;
            }
        }
        if (marker == 0xc2) progressive = true;  // SOF2
        if (marker == 0xda) {  // SOS: Ns, Ns x (component, DC table << 4 | AC table), Ss, Se, Ah/Al
            const size_t ns = byte_or_0(pos + 2);
            const uint8_t ss = byte_or_0(pos + 3 + 2 * ns), ah = byte_or_0(pos + 5 + 2 * ns) >> 4;
            const bool dc = !progressive || (ss == 0 && ah == 0), ac = !progressive || ss > 0;
            for (size_t c = 0; c < ns && c < 4; ++c) {
                const uint8_t tables = byte_or_0(pos + 4 + 2 * c);
                const uint32_t td = tables >> 4, ta = tables & 15;
                if ((dc && td <= 3 && !(defined >> td & 1u)) ||
                    (ac && ta <= 3 && !(defined >> (4 + ta) & 1u)))
                    fail(name, "corrupt JPEG: a scan uses a Huffman table that was not defined");
            }
        }
        pos = end;
        if (marker == 0xda) {  // SOS: entropy-coded data follows up to the next real marker
            for (; pos + 1 < size; ++pos) {
                if (byte_at(bytes, pos) != 0xff) continue;
                const uint8_t next = byte_at(bytes, pos + 1);
                if (next != 0x00 && next != 0xff && (next < 0xd0 || next > 0xd7)) break;
            }
        }
    }
}

/// Radiance HDR: walks the pixel data exactly as stb_image 2.27 reads it and rejects what stb
/// would mis-read: a cut-off file (stb reads zeros past the end, and a run-length scanline cut
/// off, or holding a zero-length literal run, loops forever: CVE-2021-42715) and runs that
/// overflow their scanline. `width`, `height` are the header's, already checked.
void check_hdr_pixels(const std::string& name, std::string_view bytes, int width, int height) {
    // header: signature line, variable lines up to an empty line, then the resolution line
    size_t pos = 0;
    auto skip_line = [&]() -> bool {  // false when the line is empty
        const size_t start = pos;
        const size_t end = bytes.find('\n', pos);
        pos = end == std::string_view::npos ? bytes.size() : end + 1;
        return end != start;
    };
    skip_line();
    while (pos < bytes.size() && skip_line()) {
    }
    skip_line();

    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    auto left = [&] { return bytes.size() - pos; };
    auto truncated = [&](int row) {
        fail(name, "truncated Radiance HDR pixel data (row " + std::to_string(row) + " of " +
                       std::to_string(height) + ")");
    };
    if (width < 8 || width >= 32768) {  // flat RGBE: 4 bytes per pixel
        if (left() < 4 * pixels) truncated(static_cast<int>(left() / 4 / size_t(width)));
        return;
    }
    for (int row = 0; row < height; ++row) {
        if (left() < 4) truncated(row);
        const uint8_t c1 = byte_at(bytes, pos), c2 = byte_at(bytes, pos + 1);
        const uint8_t hi = byte_at(bytes, pos + 2);
        if (c1 != 2 || c2 != 2 || (hi & 0x80) != 0) {
            // not run-length encoded: stb reads the whole image flat from here, from (0, 0)
            if (left() < 4 * pixels) truncated(row);
            return;
        }
        const int length = hi << 8 | byte_at(bytes, pos + 3);
        pos += 4;
        if (length != width)
            fail(name, "corrupt Radiance HDR: scanline " + std::to_string(row) + " has length " +
                           std::to_string(length) + ", expected " + std::to_string(width));
        for (int channel = 0; channel < 4; ++channel) {
            for (int i = 0; i < width;) {
                if (left() < 1) truncated(row);
                int count = byte_at(bytes, pos++);
                size_t data = static_cast<size_t>(count);  // bytes following the count
                if (count > 128) {
                    count -= 128;
                    data = 1;
                } else if (count == 0) {
                    fail(name, "corrupt Radiance HDR: zero-length run in scanline " +
                                   std::to_string(row));
                }
                if (count > width - i)
                    fail(name, "corrupt Radiance HDR: run past the end of scanline " +
                                   std::to_string(row));
                if (left() < data) truncated(row);
                pos += data;
                i += count;
            }
        }
    }
}

/// Largest single allocation a legitimate decode of a width x height image needs, with slack:
/// PNG's inflated data of 16-bit RGBA is 8 bytes a texel plus a filter byte a row and stb may
/// double its buffer once (interlaced images); float RGB output is 12 bytes a texel.
size_t decode_budget(int width, int height) {
    const auto w = static_cast<size_t>(width), h = static_cast<size_t>(height);
    return 16 * w * h + 64 * (w + h) + (size_t{1} << 20);
}

float linear_8bit(int value) { return static_cast<float>(value) / 255.0f; }

}  // namespace

float srgb_to_linear(float c) {
    const double x = c;
    const double linear = x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
    return static_cast<float>(linear);
}

Texture load_texture_from_memory(std::string_view bytes, const std::string& name_for_errors,
                                 ImageEncoding encoding) {
    const std::string& name = name_for_errors;
    if (bytes.empty()) fail(name, "empty file, not an image");
    if (static_cast<int64_t>(bytes.size()) > max_image_file_bytes)
        fail(name, "file is " + std::to_string(bytes.size()) + " bytes, over the limit of 2^29");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int length = static_cast<int>(bytes.size());

    // Everything about the size is settled from the header, before any decoding. A JPEG's
    // segments are checked before stb's header probe, which already reads Huffman tables.
    if (is_png(bytes)) check_png_header(name, bytes);
    if (const size_t start = jpeg_start(bytes); start != 0) check_jpeg(name, bytes, start);
    int width = 0, height = 0, channels = 0;
    if (stbi_info_from_memory(data, length, &width, &height, &channels) == 0)
        fail(name, "not a PNG, JPEG or Radiance HDR image (" + stb_reason() + ")");
    check_size(name, width, height);
    const bool hdr = stbi_is_hdr_from_memory(data, length) != 0;
    if (hdr) check_hdr_pixels(name, bytes, width, height);

    Texture texture;
    texture.source = name;
    texture.kind = TextureKind::image;
    const size_t count = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
    int got_width = 0, got_height = 0, file_channels = 0;
    auto check_decoded = [&](const void* pixels) {
        if (pixels == nullptr) fail(name, "cannot decode: " + stb_reason());
        if (got_width != width || got_height != height)
            fail(name, "decoded size differs from the header");  // not expected from stb
    };

    AllocationBudget budget(decode_budget(width, height));
    if (hdr) {
        std::unique_ptr<float, StbFree> pixels(
            stbi_loadf_from_memory(data, length, &got_width, &got_height, &file_channels, 3));
        check_decoded(pixels.get());
        texture.texels.assign(pixels.get(), pixels.get() + count);
    } else if (stbi_is_16_bit_from_memory(data, length) != 0) {
        std::unique_ptr<stbi_us, StbFree> pixels(
            stbi_load_16_from_memory(data, length, &got_width, &got_height, &file_channels, 3));
        check_decoded(pixels.get());
        texture.texels.resize(count);
        for (size_t i = 0; i < count; ++i) {
            const float value = static_cast<float>(pixels.get()[i]) / 65535.0f;
            texture.texels[i] = encoding == ImageEncoding::srgb ? srgb_to_linear(value) : value;
        }
    } else {
        std::unique_ptr<stbi_uc, StbFree> pixels(
            stbi_load_from_memory(data, length, &got_width, &got_height, &file_channels, 3));
        check_decoded(pixels.get());
        float table[256];
        for (int i = 0; i < 256; ++i)
            table[i] =
                encoding == ImageEncoding::srgb ? srgb_to_linear(linear_8bit(i)) : linear_8bit(i);
        texture.texels.resize(count);
        for (size_t i = 0; i < count; ++i) texture.texels[i] = table[pixels.get()[i]];
    }
    texture.width = width;
    texture.height = height;
    return texture;
}

Texture load_texture(const std::string& path, ImageEncoding encoding) {
    // Size and kind first, so neither a huge file nor a pipe is read; map_file reports
    // missing files, directories and permissions.
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (!error && std::filesystem::exists(status) && !std::filesystem::is_directory(status)) {
        if (!std::filesystem::is_regular_file(status)) fail(path, "not a regular file");
        const auto bytes = std::filesystem::file_size(path, error);
        if (!error && bytes > static_cast<uintmax_t>(max_image_file_bytes))
            fail(path, "file is " + std::to_string(bytes) + " bytes, over the limit of 2^29");
    }
    return load_texture_from_memory(map_file(path).view(), path, encoding);
}

Texture make_checker(vec3 a, vec3 b, float checks) {
    Texture texture;
    texture.source = "checker";
    texture.kind = TextureKind::checker;
    texture.color_a = a;
    texture.color_b = b;
    texture.checks = checks;
    return texture;
}

}  // namespace raylane
