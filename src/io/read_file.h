// io: reading whole files into memory, and quoting input text inside one-line error messages.
// Used by every loader in io/ (load_obj.cpp, load_ply.cpp, load_scene.cpp, ...).
#pragma once

#include <string>
#include <string_view>

namespace raylane {

/// The whole content of `path`, bytes unchanged (no newline translation).
/// Throws InputError "path: cannot read: reason" when the file is missing, is a directory, or
/// cannot be read.
std::string read_file(const std::string& path);

/// `text` made safe to put inside a one-line error message: at most `max_chars` characters,
/// control and non-ASCII bytes written as \xNN, "..." appended when cut, wrapped in quotes.
std::string quote_for_error(std::string_view text, size_t max_chars = 24);

/// The last component of `path` ("models/dragon.ply" -> "dragon.ply").
std::string file_name_of(const std::string& path);

}  // namespace raylane
