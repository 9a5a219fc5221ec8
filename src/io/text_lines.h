// io: the lines of a text file, ended by LF, CR LF or a CR alone, for the text readers
// (load_obj.cpp, the PLY header in ply_header.cpp and ASCII PLY bodies in load_ply.cpp).
#pragma once

#include <cstddef>
#include <cstring>
#include <string_view>

namespace raylane {

/// Walks the lines of a text in order. A line ends at LF (Unix), CR LF (Windows) or a CR alone
/// (classic Mac OS), and one file may mix them, as the common OBJ and PLY readers take it. A
/// last line without an end is a line too; an end at the very end of the text starts no other.
/// The next LF and the next CR are each found once (memchr) and kept until the walk passes
/// them, so a file of CR-only lines, or of LF-only ones, is scanned about once.
class LineCursor {
  public:
    explicit LineCursor(std::string_view text)
        : cur_(text.data()),
          end_(text.data() + text.size()),
          next_lf_(find(cur_, '\n')),
          next_cr_(find(cur_, '\r')) {}

    /// The next line, without its end, into `line`; false when the text is used up.
    bool next(std::string_view& line) {
        if (cur_ == end_) return false;
        if (next_lf_ < cur_) next_lf_ = find(cur_, '\n');
        if (next_cr_ < cur_) next_cr_ = find(cur_, '\r');
        const char* stop = next_lf_ < next_cr_ ? next_lf_ : next_cr_;
        line = std::string_view(cur_, static_cast<size_t>(stop - cur_));
        line_end_ = std::string_view(stop, 0);
        if (stop < end_) {
            const bool crlf = *stop == '\r' && stop + 1 < end_ && stop[1] == '\n';
            line_end_ = std::string_view(stop, crlf ? 2 : 1);
        }
        cur_ = stop + line_end_.size();
        return true;
    }

    /// The end of the line `next` gave last: "\n", "\r\n", "\r", or "" for the text's last line.
    std::string_view line_end() const { return line_end_; }

    /// The first byte after the line `next` gave last (the text's end when it was the last).
    const char* rest() const { return cur_; }

  private:
    /// The first `c` at or after `from`, else end_.
    const char* find(const char* from, char c) const {
        if (from == end_) return end_;  // (memchr may not be given a null pointer)
        const void* hit = std::memchr(from, c, static_cast<size_t>(end_ - from));
        return hit ? static_cast<const char*>(hit) : end_;
    }

    const char* cur_;
    const char* end_;
    const char* next_lf_;  ///< the first LF at or after cur_, else end_ (found again when passed)
    const char* next_cr_;  ///< the same for CR
    std::string_view line_end_;
};

}  // namespace raylane
