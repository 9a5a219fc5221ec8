// image: the EXR writer and reader (exr.h): layers, windows and attributes come back as written,
// halves round as OpenEXR rounds them, and damaged files give one-line InputErrors.
#include "image/exr.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "support/input_error.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

/// A film of distinct values, negative, fractional and large ones among them.
Film exr_test_film(int w, int h, float scale) {
    Film film = make_film(w, h);
    for (size_t i = 0; i < film.pixels.size(); ++i)
        film.pixels[i] = scale * vec3(float(i) / 3.0f, -0.5f * float(i), 1000.0f + float(i));
    return film;
}

/// A 7x5 frame whose data window is [2, 6) x [1, 4), with a colour and a depth layer.
ExrImage test_image(bool full_float) {
    ExrImage image;
    image.width = 7, image.height = 5;
    image.x0 = 2, image.y0 = 1, image.x1 = 6, image.y1 = 4;
    image.layers.push_back({"", {"R", "G", "B"}, exr_test_film(4, 3, 1.0f)});
    Film depth = exr_test_film(4, 3, 2.0f);
    for (vec3& p : depth.pixels) p = vec3(p.x);
    image.layers.push_back({"depth", {"Z"}, depth});
    image.attributes = {{"raylane:scene", "0123456789abcdef"}, {"raylane:settings", "spp=4"}};
    image.full_float = full_float;
    return image;
}

std::string file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Exr, ReadsBackLayersWindowAndAttributesOfAFloatImage) {
    const test::TempDir dir("raylane_exr_");
    const std::string file = (dir.path / "part.exr").string();
    const ExrImage image = test_image(true);
    write_exr(file, image);
    EXPECT_FALSE(std::filesystem::exists(file + ".partial"));
    const ExrImage back = read_exr(file);
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.x0, 2);
    EXPECT_EQ(back.y0, 1);
    EXPECT_EQ(back.x1, 6);
    EXPECT_EQ(back.y1, 4);
    EXPECT_TRUE(back.full_float);
    ASSERT_EQ(back.layers.size(), 2u);
    EXPECT_EQ(back.layers[0].name, "");
    EXPECT_EQ(back.layers[0].channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(back.layers[0].film.pixels, image.layers[0].film.pixels);
    EXPECT_EQ(back.layers[1].name, "depth");
    EXPECT_EQ(back.layers[1].channels, std::vector<std::string>{"Z"});
    EXPECT_EQ(back.layers[1].film.pixels, image.layers[1].film.pixels);
    EXPECT_EQ(exr_attribute(back, "raylane:scene"), "0123456789abcdef");
    EXPECT_EQ(exr_attribute(back, "raylane:settings"), "spp=4");
    EXPECT_EQ(exr_attribute(back, "raylane:none"), "");
}

TEST(Exr, OpenExrSeesTheChannelsTypesAndWindows) {
    const test::TempDir dir("raylane_exr_");
    for (bool full_float : {false, true}) {
        const std::string file = (dir.path / "image.exr").string();
        write_exr(file, test_image(full_float));
        Imf::InputFile in(file.c_str());
        const Imf::Header& header = in.header();
        EXPECT_EQ(header.displayWindow(), Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(6, 4)));
        EXPECT_EQ(header.dataWindow(), Imath::Box2i(Imath::V2i(2, 1), Imath::V2i(5, 3)));
        std::vector<std::string> names;
        for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
            names.push_back(c.name());
            EXPECT_EQ(c.channel().type, full_float ? Imf::FLOAT : Imf::HALF) << c.name();
        }
        EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "R", "depth.Z"}));
        const auto* scene = header.findTypedAttribute<Imf::StringAttribute>("raylane:scene");
        ASSERT_NE(scene, nullptr);
        EXPECT_EQ(scene->value(), "0123456789abcdef");
    }
}

TEST(Exr, HalvesRoundAsOpenExrRoundsFloats) {
    const test::TempDir dir("raylane_exr_");
    const std::string file = (dir.path / "half.exr").string();
    const ExrImage image = test_image(false);
    write_exr(file, image);
    const ExrImage back = read_exr(file);
    EXPECT_FALSE(back.full_float);
    ASSERT_EQ(back.layers.size(), 2u);
    for (size_t l = 0; l < 2; ++l) {
        const Film& in = image.layers[l].film;
        const Film& out = back.layers[l].film;
        ASSERT_EQ(out.pixels.size(), in.pixels.size());
        for (size_t i = 0; i < in.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(out.pixels[i][c], float(Imath::half(in.pixels[i][c]))) << l << " " << i;
    }
    // a third a pixel's x is no half: the halves are not the floats
    EXPECT_NE(back.layers[0].film.pixels[1].x, image.layers[0].film.pixels[1].x);
}

TEST(Exr, TheSameImageGivesTheSameBytes) {
    const test::TempDir dir("raylane_exr_");
    const std::string a = (dir.path / "a.exr").string(), b = (dir.path / "b.exr").string();
    write_exr(a, test_image(false));
    write_exr(b, test_image(false));
    EXPECT_EQ(file_bytes(a), file_bytes(b));
    EXPECT_GT(file_bytes(a).size(), 100u);
}

TEST(Exr, InconsistentImagesAreNotWritten) {
    const test::TempDir dir("raylane_exr_");
    const std::string file = (dir.path / "bad.exr").string();
    ExrImage outside = test_image(true);
    outside.x1 = 8;  // past the frame
    EXPECT_THROW(write_exr(file, outside), std::invalid_argument);
    ExrImage wrong = test_image(true);
    wrong.layers[1].film = make_film(3, 3);  // not the data window's size
    EXPECT_THROW(write_exr(file, wrong), std::invalid_argument);
    EXPECT_FALSE(std::filesystem::exists(file));
    EXPECT_THROW(write_exr((dir.path / "no" / "such.exr").string(), test_image(true)),
                 std::runtime_error);
}

TEST(Exr, MissingGarbageAndTruncatedFilesGiveOneLineNamingTheFile) {
    const test::TempDir dir("raylane_exr_");
    const std::string missing = (dir.path / "missing.exr").string();
    EXPECT_EQ(test::input_error_of([&] { read_exr(missing); }), missing + ": no such file");
    const std::string garbage = (dir.path / "garbage.exr").string();
    test::write_bytes(garbage, "P6\n1 1\n255\n\x01\x02\x03 not an EXR at all");
    const std::string why = test::input_error_of([&] { read_exr(garbage); });
    EXPECT_EQ(why.rfind(garbage + ": not a readable EXR", 0), 0u) << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;

    const std::string whole = (dir.path / "whole.exr").string();
    ExrImage big = test_image(true);
    write_exr(whole, big);
    const std::string bytes = file_bytes(whole);
    const std::string cut = (dir.path / "cut.exr").string();
    // every length short of the whole file: the header cut, the offsets, the pixel data
    for (size_t n = 0; n < bytes.size(); n += (n < 400 ? 1 : 7)) {
        test::write_bytes(cut, std::string_view(bytes).substr(0, n));
        const std::string reason = test::input_error_of([&] { read_exr(cut); });
        EXPECT_EQ(reason.rfind(cut + ": ", 0), 0u) << n << ": " << reason;
        EXPECT_EQ(reason.find('\n'), std::string::npos) << n << ": " << reason;
        const std::string in_memory = test::input_error_of(
            [&] { read_exr_from_memory(std::string_view(bytes).substr(0, n), "cut"); });
        EXPECT_EQ(in_memory.rfind("cut: ", 0), 0u) << n << ": " << in_memory;
    }
}

TEST(Exr, ReadsFromMemoryWhatItReadsFromTheFile) {
    const test::TempDir dir("raylane_exr_");
    const std::string file = (dir.path / "image.exr").string();
    write_exr(file, test_image(true));
    const ExrImage from_file = read_exr(file);
    const ExrImage from_memory = read_exr_from_memory(file_bytes(file), "image");
    EXPECT_EQ(from_memory.x0, from_file.x0);
    EXPECT_EQ(from_memory.y1, from_file.y1);
    EXPECT_EQ(from_memory.attributes, from_file.attributes);
    ASSERT_EQ(from_memory.layers.size(), from_file.layers.size());
    for (size_t l = 0; l < from_file.layers.size(); ++l)
        EXPECT_EQ(from_memory.layers[l].film.pixels, from_file.layers[l].film.pixels);
}

TEST(Exr, HeadersThatClaimMoreThanTheFileHoldsAreRefusedBeforeOpenExrReadsThem) {
    const test::TempDir dir("raylane_exr_");
    const std::string file = (dir.path / "image.exr").string();
    write_exr(file, test_image(true));
    const std::string bytes = file_bytes(file);
    // the size of the raylane:scene attribute, after its name and type
    const std::string key("raylane:scene\0string\0", 21);
    const size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos);
    std::string huge = bytes;
    huge.replace(at + key.size(), 4, "\xff\xff\xff\x7f");
    EXPECT_EQ(test::input_error_of([&] { read_exr_from_memory(huge, "huge"); }),
              "huge: not a readable EXR: header attribute \"raylane:scene\" holds 2147483647 "
              "bytes, past the end of the file (truncated or damaged)");
    std::string tiled = bytes;
    tiled[5] = char(tiled[5] | 0x02);  // the tiled flag, 0x200 of the version field
    EXPECT_EQ(test::input_error_of([&] { read_exr_from_memory(tiled, "tiled"); }),
              "tiled: not a readable EXR: a tiled EXR (Raylane reads scan-line files)");
}

TEST(Exr, ALayerOfTwoChannelsIsNotRead) {
    const test::TempDir dir("raylane_exr_");
    const std::string file = (dir.path / "uv.exr").string();
    ExrImage image = test_image(true);
    image.layers.push_back({"uv", {"U"}, image.layers[0].film});
    image.layers.push_back({"uv", {"V"}, image.layers[0].film});
    write_exr(file, image);
    EXPECT_EQ(test::input_error_of([&] { read_exr(file); }),
              file + ": layer \"uv\" has 2 channels (Raylane reads layers of 1 or 3)");
}

}  // namespace
}  // namespace raylane
