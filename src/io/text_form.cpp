// io: the first-bytes checks of model files (text_form.h).
#include "io/text_form.h"

#include <cstdint>

#include "core/error.h"
#include "io/read_file.h"

namespace raylane {

namespace {

std::string_view first_kib(std::string_view bytes) { return bytes.substr(0, text_sniff_bytes); }

bool is_ascii_char(unsigned char c) { return c != 0 && c < 0x80; }

bool is_control(unsigned char c) {
    return c < 0x20 && c != '\t' && c != '\n' && c != '\v' && c != '\f' && c != '\r';
}

/// ASCII text stored as UTF-16 (LE or BE): most byte pairs hold a NUL and an ASCII character.
bool looks_like_utf16_without_mark(std::string_view bytes) {
    const std::string_view sample = first_kib(bytes);
    const size_t pairs = sample.size() / 2;
    if (pairs < 2) return false;
    size_t little = 0;
    size_t big = 0;
    for (size_t i = 0; i < pairs; ++i) {
        const auto a = static_cast<unsigned char>(sample[2 * i]);
        const auto b = static_cast<unsigned char>(sample[2 * i + 1]);
        little += is_ascii_char(a) && b == 0 ? 1 : 0;
        big += a == 0 && is_ascii_char(b) ? 1 : 0;
    }
    return 4 * little >= 3 * pairs || 4 * big >= 3 * pairs;
}

/// The offset of the byte that makes `bytes` binary (see refuse_binary), else SIZE_MAX.
size_t binary_byte(std::string_view bytes) {
    const std::string_view sample = first_kib(bytes);
    constexpr int controls_for_binary = 16;
    int controls = 0;
    size_t last_control = SIZE_MAX;
    for (size_t i = 0; i < sample.size(); ++i) {
        const auto c = static_cast<unsigned char>(sample[i]);
        if (c == 0) return i;
        if (is_control(c) && ++controls == controls_for_binary) last_control = i;
    }
    return last_control;
}

}  // namespace

void refuse_empty(std::string_view bytes, const std::string& file) {
    if (bytes.empty()) throw InputError(file + ": is empty");
}

void refuse_utf16(std::string_view bytes, const std::string& file) {
    const bool mark = bytes.starts_with("\xFF\xFE") || bytes.starts_with("\xFE\xFF");
    if (mark || looks_like_utf16_without_mark(bytes)) {
        throw InputError(file + ": is UTF-16 text; save it as UTF-8 or ASCII");
    }
}

void refuse_gzip(std::string_view bytes, const std::string& file) {
    if (bytes.starts_with("\x1F\x8B")) {
        throw InputError(file + ": is gzip-compressed; name it " + file_name_of(file) +
                         ".gz to read it");
    }
}

void refuse_binary(std::string_view bytes, const std::string& file, std::string_view format) {
    const size_t at = binary_byte(bytes);
    if (at == SIZE_MAX) return;
    static constexpr char hex[] = "0123456789abcdef";
    const auto c = static_cast<unsigned char>(bytes[at]);
    throw InputError(file + ": is a binary file, not a text " + std::string(format) + " (byte " +
                     std::to_string(at) + " is 0x" + hex[c >> 4] + hex[c & 15] + ")");
}

void refuse_non_text(std::string_view bytes, const std::string& file, std::string_view format) {
    refuse_empty(bytes, file);
    refuse_utf16(bytes, file);
    refuse_gzip(bytes, file);
    refuse_binary(bytes, file, format);
}

}  // namespace raylane
