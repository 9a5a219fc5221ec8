// io: gzip model files inflated into one block of memory (gzip_file.h).
#include "io/gzip_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <new>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace raylane {

namespace {

/// Compressed bytes read per read(2).
constexpr size_t chunk_bytes = size_t{64} << 10;
/// Output block of a gzip file whose size is not known (a pipe): grown as it fills.
constexpr size_t unknown_size_guess = size_t{1} << 20;
/// Deflate's largest expansion: 1032 output bytes per input byte (zlib's FAQ), which bounds
/// what the trailer's length field may claim.
constexpr uint64_t max_deflate_ratio = 1032;

size_t round_to_pages(size_t bytes) {
    const auto page = static_cast<size_t>(::sysconf(_SC_PAGESIZE));
    return std::max(page, (bytes + page - 1) / page * page);
}

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw InputError(path + ": " + reason);
}

/// The compressed file, read in chunks; closed on every exit path.
class GzipInput {
  public:
    explicit GzipInput(const std::string& path) : path_(path), chunk_(chunk_bytes) {
        fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd_ < 0) fail_read(errno);
    }
    GzipInput(const GzipInput&) = delete;
    GzipInput& operator=(const GzipInput&) = delete;
    ~GzipInput() { ::close(fd_); }

    /// The decompressed size the gzip trailer gives (its last 4 bytes, little endian, modulo
    /// 2^32), bounded by deflate's largest expansion of the file; 0 when the file is not a
    /// regular file or is too short to hold a trailer.
    uint64_t size_hint() const {
        struct stat info {};
        if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode) || info.st_size < 18) return 0;
        unsigned char trailer[4] = {};
        if (::pread(fd_, trailer, 4, info.st_size - 4) != 4) return 0;
        const uint64_t claimed = trailer[0] | uint64_t{trailer[1]} << 8 |
                                 uint64_t{trailer[2]} << 16 | uint64_t{trailer[3]} << 24;
        return std::min(claimed, static_cast<uint64_t>(info.st_size) * max_deflate_ratio);
    }

    /// Refills the stream's input when it is used up; false at the end of the file.
    bool refill(z_stream& z) {
        if (z.avail_in > 0) return true;
        for (;;) {
            const ssize_t got = ::read(fd_, chunk_.data(), chunk_.size());
            if (got < 0 && errno == EINTR) continue;
            if (got < 0) fail_read(errno);
            read_ += static_cast<uint64_t>(got);
            z.next_in = chunk_.data();
            z.avail_in = static_cast<uInt>(got);
            return got > 0;
        }
    }

    /// Compressed bytes the stream has consumed so far.
    uint64_t consumed(const z_stream& z) const { return read_ - z.avail_in; }

  private:
    [[noreturn]] void fail_read(int error) const {
        fail(path_, "cannot read: " + std::generic_category().message(error));
    }

    const std::string& path_;
    int fd_ = -1;
    std::vector<unsigned char> chunk_;
    uint64_t read_ = 0;
};

/// Anonymous memory for the decompressed bytes, grown by remapping its pages (mremap), so that
/// no byte is ever copied and no second block is ever held.
class InflatedBlock {
  public:
    explicit InflatedBlock(size_t capacity) { map(round_to_pages(capacity)); }
    InflatedBlock(const InflatedBlock&) = delete;
    InflatedBlock& operator=(const InflatedBlock&) = delete;
    ~InflatedBlock() {
        if (data_) ::munmap(data_, capacity_);
    }

    unsigned char* free_space() const { return static_cast<unsigned char*>(data_) + size_; }
    size_t free_bytes() const { return capacity_ - size_; }
    size_t size() const { return size_; }
    void add(size_t bytes) { size_ += bytes; }

    /// Twice the room, or up to `limit` bytes in all when that is less (but always more).
    void grow(size_t limit) {
        const size_t capacity =
            round_to_pages(std::max(capacity_ + 1, std::min(2 * capacity_, limit)));
        void* moved = ::mremap(data_, capacity_, capacity, MREMAP_MAYMOVE);
        if (moved == MAP_FAILED) throw std::bad_alloc();
        data_ = moved;
        capacity_ = capacity;
    }

    /// The bytes, read-only, their pages beyond the last given back.
    FileBytes release() {
        if (size_ == 0) return FileBytes();
        const size_t kept = round_to_pages(size_);
        if (kept < capacity_) ::munmap(static_cast<char*>(data_) + kept, capacity_ - kept);
        ::mprotect(data_, kept, PROT_READ);
        FileBytes bytes = FileBytes::adopt_mapping(static_cast<const char*>(data_), size_);
        data_ = nullptr;
        return bytes;
    }

  private:
    void map(size_t capacity) {
        data_ =
            ::mmap(nullptr, capacity, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (data_ == MAP_FAILED) {
            data_ = nullptr;
            throw std::bad_alloc();
        }
        capacity_ = capacity;
    }

    void* data_ = nullptr;
    size_t size_ = 0;
    size_t capacity_ = 0;
};

/// zlib's inflate state for gzip framing (window bits 15 + 16); ended on every exit path.
struct GzipInflater {
    z_stream z{};
    GzipInflater() {
        if (inflateInit2(&z, 15 + 16) != Z_OK) throw std::bad_alloc();
    }
    GzipInflater(const GzipInflater&) = delete;
    GzipInflater& operator=(const GzipInflater&) = delete;
    ~GzipInflater() { inflateEnd(&z); }
};

bool starts_like_gzip(const z_stream& z) {
    return z.avail_in > 0 && z.next_in[0] == 0x1f && (z.avail_in < 2 || z.next_in[1] == 0x8b);
}

/// One call of inflate into the free space of `out`, which is grown first (up to `limit`
/// bytes) when full.
int inflate_some(z_stream& z, InflatedBlock& out, size_t limit) {
    if (out.free_bytes() == 0) out.grow(limit);
    z.next_out = out.free_space();
    z.avail_out = static_cast<uInt>(std::min<size_t>(out.free_bytes(), UINT_MAX));
    const uInt room = z.avail_out;
    const int status = inflate(&z, Z_NO_FLUSH);
    out.add(room - z.avail_out);
    return status;
}

[[noreturn]] void refuse_size(const std::string& path, size_t max_bytes) {
    fail(path,
         "decompresses to more than " +
             (max_bytes == max_inflated_bytes ? std::string("2^31") : std::to_string(max_bytes)) +
             " bytes, over the limit for a mesh");
}

}  // namespace

bool has_gzip_extension(const std::string& path) {
    const size_t n = path.size();
    return n >= 3 && path[n - 3] == '.' && (path[n - 2] | 0x20) == 'g' &&
           (path[n - 1] | 0x20) == 'z';
}

FileBytes inflate_file(const std::string& path, size_t max_bytes) {
    GzipInput input(path);
    GzipInflater inflater;
    z_stream& z = inflater.z;
    if (!input.refill(z)) fail(path, "is empty");
    if (!starts_like_gzip(z)) fail(path, "is not gzip data (it does not start with 1f 8b)");
    const uint64_t hint = std::min<uint64_t>(input.size_hint(), max_bytes);
    InflatedBlock out(hint > 0 ? static_cast<size_t>(hint) + 1 : unknown_size_guess);
    bool member_ended = false;
    for (;;) {
        // (inflate may still have output to give when all input is in: call it until it ends)
        const bool more_input = input.refill(z);
        if (member_ended) {  // after a whole member: the next member, or the end of the file
            if (!more_input) break;
            if (!starts_like_gzip(z)) {
                fail(path, "data after the end of the gzip data at compressed byte " +
                               std::to_string(input.consumed(z)));
            }
            inflateReset(&z);
            member_ended = false;
        }
        const int status = inflate_some(z, out, max_bytes + 1);
        if (out.size() > max_bytes) refuse_size(path, max_bytes);
        if (status == Z_STREAM_END) {
            member_ended = true;
        } else if (status == Z_BUF_ERROR && !more_input) {  // (there was room for output)
            fail(path, "gzip data ends early, after " + std::to_string(input.consumed(z)) +
                           " compressed bytes");
        } else if (status != Z_OK && status != Z_BUF_ERROR) {
            fail(path, "gzip data is corrupt at compressed byte " +
                           std::to_string(input.consumed(z)) + " (zlib: " +
                           (z.msg ? std::string(z.msg) : "error " + std::to_string(status)) + ")");
        }
    }
    return out.release();
}

FileBytes read_model_file(const std::string& path) {
    return has_gzip_extension(path) ? inflate_file(path) : map_file(path);
}

}  // namespace raylane
