// image: writing a file through a temporary and a rename, so that an interrupted write never
// leaves a half file under its name. Used by the PNG (film.cpp) and PFM (pfm.cpp) writers.
#pragma once

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace raylane {
namespace image_detail {

/// Renames `tmp` over `path`, or removes it and throws.
inline void commit_file(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write: " + ec.message());
    }
}

inline std::string temp_name(const std::string& path) { return path + ".partial"; }

/// Writes a file through write(FILE*) -> bool into a temporary, then renames it over `path`:
/// an interrupted write never leaves a half file there. Throws std::runtime_error.
template <class Write>
void write_file(const std::string& path, Write&& write) {
    const std::string tmp = temp_name(path);
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
    errno = 0;
    bool ok = write(f);
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
        const int error = errno;
        std::remove(tmp.c_str());
        throw std::runtime_error(path + ": write failed" +
                                 (error ? std::string(": ") + std::strerror(error) : ""));
    }
    commit_file(tmp, path);
}

}  // namespace image_detail
}  // namespace raylane
