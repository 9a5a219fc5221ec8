// io: LineCursor (text_lines.h): lines ended by LF, CR LF and a CR alone, mixed in one text,
// and where the text after the last line given starts.
#include "io/text_lines.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

namespace raylane {
namespace {

std::vector<std::string> split_lines(std::string_view text) {
    std::vector<std::string> out;
    LineCursor cursor(text);
    for (std::string_view line; cursor.next(line);) out.emplace_back(line);
    return out;
}

using Lines = std::vector<std::string>;

TEST(LineCursor, EndsLinesAtLfCrlfAndCrAlone) {
    EXPECT_EQ(split_lines("a\nb\n"), (Lines{"a", "b"}));
    EXPECT_EQ(split_lines("a\r\nb\r\n"), (Lines{"a", "b"}));
    EXPECT_EQ(split_lines("a\rb\r"), (Lines{"a", "b"}));
    // mixed in one text; CR CR LF is an empty line between two ends
    EXPECT_EQ(split_lines("a\rb\nc\r\nd\r\r\ne"), (Lines{"a", "b", "c", "d", "", "e"}));
    // LF CR is two ends
    EXPECT_EQ(split_lines("a\n\rb"), (Lines{"a", "", "b"}));
}

TEST(LineCursor, KeepsALastLineWithoutAnEndAndStartsNoLineAfterTheLastEnd) {
    EXPECT_EQ(split_lines("a\nb"), (Lines{"a", "b"}));
    EXPECT_EQ(split_lines("a\r"), (Lines{"a"}));
    EXPECT_EQ(split_lines("\n"), (Lines{""}));
    EXPECT_EQ(split_lines("\r\n\r\n"), (Lines{"", ""}));
    EXPECT_EQ(split_lines(""), Lines{});
    EXPECT_EQ(split_lines(std::string_view()), Lines{});
}

TEST(LineCursor, TellsEachLinesEndAndWhereTheRestStarts) {
    const std::string_view text = "ply\rend\r\nbody\n";
    LineCursor cursor(text);
    std::string_view line;
    ASSERT_TRUE(cursor.next(line));
    EXPECT_EQ(line, "ply");
    EXPECT_EQ(cursor.line_end(), "\r");
    EXPECT_EQ(cursor.rest(), text.data() + 4);
    ASSERT_TRUE(cursor.next(line));
    EXPECT_EQ(line, "end");
    EXPECT_EQ(cursor.line_end(), "\r\n");
    EXPECT_EQ(cursor.rest(), text.data() + 9);
    ASSERT_TRUE(cursor.next(line));
    EXPECT_EQ(cursor.line_end(), "\n");
    EXPECT_FALSE(cursor.next(line));
    const std::string_view last = "x";
    LineCursor unended(last);
    ASSERT_TRUE(unended.next(line));
    EXPECT_EQ(unended.line_end(), "");
    EXPECT_EQ(unended.rest(), last.data() + 1);
}

TEST(LineCursor, SplitsAMegabyteOfCrOnlyLines) {
    std::string text;
    for (int i = 0; i < 100000; ++i) text += "v 1 2\r";
    LineCursor cursor(text);
    size_t count = 0;
    for (std::string_view line; cursor.next(line);) {
        ASSERT_EQ(line, "v 1 2") << count;
        ++count;
    }
    EXPECT_EQ(count, 100000u);
    EXPECT_EQ(cursor.rest(), text.data() + text.size());
}

}  // namespace
}  // namespace raylane
