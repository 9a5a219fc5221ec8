// image: the PFM writer and reader (pfm.h): the reader takes back what the writer wrote, bit for
// bit, and turns down any other file.
#include "image/pfm.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "support/temp_dir.h"

namespace raylane {
namespace {

/// A film of distinct values, negative and fractional ones among them.
Film pfm_test_film(int w, int h) {
    Film film = make_film(w, h);
    for (size_t i = 0; i < film.pixels.size(); ++i)
        film.pixels[i] = vec3(float(i), 0.5f * float(i), -1.0f / float(i + 1));
    return film;
}

TEST(Pfm, ReadsBackWhatWritePfmWrote) {
    const test::TempDir dir("raylane_pfm_");
    const std::string file = (dir.path / "film.pfm").string();
    const Film film = pfm_test_film(5, 3);
    write_pfm(file, film);
    std::ifstream in(file, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_EQ(bytes.rfind("PF\n5 3\n-1.0\n", 0), 0u);  // bottom row first, after the header
    EXPECT_EQ(bytes.size(), 12u + 5u * 3u * sizeof(vec3));
    const std::optional<Film> back = read_pfm(file, 5, 3);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->width, 5);
    EXPECT_EQ(back->height, 3);
    EXPECT_EQ(back->pixels, film.pixels);
    EXPECT_FALSE(std::filesystem::exists(file + ".partial"));
}

TEST(Pfm, OtherSizesAndDamagedFilesAreNotRead) {
    const test::TempDir dir("raylane_pfm_");
    const std::string file = (dir.path / "film.pfm").string();
    write_pfm(file, pfm_test_film(5, 3));
    EXPECT_FALSE(read_pfm(file, 5, 4).has_value());
    EXPECT_FALSE(read_pfm(file, 3, 5).has_value());
    EXPECT_FALSE(read_pfm((dir.path / "none.pfm").string(), 5, 3).has_value());
    std::filesystem::resize_file(file, std::filesystem::file_size(file) - 4);  // truncated
    EXPECT_FALSE(read_pfm(file, 5, 3).has_value());
    write_pfm(file, pfm_test_film(5, 3));
    std::ofstream(file, std::ios::app | std::ios::binary) << "x";  // trailing bytes
    EXPECT_FALSE(read_pfm(file, 5, 3).has_value());
    const std::string floats(5 * 3 * sizeof(vec3), '\0');
    test::write_bytes(dir.path / "positive.pfm", "PF\n5 3\n1.0\n" + floats);  // big-endian
    EXPECT_FALSE(read_pfm((dir.path / "positive.pfm").string(), 5, 3).has_value());
    test::write_bytes(dir.path / "grey.pfm", "Pf\n5 3\n-1.0\n" + floats);  // one channel
    EXPECT_FALSE(read_pfm((dir.path / "grey.pfm").string(), 5, 3).has_value());
    test::write_bytes(dir.path / "ok.pfm", "PF\n5 3\n-1.0\n" + floats);
    EXPECT_TRUE(read_pfm((dir.path / "ok.pfm").string(), 5, 3).has_value());
}

}  // namespace
}  // namespace raylane
