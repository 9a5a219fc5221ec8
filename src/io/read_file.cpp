// io: whole-file reads for the loaders (read_file.h).
#include "io/read_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>
#include <utility>

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

FileBytes::FileBytes(FileBytes&& other) noexcept
    : mapped_(std::exchange(other.mapped_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      data_(std::move(other.data_)) {
    other.data_.clear();
}

FileBytes& FileBytes::operator=(FileBytes&& other) noexcept {
    if (this != &other) {
        if (mapped_) ::munmap(const_cast<char*>(mapped_), size_);
        mapped_ = std::exchange(other.mapped_, nullptr);
        size_ = std::exchange(other.size_, 0);
        data_ = std::move(other.data_);
        other.data_.clear();
    }
    return *this;
}

FileBytes::~FileBytes() {
    if (mapped_) ::munmap(const_cast<char*>(mapped_), size_);
}

FileBytes FileBytes::adopt_mapping(const char* mapping, size_t size) {
    FileBytes bytes;
    bytes.mapped_ = mapping;
    bytes.size_ = size;
    return bytes;
}

FileBytes map_file(const std::string& path) {
    FileDescriptor file;
    file.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (file.fd < 0) throw_read_error(path, errno);
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) throw_read_error(path, errno);
    if (S_ISDIR(info.st_mode)) throw_read_error(path, EISDIR);

    FileBytes bytes;
    // Regular files: mapped, every page at once (MAP_POPULATE). A file the kernel will not map
    // is read like the rest.
    if (S_ISREG(info.st_mode) && info.st_size > 0) {
        const auto size = static_cast<size_t>(info.st_size);
        void* p = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
        if (p != MAP_FAILED) {
            bytes.mapped_ = static_cast<const char*>(p);
            bytes.size_ = size;
            return bytes;
        }
    }
    // Pipes and devices: grow as data arrives.
    std::string& data = bytes.data_;
    size_t size = 0;
    data.resize(S_ISREG(info.st_mode) ? static_cast<size_t>(info.st_size) + 1 : 65536);
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
    return bytes;
}

std::string read_file(const std::string& path) {
    FileBytes bytes = map_file(path);
    if (!bytes.mapped_) return std::move(bytes.data_);
    return std::string(bytes.view());
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
