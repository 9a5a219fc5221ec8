// io: what a model file holds, told from its first bytes before a text reader parses it: the
// refusals of an empty file, UTF-16 text, gzip data under a plain name and binary data, each
// one line that says what the file is. Used by load_obj.cpp and ply_header.cpp.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace raylane {

/// How many bytes at the start of a file the checks below look at.
inline constexpr size_t text_sniff_bytes = 1024;

/// Throws InputError "file: is empty" when `bytes` is empty.
void refuse_empty(std::string_view bytes, const std::string& file);

/// Throws InputError "file: is UTF-16 text; save it as UTF-8 or ASCII" for a UTF-16 byte order
/// mark (FF FE or FE FF) at the start, or when, in the first KiB, at least 3 of 4 byte pairs
/// are an ASCII character and a NUL (in either order): UTF-16 text without a mark.
void refuse_utf16(std::string_view bytes, const std::string& file);

/// Throws InputError "file: is gzip-compressed; name it NAME.gz to read it" when `bytes` start
/// with the gzip magic 1F 8B (the file's name does not end in .gz, or it would be inflated).
void refuse_gzip(std::string_view bytes, const std::string& file);

/// Throws InputError "file: is a binary file, not a text FORMAT (byte N is 0xNN)" when the first
/// KiB holds a NUL byte, or 16 or more other control bytes (below 0x20, and not tab, LF, VT, FF
/// or CR). N is the first NUL, else the 16th control byte. A stray control byte or two in a
/// text file is left to the reader, which names its line.
void refuse_binary(std::string_view bytes, const std::string& file, std::string_view format);

/// refuse_empty, refuse_utf16, refuse_gzip and refuse_binary in that order: what a reader of a
/// text-only format (OBJ) checks before parsing.
void refuse_non_text(std::string_view bytes, const std::string& file, std::string_view format);

}  // namespace raylane
