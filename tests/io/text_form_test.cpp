// io: the first-bytes checks of model files (text_form.h): where UTF-16 and binary data begin to
// be refused, and what stays for the readers. The readers' own messages are tested in
// load_obj_test.cpp and load_ply_test.cpp.
#include "io/text_form.h"

#include <gtest/gtest.h>

#include <string>

#include "support/input_error.h"

namespace raylane {
namespace {

/// `ascii` as UTF-16 without a byte order mark, little or big endian.
std::string utf16_of(std::string_view ascii, bool big_endian) {
    std::string out;
    for (char c : ascii) {
        out += big_endian ? std::string{'\0', c} : std::string{c, '\0'};
    }
    return out;
}

TEST(TextForm, RefusesUtf16WithAMarkOrByItsNulBytes) {
    const std::string utf16 = "m.obj: is UTF-16 text; save it as UTF-8 or ASCII";
    const std::string text = "v 0 0 0\r\nv 1 0 0\r\n";
    EXPECT_EQ(test::input_error_of([&] { refuse_utf16("\xFF\xFEv", "m.obj"); }), utf16);
    EXPECT_EQ(test::input_error_of([&] { refuse_utf16("\xFE\xFF", "m.obj"); }), utf16);
    EXPECT_EQ(test::input_error_of([&] { refuse_utf16(utf16_of(text, false), "m.obj"); }), utf16);
    EXPECT_EQ(test::input_error_of([&] { refuse_utf16(utf16_of(text, true), "m.obj"); }), utf16);
    // 3 of 4 pairs: refused; fewer: not UTF-16 (left to the binary check)
    EXPECT_EQ(test::input_error_of([&] { refuse_utf16(utf16_of("abc", false) + "de", "m.obj"); }),
              utf16);
    EXPECT_NO_THROW(refuse_utf16(utf16_of("ab", false) + "cdef", "m.obj"));
    EXPECT_NO_THROW(refuse_utf16(text, "m.obj"));
}

TEST(TextForm, RefusesANulOrSixteenControlBytesInTheFirstKib) {
    std::string bytes = "v 0 0 0\n";
    bytes += std::string(15, '\x01');
    EXPECT_NO_THROW(refuse_binary(bytes, "m.obj", "OBJ"));
    bytes += '\x02';
    EXPECT_EQ(test::input_error_of([&] { refuse_binary(bytes, "m.obj", "OBJ"); }),
              "m.obj: is a binary file, not a text OBJ (byte 23 is 0x02)");
    EXPECT_EQ(test::input_error_of([&] { refuse_binary(std::string("v 0\0", 4), "m.obj", "OBJ"); }),
              "m.obj: is a binary file, not a text OBJ (byte 3 is 0x00)");
    // only the first KiB is looked at
    const std::string late = std::string(1024, '#') + std::string(1, '\0');
    EXPECT_NO_THROW(refuse_binary(late, "m.obj", "OBJ"));
    // tabs, line ends, VT, FF and UTF-8 are text
    EXPECT_NO_THROW(
        refuse_non_text("# caf\xC3\xA9\tv\v\f\r\n\xEF\xBB\xBFv 0 0 0\n", "m.obj", "OBJ"));
}

TEST(TextForm, RefusesGzipDataUnderAPlainName) {
    EXPECT_EQ(test::input_error_of([] { refuse_gzip("\x1F\x8B\x08", "models/m.obj"); }),
              "models/m.obj: is gzip-compressed; name it m.obj.gz to read it");
    EXPECT_NO_THROW(refuse_gzip("\x1F", "m.obj"));
}

}  // namespace
}  // namespace raylane
