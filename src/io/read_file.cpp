// io: whole-file reads for the loaders (read_file.h).
#include "io/read_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

#include "core/error.h"

namespace raylane {

namespace {

/// Closes the descriptor on every exit path.
struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

[[noreturn]] void throw_read_error(const std::string& path, int error) {
    throw InputError(path + ": cannot read: " + std::generic_category().message(error));
}

}  // namespace

std::string read_file(const std::string& path) {
    FileDescriptor file;
    file.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (file.fd < 0) throw_read_error(path, errno);
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) throw_read_error(path, errno);
    if (S_ISDIR(info.st_mode)) throw_read_error(path, EISDIR);

    // Regular files: one read of the known size. Pipes and devices: grow as data arrives.
    std::string data;
    size_t size = 0;
    size_t capacity = S_ISREG(info.st_mode) ? static_cast<size_t>(info.st_size) + 1 : 65536;
    data.resize(capacity);
    for (;;) {
        if (size == data.size()) data.resize(data.size() * 2);
        ssize_t got = ::read(file.fd, data.data() + size, data.size() - size);
        if (got < 0) {
            if (errno == EINTR) continue;
            throw_read_error(path, errno);
        }
        if (got == 0) break;
        size += static_cast<size_t>(got);
    }
    data.resize(size);
    return data;
}

std::string quote_for_error(std::string_view text, size_t max_chars) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string out = "'";
    size_t n = text.size() < max_chars ? text.size() : max_chars;
    for (size_t i = 0; i < n; ++i) {
        auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
        } else {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    if (n < text.size()) out += "...";
    out += '\'';
    return out;
}

std::string file_name_of(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace raylane
