// io: reading whole files into memory, and quoting input text inside one-line error messages.
// Used by every loader in io/ (load_obj.cpp, load_ply.cpp, load_scene.cpp, ...).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace raylane {

/// The bytes of a file, for as long as the object lives: a read-only mapping of a regular file
/// (no copy and no fresh memory: its pages are the page cache's; a 3 MB model maps in 2 ms
/// where reading it into new memory took 10–18 ms), else the bytes read into a
/// string (pipes, devices, empty files). A mapped file that another program truncates while it
/// is being parsed ends the process with SIGBUS, as in every program that maps its input.
class FileBytes {
  public:
    FileBytes() = default;
    FileBytes(FileBytes&& other) noexcept;
    FileBytes& operator=(FileBytes&& other) noexcept;
    FileBytes(const FileBytes&) = delete;
    FileBytes& operator=(const FileBytes&) = delete;
    ~FileBytes();
    std::string_view view() const {
        return mapped_ ? std::string_view(mapped_, size_) : std::string_view(data_);
    }

    /// Takes over `size` (> 0) bytes at `mapping`, a block of mmap no longer than `size`
    /// rounded up to whole pages, and unmaps it when the object goes (gzip_file.cpp's output).
    static FileBytes adopt_mapping(const char* mapping, size_t size);

  private:
    friend FileBytes map_file(const std::string& path);
    friend std::string read_file(const std::string& path);
    const char* mapped_ = nullptr;
    size_t size_ = 0;
    std::string data_;
};

/// The whole content of `path`, bytes unchanged (no newline translation), mapped or read as
/// FileBytes says. Throws InputError "path: cannot read: reason" when the file is missing, is a
/// directory, or cannot be read.
FileBytes map_file(const std::string& path);

/// map_file's bytes copied into a string.
std::string read_file(const std::string& path);

/// `text` made safe to put inside a one-line error message: at most `max_chars` characters,
/// control and non-ASCII bytes written as \xNN, "..." appended when cut, wrapped in quotes.
std::string quote_for_error(std::string_view text, size_t max_chars = 24);

/// The last component of `path` ("models/dragon.ply" -> "dragon.ply").
std::string file_name_of(const std::string& path);

}  // namespace raylane
