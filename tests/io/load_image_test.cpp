// tests for io/load_image.cpp: the shipped textures and environment maps, small PNG / HDR files
// written here at run time (stb_image_write, and a minimal PNG writer for 16-bit and patched
// headers), encodings, and hostile files (empty, garbage, truncated, huge headers, directories).
#include "io/load_image.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/read_file.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

const std::string shared_dir = RAYLANE_SHARED_DIR;

/// A directory for this process's fixtures, removed at exit.
struct ProcessTempDir {
    fs::path path = fs::temp_directory_path() / ("raylane_load_image_" + std::to_string(getpid()));
    ProcessTempDir() { fs::create_directories(path); }
    ~ProcessTempDir() {
        std::error_code error;
        fs::remove_all(path, error);
    }
};
std::string temp_file(const std::string& name) {
    static ProcessTempDir dir;
    return (dir.path / name).string();
}

/// Writes an 8-bit PNG with stb_image_write; pixels row 0 = top, `channels` bytes per pixel.
std::string write_png(const std::string& name, int width, int height, int channels,
                      const std::vector<uint8_t>& pixels) {
    const std::string path = temp_file(name);
    EXPECT_NE(
        stbi_write_png(path.c_str(), width, height, channels, pixels.data(), width * channels), 0);
    return path;
}

/// PNG bytes from stb_image_write, for the tests that patch or cut them.
std::string png_bytes(int width, int height, int channels, const std::vector<uint8_t>& pixels) {
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<size_t>(size));
    };
    EXPECT_NE(stbi_write_png_to_func(append, &bytes, width, height, channels, pixels.data(),
                                     width * channels),
              0);
    return bytes;
}

std::vector<uint8_t> random_bytes(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> bytes(n);
    for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    return bytes;
}

// a minimal PNG writer: any header, stored (uncompressed) deflate blocks ---------------------

uint32_t crc32(std::string_view bytes) {
    uint32_t crc = 0xffffffffu;
    for (char c : bytes) {
        crc ^= static_cast<uint8_t>(c);
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void put32(std::string& out, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xff);
}

std::string chunk(const std::string& type, const std::string& data) {
    std::string out;
    put32(out, static_cast<uint32_t>(data.size()));
    const std::string body = type + data;
    out += body;
    put32(out, crc32(body));
    return out;
}

/// A PNG of the given header whose IDAT holds `scanlines` (filter byte + row bytes, each row).
std::string handmade_png(uint32_t width, uint32_t height, int bit_depth, int color_type,
                         const std::string& scanlines) {
    std::string ihdr;
    put32(ihdr, width);
    put32(ihdr, height);
    ihdr += static_cast<char>(bit_depth);
    ihdr += static_cast<char>(color_type);
    ihdr += std::string(3, '\0');  // compression, filter, interlace
    std::string zlib = "\x78\x01";
    size_t pos = 0;
    do {
        const size_t n = std::min<size_t>(65535, scanlines.size() - pos);
        const bool last = pos + n == scanlines.size();
        zlib += static_cast<char>(last ? 1 : 0);
        zlib += static_cast<char>(n & 0xff);
        zlib += static_cast<char>(n >> 8);
        zlib += static_cast<char>(~n & 0xff);
        zlib += static_cast<char>((~n >> 8) & 0xff);
        zlib += scanlines.substr(pos, n);
        pos += n;
    } while (pos < scanlines.size());
    uint32_t a = 1, b = 0;  // Adler-32
    for (char c : scanlines) {
        a = (a + static_cast<uint8_t>(c)) % 65521u;
        b = (b + a) % 65521u;
    }
    put32(zlib, b << 16 | a);
    return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", zlib) +
           chunk("IEND", "");
}

// errors ------------------------------------------------------------------------------------

/// One line, starting with "name: ", containing `part`.
void expect_error(const std::string& message, const std::string& name, const std::string& part) {
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

void expect_file_error(const std::string& path, const std::string& part) {
    expect_error(test::input_error_of([&] { load_texture(path); }), path, part);
}

void expect_memory_error(std::string_view bytes, const std::string& part) {
    expect_error(test::input_error_of([&] { load_texture_from_memory(bytes, "bytes.png"); }),
                 "bytes.png", part);
}

// the shipped images ------------------------------------------------------------------------

struct ShippedImage {
    std::string path;  ///< under shared/
    int width, height;
    bool hdr;
};

// sizes from shared/textures/README.md and shared/models/README.md
const ShippedImage shipped_images[] = {
    {"textures/apple_texture.jpg", 4096, 4096, false},
    {"textures/envMap1.jpg", 2048, 1024, false},
    {"textures/envMap2.jpg", 3750, 1875, false},
    {"textures/envMap3.jpg", 2400, 1200, false},
    {"textures/house_texture.jpg", 1024, 1024, false},
    {"textures/rosewood_veneer1_diff_1k.jpg", 1024, 1024, false},
    {"textures/Tiles074_1K_Color.png", 1024, 1024, false},
    {"textures/env/venice_sunset_1k.png", 1024, 512, false},
    {"textures/env/venice_sunset_1k.hdr", 1024, 512, true},
    {"textures/env/studio_1k.hdr", 1024, 512, true},
    {"models/apple/food_apple_01_diff_1k.png", 1024, 1024, false},
    {"models/apple/food_apple_01_nor_gl_1k.png", 1024, 1024, false},
};

TEST(LoadTexture, ReadsEveryShippedImageAtItsDocumentedSize) {
    for (const ShippedImage& image : shipped_images) {
        SCOPED_TRACE(image.path);
        const std::string path = shared_dir + "/" + image.path;
        const Texture t = load_texture(path);
        EXPECT_EQ(t.kind, TextureKind::image);
        EXPECT_EQ(t.source, path);
        EXPECT_EQ(t.width, image.width);
        EXPECT_EQ(t.height, image.height);
        ASSERT_EQ(t.texels.size(), static_cast<size_t>(image.width) * image.height * 3);
        bool finite = true;
        float lo = INFINITY, hi = -INFINITY;
        for (float x : t.texels) {
            finite = finite && std::isfinite(x);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
        EXPECT_TRUE(finite);
        EXPECT_GE(lo, 0.0f);
        EXPECT_GT(hi - lo, 0.2f) << "an image, not a constant";
        if (image.hdr) {
            EXPECT_GT(hi, 1.0f) << "an HDR environment has texels brighter than 1";
        } else {
            EXPECT_LE(hi, 1.0f);
        }
    }
}

TEST(LoadTexture, ReadsThe8BitVeniceSunsetAsTheClippedSrgbEncodedHdr) {
    // venice_sunset_1k.png is venice_sunset_1k.hdr clipped at 1 and sRGB-encoded (models/README):
    // decoded, it must match the HDR texel for texel up to 8-bit quantisation (same row order).
    const Texture hdr = load_texture(shared_dir + "/textures/env/venice_sunset_1k.hdr");
    const Texture ldr =
        load_texture(shared_dir + "/textures/env/venice_sunset_1k.png", ImageEncoding::srgb);
    ASSERT_EQ(hdr.texels.size(), ldr.texels.size());
    double sum = 0.0;
    for (size_t i = 0; i < hdr.texels.size(); ++i)
        sum += std::fabs(std::min(hdr.texels[i], 1.0f) - ldr.texels[i]);
    const double mean = sum / static_cast<double>(hdr.texels.size());
    EXPECT_LT(mean, 0.01);
    // the same comparison against the image turned upside down fails: rows are in file order
    double flipped = 0.0;
    const size_t row = static_cast<size_t>(hdr.width) * 3;
    for (size_t y = 0; y < static_cast<size_t>(hdr.height); ++y)
        for (size_t x = 0; x < row; ++x)
            flipped += std::fabs(std::min(hdr.texels[y * row + x], 1.0f) -
                                 ldr.texels[(static_cast<size_t>(hdr.height) - 1 - y) * row + x]);
    EXPECT_GT(flipped / static_cast<double>(hdr.texels.size()), 10 * mean);
}

// small fixtures ----------------------------------------------------------------------------

TEST(LoadTexture, KeepsRowOrderAndDividesBy255) {
    // 3 x 2 RGB, every byte different; row 0 of the file is the top row
    std::vector<uint8_t> pixels(3 * 2 * 3);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<uint8_t>(7 + 13 * i);
    const std::string path = write_png("rgb_3x2.png", 3, 2, 3, pixels);
    const Texture t = load_texture(path);
    ASSERT_EQ(t.width, 3);
    ASSERT_EQ(t.height, 2);
    ASSERT_EQ(t.texels.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_EQ(t.texels[i], static_cast<float>(pixels[i]) / 255.0f) << i;
    EXPECT_EQ(t.filter, Texture{}.filter);
    EXPECT_EQ(t.repeat, Texture{}.repeat);
}

TEST(LoadTexture, ReplicatesGreyAndDropsAlpha) {
    const std::vector<uint8_t> grey = {0, 64, 128, 255};
    const std::vector<uint8_t> grey_alpha = {10, 0, 20, 255, 30, 128, 40, 7};
    const std::vector<uint8_t> rgba = {1, 2, 3, 0, 4, 5, 6, 255, 7, 8, 9, 100, 250, 251, 252, 1};
    struct Case {
        std::string name;
        int channels;
        const std::vector<uint8_t>& pixels;
    };
    for (const Case& c : {Case{"grey.png", 1, grey}, Case{"grey_alpha.png", 2, grey_alpha},
                          Case{"rgba.png", 4, rgba}}) {
        SCOPED_TRACE(c.name);
        const Texture t = load_texture(write_png(c.name, 2, 2, c.channels, c.pixels));
        ASSERT_EQ(t.texels.size(), 2u * 2u * 3u);
        for (size_t p = 0; p < 4; ++p) {
            for (size_t k = 0; k < 3; ++k) {
                // grey: the one value in all three; RGBA: the first three bytes, never scaled by
                // alpha (a texel with alpha 0 keeps its colour)
                const size_t source = c.channels < 3 ? p * c.pixels.size() / 4 : p * 4 + k;
                EXPECT_EQ(t.texels[p * 3 + k], static_cast<float>(c.pixels[source]) / 255.0f);
            }
        }
    }
}

TEST(LoadTexture, DecodesSrgbWhenAsked) {
    const std::vector<uint8_t> grey = {0, 10, 128, 255};
    const std::string path = write_png("srgb.png", 4, 1, 1, grey);
    const Texture linear = load_texture(path, ImageEncoding::linear);
    const Texture srgb = load_texture(path, ImageEncoding::srgb);
    for (size_t i = 0; i < grey.size(); ++i) {
        const double c = grey[i] / 255.0;
        const double expected = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(srgb.texels[i * 3], expected, 1e-7) << int{grey[i]};
        EXPECT_EQ(linear.texels[i * 3], static_cast<float>(grey[i]) / 255.0f);
    }
    // 128 / 255 ~ 0.5 decodes to about 0.2159 (the familiar "50 % grey is 21 % linear")
    EXPECT_NEAR(srgb.texels[2 * 3], 0.21586, 1e-5);
    EXPECT_EQ(srgb.texels[0], 0.0f);
    EXPECT_EQ(srgb.texels[3 * 3], 1.0f);
    EXPECT_EQ(srgb_to_linear(1.0f), 1.0f);
}

TEST(LoadTexture, Reads16BitPngsWithSixteenBits) {
    // 2 x 1 RGB, 16 bits a sample, big-endian
    const uint16_t samples[6] = {0, 1, 0x8000, 0xffff, 0x1234, 0xfedc};
    std::string scanline(1, '\0');  // filter: none
    for (uint16_t s : samples) {
        scanline += static_cast<char>(s >> 8);
        scanline += static_cast<char>(s & 0xff);
    }
    const std::string path = temp_file("sixteen.png");
    test::write_bytes(path, handmade_png(2, 1, 16, 2, scanline));
    const Texture t = load_texture(path);
    ASSERT_EQ(t.texels.size(), 6u);
    for (int i = 0; i < 6; ++i)
        EXPECT_EQ(t.texels[i], static_cast<float>(samples[i]) / 65535.0f) << i;
    const Texture srgb = load_texture(path, ImageEncoding::srgb);
    EXPECT_EQ(srgb.texels[2], srgb_to_linear(static_cast<float>(0x8000) / 65535.0f));
}

TEST(LoadTexture, ReadsRadianceHdrAsLinearFloats) {
    // exact in RGBE: each component a multiple of 2^(e - 8), e the exponent of its pixel's largest
    const std::vector<float> texels = {4.0f,   0.25f,  1.0f, 0.0f, 2.0f,  3.0f,   8.0f, 0.5f,
                                       0.125f, 100.0f, 1.5f, 6.0f, 0.75f, 40.0f,  2.5f, 1.0f,
                                       9.0f,   12.0f,  0.0f, 0.0f, 0.0f,  200.0f, 8.0f, 64.0f};
    for (int width : {8, 2}) {  // 8: run-length scanlines; 2: flat pixels
        SCOPED_TRACE(width);
        const int height = 8 / width;
        const std::string path = temp_file("exact_" + std::to_string(width) + ".hdr");
        ASSERT_NE(stbi_write_hdr(path.c_str(), width, height, 3, texels.data()), 0);
        for (ImageEncoding encoding : {ImageEncoding::linear, ImageEncoding::srgb}) {
            const Texture t = load_texture(path, encoding);
            EXPECT_EQ(t.width, width);
            EXPECT_EQ(t.height, height);
            EXPECT_EQ(t.texels, texels);  // exact, and the encoding is ignored
        }
    }
}

TEST(MakeChecker, MakesAProceduralTexture) {
    const Texture t = make_checker(vec3(1, 0, 0), vec3(0, 0, 1), 4.0f);
    EXPECT_EQ(t.kind, TextureKind::checker);
    EXPECT_EQ(t.source, "checker");
    EXPECT_EQ(t.color_a, vec3(1, 0, 0));
    EXPECT_EQ(t.color_b, vec3(0, 0, 1));
    EXPECT_EQ(t.checks, 4.0f);
    EXPECT_TRUE(t.texels.empty());
}

// hostile and broken files -------------------------------------------------------------------

TEST(LoadTexture, RejectsAMissingFileNamingIt) {
    const std::string path = temp_file("no_such_image.png");
    expect_file_error(path, "No such file");
}

TEST(LoadTexture, RejectsADirectory) {
    const std::string path = temp_file("a_directory.png");
    fs::create_directories(path);
    expect_file_error(path, "directory");
}

TEST(LoadTexture, RejectsADeviceWithoutReadingIt) {
    if (!fs::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero";
    expect_file_error("/dev/zero", "not a regular file");  // reading it would never end
}

TEST(LoadTexture, RejectsAnEmptyFile) {
    const std::string path = temp_file("empty.png");
    test::write_bytes(path, "");
    expect_file_error(path, "empty file");
}

TEST(LoadTexture, RejectsBytesThatAreNoImage) {
    const std::string path = temp_file("garbage.png");
    const std::vector<uint8_t> noise = random_bytes(3000, 1);
    test::write_bytes(path, std::string(noise.begin(), noise.end()));
    expect_file_error(path, "not a PNG, JPEG or Radiance HDR image");
    expect_memory_error("just some text\nnot an image at all\n", "not a PNG, JPEG or Radiance");
    expect_memory_error("GIF89a\x01\x00\x01\x00\x00\x00\x00", "not a PNG, JPEG or Radiance");
    expect_memory_error("BM this would be a bitmap", "not a PNG, JPEG or Radiance");
}

TEST(LoadTexture, RejectsTruncatedPngs) {
    const std::vector<uint8_t> noise = random_bytes(64 * 64 * 3, 2);  // incompressible
    const std::string full = png_bytes(64, 64, 3, noise);
    ASSERT_GT(full.size(), 64u * 64u * 3u);
    EXPECT_EQ(load_texture_from_memory(full, "full.png").width, 64);
    // (a cut inside the last 4 bytes, IEND's CRC, leaves the whole image and is accepted)
    for (size_t keep : {size_t{8}, size_t{20}, size_t{33}, size_t{60}, full.size() / 2,
                        full.size() - 13, full.size() - 12}) {
        SCOPED_TRACE(keep);
        const std::string path = temp_file("cut_" + std::to_string(keep) + ".png");
        test::write_bytes(path, std::string_view(full).substr(0, keep));
        expect_file_error(path, "");
    }
    const std::string real = read_file(shared_dir + "/textures/Tiles074_1K_Color.png");
    expect_memory_error(std::string_view(real).substr(0, real.size() / 2), "");
}

std::string jpeg_bytes(int width, int height, const std::vector<uint8_t>& pixels) {
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<size_t>(size));
    };
    EXPECT_NE(stbi_write_jpg_to_func(append, &bytes, width, height, 3, pixels.data(), 90), 0);
    return bytes;
}

std::string hdr_bytes(int width, int height, const std::vector<float>& texels) {
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<size_t>(size));
    };
    EXPECT_NE(stbi_write_hdr_to_func(append, &bytes, width, height, 3, texels.data()), 0);
    return bytes;
}

TEST(LoadTexture, RejectsAnEmptyFirstIdatChunk) {
    // stb would copy zero bytes to a null buffer (undefined behaviour) before failing
    const std::string good = handmade_png(1, 1, 8, 0, std::string("\0\x80", 2));
    const size_t idat = good.find("IDAT") - 4;
    const std::string bad = good.substr(0, idat) + chunk("IDAT", "") + good.substr(idat);
    expect_memory_error(bad, "empty IDAT");
    // an empty IDAT after one with data is harmless and accepted
    const size_t iend = good.find("IEND") - 4;
    const std::string late = good.substr(0, iend) + chunk("IDAT", "") + good.substr(iend);
    const Texture t = load_texture_from_memory(late, "late.png");
    EXPECT_EQ(t.width, 1);
    EXPECT_EQ(t.height, 1);
}

TEST(LoadTexture, RejectsTruncatedAndCorruptJpegs) {
    // stb_image alone decodes a cut-off JPEG without an error (the missing data reads as zeros)
    const std::string real = read_file(shared_dir + "/textures/envMap3.jpg");
    for (size_t keep : {size_t{200}, real.size() / 3, real.size() - 2}) {
        SCOPED_TRACE(keep);
        expect_memory_error(std::string_view(real).substr(0, keep), "truncated JPEG");
        // stb also accepts 0xff fill bytes before the start-of-image marker
        std::string filled(1, '\xff');
        filled.append(real, 0, keep);
        expect_memory_error(filled, "truncated JPEG");
    }
    // a Huffman table of more than 256 codes (stb_image 2.27 writes past its tables, already
    // in the header probe): one count of the first DHT table raised
    std::string jpeg = jpeg_bytes(16, 16, random_bytes(16 * 16 * 3, 10));
    EXPECT_EQ(load_texture_from_memory(jpeg, "good.jpg").width, 16);
    const size_t dht = jpeg.find("\xff\xc4");
    ASSERT_NE(dht, std::string::npos);
    jpeg[dht + 4 + 1 + 15] = static_cast<char>(250);  // marker, length, class/id, 16th count
    expect_memory_error(jpeg, "Huffman table of");

    // a scan that names a Huffman table no DHT defined (stb decodes with a zeroed table and
    // shifts past 31 bits): the first component's AC table id set to 3
    std::string scan = jpeg_bytes(16, 16, random_bytes(16 * 16 * 3, 11));
    const size_t sos = scan.find("\xff\xda");
    ASSERT_NE(sos, std::string::npos);
    scan[sos + 6] = static_cast<char>((static_cast<uint8_t>(scan[sos + 6]) & 0xf0) | 3);
    expect_memory_error(scan, "Huffman table that was not defined");
    // the same file with the DC table id changed instead
    scan = jpeg_bytes(16, 16, random_bytes(16 * 16 * 3, 11));
    scan[sos + 6] = static_cast<char>((static_cast<uint8_t>(scan[sos + 6]) & 0x0f) | 0x20);
    expect_memory_error(scan, "Huffman table that was not defined");
}

/// A 16x8 grey baseline JPEG whose two blocks both have the largest negative DC difference,
/// under a 16-bit quantiser of 48830: the DC predictor reaches -65534 and -65534 * 48830
/// overflows int in stb_image 2.27 (found by fuzz_image; tests/fuzz/regressions/image).
std::string jpeg_with_overflowing_dc() {
    auto segment = [](uint8_t marker, const std::string& payload) {
        const size_t length = payload.size() + 2;
        return std::string{'\xff', static_cast<char>(marker), static_cast<char>(length >> 8),
                           static_cast<char>(length & 0xff)} +
               payload;
    };
    std::string quantiser(1, '\x10');                                             // 16-bit table 0
    for (int i = 0; i < 64; ++i) quantiser += "\xbe\xbe";                         // 48830
    const std::string one_code = std::string(1, '\x01') + std::string(15, '\0');  // one code, '0'
    std::string jpeg = "\xff\xd8";
    jpeg += segment(0xdb, quantiser);
    jpeg += segment(0xc0, std::string("\x08\x00\x08\x00\x10\x01\x01\x11\x00", 9));
    jpeg += segment(0xc4, std::string(1, '\x00') + one_code + '\x0f');  // DC: '0' -> category 15
    jpeg += segment(0xc4, std::string(1, '\x10') + one_code + '\x00');  // AC: '0' -> end of block
    jpeg += segment(0xda, std::string("\x01\x01\x00\x00\x3f\x00", 6));
    // per block: DC code '0', 15 zero bits (difference -32767), AC code '0'; 34 bits, padded
    jpeg += std::string("\x00\x00\x00\x00\x3f", 5);
    return jpeg + "\xff\xd9";
}

/// A decoded corrupt image: its declared size, three channels, every texel in [0, 1].
void expect_texture_of_size(const Texture& texture, int width, int height) {
    EXPECT_EQ(texture.width, width);
    EXPECT_EQ(texture.height, height);
    ASSERT_EQ(texture.texels.size(), size_t(width) * size_t(height) * 3);
    for (float texel : texture.texels) {
        EXPECT_TRUE(texel >= 0.0f && texel <= 1.0f) << texel;
    }
}

TEST(LoadTexture, DecodesAJpegWhoseDcOverflowsIntWithDefinedBehaviour) {
    // io/stb_image.cpp is compiled with -fwrapv, so the overflow wraps and the result is an
    // ordinary texture. The undefined behaviour itself is seen by clang's UBSan only (GCC
    // narrows the multiplication to 16 bits first): scripts/fuzz.sh replays these bytes.
    const std::string jpeg = jpeg_with_overflowing_dc();
    EXPECT_EQ(jpeg,
              read_file(std::string(RAYLANE_SOURCE_DIR) +
                        "/tests/fuzz/regressions/image/jpeg_dc_times_quantiser_overflows_int"));
    expect_texture_of_size(load_texture_from_memory(jpeg, "overflow.jpg"), 16, 8);
}

TEST(LoadTexture, DecodesAJpegWhoseHuffmanCodesRunPastItsBitsWithDefinedBehaviour) {
    // A corrupt scan whose codes need more bits than are left before a marker: stb_image 2.27 let
    // its bit count go negative and then shifted a 32-bit buffer by 32, undefined behaviour that
    // UBSan reports here in the asan preset (found by fuzz_image, which replays these bytes). The
    // build adds guards after stb 2.28's (cmake/patch_stb_image.cmake): the missing bits read as
    // zeros, and the corrupt file decodes to some texture of its declared size.
    const std::string jpeg = read_file(std::string(RAYLANE_SOURCE_DIR) +
                                       "/tests/fuzz/regressions/image/"
                                       "jpeg_ac_codes_longer_than_the_bits_left");
    ASSERT_EQ(jpeg.size(), 355u);
    expect_texture_of_size(load_texture_from_memory(jpeg, "overrun.jpg"), 20, 232);
}

TEST(LoadTexture, RejectsTruncatedAndCorruptHdrsWithoutHanging) {
    const std::string real = read_file(shared_dir + "/textures/env/venice_sunset_1k.hdr");
    for (size_t keep : {real.size() / 2, real.size() - 1}) {
        SCOPED_TRACE(keep);
        expect_memory_error(std::string_view(real).substr(0, keep), "truncated Radiance HDR");
    }
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
    // run-length scanline whose first literal run has length 0 (stb 2.27 would loop forever)
    expect_memory_error(
        header + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\x00", 5) + std::string(40, '\x01'),
        "zero-length run");
    // a run longer than the scanline
    expect_memory_error(header + "-Y 1 +X 8\n" + std::string("\x02\x02\x00\x08\xff\x07", 6) +
                            std::string(40, '\x01'),
                        "run past the end");
    // flat pixels (width < 8): 3 of 4 pixels present
    expect_memory_error(header + "-Y 1 +X 4\n" + std::string(12, '\x40'), "truncated Radiance");
    expect_memory_error(header + "-Y 2 +X 8\n" + std::string("\x02\x02\x00\x07", 4),
                        "has length 7, expected 8");
}

TEST(LoadTexture, RejectsImagesWithNoPixels) {
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
    expect_memory_error(header + "-Y 0 +X 8\n", "");
    expect_memory_error(header + "-Y -3 +X 8\n", "");
    expect_memory_error(handmade_png(0, 2, 8, 2, std::string(2, '\0')), "no pixels (0x2)");
}

TEST(LoadTexture, RejectsHugeHeadersBeforeDecoding) {
    // a real 4 x 4 PNG with only the IHDR width and height changed (the CRC is left stale: stb
    // ignores it); each would make a decoder allocate gigabytes
    const std::string small = png_bytes(4, 4, 3, random_bytes(48, 3));
    ASSERT_EQ(small.substr(12, 4), "IHDR");
    struct Size {
        uint32_t width, height;
    };
    for (Size size : {Size{100000, 100000}, Size{10000, 10000}, Size{40000, 1}, Size{1, 40000},
                      Size{8193, 8192}, Size{0x7fffffff, 0x7fffffff}}) {
        SCOPED_TRACE(std::to_string(size.width) + "x" + std::to_string(size.height));
        std::string patched = small;
        std::string dims;
        put32(dims, size.width);
        put32(dims, size.height);
        patched.replace(16, 8, dims);
        const std::string path = temp_file("huge.png");
        test::write_bytes(path, patched);
        expect_file_error(path, "over the limit");
    }
    // a Radiance header too
    expect_memory_error("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 30000 +X 30000\n",
                        "is 30000x30000, over the limit");
    // the largest allowed area is not refused for its size (it fails later, for lack of data)
    std::string patched = small;
    std::string dims;
    put32(dims, 8192);
    put32(dims, 8192);
    patched.replace(16, 8, dims);
    const std::string message =
        test::input_error_of([&] { load_texture_from_memory(patched, "max.png"); });
    EXPECT_EQ(message.find("over the limit"), std::string::npos) << message;
}

/// Loads `trials` random mutations of `good` (a few bytes overwritten, sometimes cut short):
/// every outcome is a texture of consistent size or one InputError line, never a crash, a hang
/// or (under the sanitizers) a bad memory access.
void load_mutations(const std::string& good, const std::string& name, uint32_t seed) {
#ifdef RAYLANE_SANITIZED
    const int trials = 300;
#else
    const int trials = 3000;
#endif
    std::mt19937 rng(seed);
    for (int trial = 0; trial < trials; ++trial) {
        std::string bytes = good;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) bytes[rng() % bytes.size()] = static_cast<char>(rng());
        if (rng() % 4 == 0) bytes.resize(rng() % bytes.size());
        try {
            const Texture t = load_texture_from_memory(bytes, name);
            EXPECT_EQ(t.texels.size(), static_cast<size_t>(t.width) * t.height * 3);
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        }
    }
}

TEST(LoadTexture, SurvivesRandomMutationsOfSmallFiles) {
    load_mutations(png_bytes(16, 16, 3, random_bytes(16 * 16 * 3, 4)), "mutant.png", 5);
    const std::string jpeg = jpeg_bytes(24, 16, random_bytes(24 * 16 * 3, 6));
    EXPECT_EQ(load_texture_from_memory(jpeg, "good.jpg").width, 24);
    load_mutations(jpeg, "mutant.jpg", 7);
    std::vector<float> texels(16 * 4 * 3);
    std::mt19937 rng(8);
    for (float& x : texels) x = static_cast<float>(rng() % 1000) / 100.0f;
    for (int width : {16, 4}) {  // run-length and flat
        const std::string hdr = hdr_bytes(width, 64 / width, texels);
        EXPECT_EQ(load_texture_from_memory(hdr, "good.hdr").width, width);
        load_mutations(hdr, "mutant.hdr", 9 + static_cast<uint32_t>(width));
    }
}

}  // namespace
}  // namespace raylane
