// image: zlib_compress (deflate.h) decoded again by stb_image's inflater, its Adler-32 against
// a plain one, the same bytes for any thread count, and a PNG written and read back.
#include "image/deflate.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "image/film.h"
#include "io/read_file.h"
#include "io/stb_image.h"

namespace raylane {
namespace {

/// Adler-32 with the modulo after every byte (RFC 1950's definition, no shortcut).
uint32_t plain_adler32(const std::vector<uint8_t>& data) {
    uint32_t a = 1, b = 0;
    for (uint8_t x : data) {
        a = (a + x) % 65521;
        b = (b + a) % 65521;
    }
    return b << 16 | a;
}

/// stb_image's inflater on a zlib stream (it checks the header, not the checksum).
std::vector<uint8_t> inflate(const std::vector<uint8_t>& z) {
    int n = 0;
    char* p = stbi_zlib_decode_malloc(reinterpret_cast<const char*>(z.data()),
                                      static_cast<int>(z.size()), &n);
    if (!p) return {0xde, 0xad};  // not the input of any case below
    std::vector<uint8_t> out(p, p + n);
    stb_free(p);
    return out;
}

void expect_round_trip(const std::vector<uint8_t>& data, const std::string& what) {
    const std::vector<uint8_t> z = zlib_compress(data);
    ASSERT_GE(z.size(), 8u) << what;
    EXPECT_EQ(z[0], 0x78) << what;
    EXPECT_EQ((z[0] << 8 | z[1]) % 31, 0) << what;
    EXPECT_TRUE(inflate(z) == data) << what;
    const uint32_t trailer = uint32_t(z[z.size() - 4]) << 24 | uint32_t(z[z.size() - 3]) << 16 |
                             uint32_t(z[z.size() - 2]) << 8 | z[z.size() - 1];
    EXPECT_EQ(trailer, plain_adler32(data)) << what;
    EXPECT_EQ(adler32(data), plain_adler32(data)) << what;
}

/// Rows like a filtered image's (5761 bytes): most repeat the row above, the others are runs
/// of a few values.
std::vector<uint8_t> image_like(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> d(n);
    const size_t row = 5761;
    for (size_t start = 0; start < n; start += row) {
        const bool repeat = start >= row && rng() % 4 != 0;
        uint8_t value = 0;
        for (size_t i = start; i < std::min(n, start + row); ++i) {
            if (rng() % 16 == 0) value = static_cast<uint8_t>(rng() % 7);
            d[i] = repeat ? d[i - row] : value;
        }
    }
    return d;
}

TEST(ZlibCompress, InflatesBackToTheData) {
    expect_round_trip({}, "empty");
    expect_round_trip({42}, "one byte");
    expect_round_trip({1, 2, 3}, "three bytes");
    expect_round_trip({7, 7, 7, 7, 7, 7, 7, 7, 7}, "a run shorter than a word");
    expect_round_trip(std::vector<uint8_t>(1 << 20, 0), "1 MiB of zeros: matches of 258");
    const size_t chunk = size_t(256) << 10;
    for (size_t n : {chunk - 1, chunk, chunk + 1, 3 * chunk + 12345})
        expect_round_trip(image_like(n, static_cast<uint32_t>(n)),
                          "image-like " + std::to_string(n));
    // incompressible: stored blocks (65535 bytes each, and a short last one) in some chunks
    std::mt19937 rng(5);
    std::vector<uint8_t> noise(chunk + 70000);
    for (uint8_t& x : noise) x = static_cast<uint8_t>(rng());
    expect_round_trip(noise, "noise");
    const std::vector<uint8_t> z = zlib_compress(noise);
    EXPECT_LE(z.size(), noise.size() + 5 * (noise.size() / 65535 + 3) + 4 * 3 + 8);
    // a block of noise in zeros repeated at the farthest distance deflate allows (32768: one
    // match) and one beyond (32769: 300 more literals); its 4-byte hashes meet no other position
    size_t size[2];
    for (size_t k = 0; k < 2; ++k) {
        const size_t d = 32768 + k;
        std::vector<uint8_t> far(100000, 0);
        for (size_t i = 0; i < 300; ++i) far[1000 + i] = far[1000 + d + i] = uint8_t(rng() | 1u);
        expect_round_trip(far, "a repeat at distance " + std::to_string(d));
        size[k] = zlib_compress(far).size();
    }
    EXPECT_GT(size[1], size[0] + 250);
}

TEST(ZlibCompress, CompressesRepeatsAndIsTheSameForAnyThreadCount) {
    const std::vector<uint8_t> data = image_like(3 << 20, 11);
    const std::vector<uint8_t> z = zlib_compress(data);
    EXPECT_LT(z.size(), data.size() / 4);  // the rows repeat: it must find the matches
    std::vector<uint8_t> one;
    tbb::task_arena(1).execute([&] { one = zlib_compress(data); });
    EXPECT_TRUE(one == z);
}

TEST(WritePng, ReadsBackAsTheFilmsBytes) {
    Film film = make_film(301, 67);
    for (int y = 0; y < film.height; ++y)
        for (int x = 0; x < film.width; ++x)
            film.at(x, y) = vec3(float(x) / 300.0f, float(y % 9) / 8.0f, x > 150 ? 0.25f : 0.75f);
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("raylane_deflate_test_" + std::to_string(::getpid()) + ".png"))
                                 .string();
    for (Encoding e : {Encoding::srgb, Encoding::linear}) {
        write_png(path, film, e);
        const ImageBytes want = encode_film(film, e);
        const std::string png = read_file(path);
        int w = 0, h = 0, channels = 0;
        stbi_uc* got = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                                             static_cast<int>(png.size()), &w, &h, &channels, 3);
        ASSERT_NE(got, nullptr) << stbi_failure_reason();
        EXPECT_EQ(w, film.width);
        EXPECT_EQ(h, film.height);
        EXPECT_TRUE(std::equal(want.begin(), want.end(), got));
        stb_free(got);
    }
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace raylane
