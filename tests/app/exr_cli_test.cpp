// Tests of `raylane render -o FILE.exr` (linear films as layers, half or float) and of `raylane
// assemble` (parts joined into the bytes render writes for the whole frame, bad parts refused
// with one line).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "distribute/part.h"
#include "distribute/write_output.h"
#include "image/exr.h"
#include "image/pfm.h"
#include "support/cli_run.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

using test::CliRun;
using test::lines;
using test::run;

std::string file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// the built-in scene, small
const std::string small = "render --width 40 --height 30 --spp 2 ";

TEST(ExrCli, FloatExrHoldsThePfmsValuesAndHalfExrTheirHalves) {
    const test::TempDir dir("raylane_exr_cli_");
    const std::string pfm = (dir.path / "c.pfm").string(), exr = (dir.path / "c.exr").string(),
                      half_exr = (dir.path / "h.exr").string();
    ASSERT_EQ(run(small + "-o " + pfm).code, 0);
    const CliRun r = run(small + "--exr-float -o " + exr);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("image      " + exr), std::string::npos) << r.out;
    ASSERT_EQ(run(small + "-o " + half_exr).code, 0);
    const std::optional<Film> values = read_pfm(pfm, 40, 30);
    ASSERT_TRUE(values.has_value());
    const ExrImage full = read_exr(exr), half = read_exr(half_exr);
    EXPECT_TRUE(full.full_float);
    EXPECT_FALSE(half.full_float);
    ASSERT_EQ(full.layers.size(), 1u);
    ASSERT_EQ(half.layers.size(), 1u);
    EXPECT_EQ(full.layers[0].channels, (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(full.layers[0].film.pixels, values->pixels);
    // halves: as OpenEXR rounds the floats, so within 2^-11 of each
    float largest = 0.0f;
    for (size_t i = 0; i < values->pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float v = values->pixels[i][c], h = half.layers[0].film.pixels[i][c];
            ASSERT_LE(std::abs(h - v), std::abs(v) * 0x1p-11f + 0x1p-24f) << i;
            largest = std::max(largest, v);
        }
    }
    EXPECT_GT(largest, 0.1f);  // a lit image, not a black one
    // the header names the scene and the settings
    EXPECT_EQ(exr_attribute(full, "raylane:scene").size(), 16u);
    EXPECT_NE(exr_attribute(full, "raylane:settings").find("aov=color; tonemap=srgb; spp=2;"),
              std::string::npos);
}

TEST(ExrCli, AovAllWritesFourNamedLayersEachTheRawAov) {
    const test::TempDir dir("raylane_exr_cli_");
    const std::string exr = (dir.path / "all.exr").string();
    const CliRun r = run(small + "--aov all --exr-float -o " + exr);
    ASSERT_EQ(r.code, 0) << r.err;
    const ExrImage image = read_exr(exr);
    std::vector<std::string> names;
    for (const ExrLayer& layer : image.layers) {
        std::string channels;
        for (const std::string& c : layer.channels) channels += c;
        names.push_back(layer.name + ":" + channels);
    }
    EXPECT_EQ(names, (std::vector<std::string>{":RGB", "bvh_cost:Y", "depth:Z", "normal:XYZ"}));
    EXPECT_NE(exr_attribute(image, "raylane:settings").find("aov=all;"), std::string::npos);
    // each layer holds what --aov writes to a PFM
    const char* aovs[] = {"color", "bvh-cost", "depth", "normal"};
    for (size_t l = 0; l < 4; ++l) {
        const std::string pfm = (dir.path / "aov.pfm").string();
        ASSERT_EQ(run(small + "--aov " + aovs[l] + " -o " + pfm).code, 0);
        const std::optional<Film> values = read_pfm(pfm, 40, 30);
        ASSERT_TRUE(values.has_value());
        EXPECT_EQ(image.layers[l].film.pixels, values->pixels) << aovs[l];
    }
}

TEST(ExrCli, AovAllWithoutAnExrGivesOneLine) {
    const test::TempDir dir("raylane_exr_cli_");
    const CliRun r = run(small + "--aov all -o " + (dir.path / "all.png").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("use -o FILE.exr"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path / "all.png"));
}

/// A whole frame as a part (rendered with --exr-float), and the same render as PNG, PFM and EXR.
struct Whole {
    Part part;
    std::filesystem::path png, pfm, exr;
};

Whole render_whole(const std::filesystem::path& dir, const std::string& args) {
    Whole w;
    w.png = dir / "whole.png", w.pfm = dir / "whole.pfm", w.exr = dir / "whole.exr";
    const std::filesystem::path part = dir / "whole_part.exr";
    for (const auto& [file, extra] :
         {std::pair{w.png, ""}, {w.pfm, ""}, {w.exr, ""}, {part, "--exr-float "}}) {
        const CliRun r = run(small + args + " " + extra + "-o " + file.string());
        EXPECT_EQ(r.code, 0) << r.err;
    }
    w.part = read_part(part.string());
    return w;
}

struct Rect {
    int x0, y0, x1, y1;
};

/// Writes the rectangles of the whole frame as parts; returns their paths, in a line.
std::string write_parts(const std::filesystem::path& dir, const Part& whole,
                        const std::vector<Rect>& rects, const PartInfo& info) {
    std::filesystem::create_directories(dir);
    std::string paths;
    for (size_t i = 0; i < rects.size(); ++i) {
        const Rect r = rects[i];
        std::vector<AovFilm> films;
        for (const ExrLayer& layer : whole.image.layers) {
            Aov aov = Aov::color;
            EXPECT_TRUE(aov_of_exr_layer(layer.name, aov));
            Film film = make_film(r.x1 - r.x0, r.y1 - r.y0);
            for (int y = r.y0; y < r.y1; ++y)
                for (int x = r.x0; x < r.x1; ++x) film.at(x - r.x0, y - r.y0) = layer.film.at(x, y);
            films.push_back({aov, std::move(film)});
        }
        const std::string path = (dir / ("part" + std::to_string(i) + ".exr")).string();
        write_part(path, std::move(films), r.x0, r.y0, whole.image.width, whole.image.height, info);
        paths += " " + path;
    }
    return paths;
}

// uneven pieces of the 40x30 frame: a column, a single pixel, a row, the rest
const std::vector<Rect> pieces = {
    {0, 0, 7, 30}, {7, 0, 8, 1}, {8, 0, 40, 1}, {7, 1, 40, 19}, {7, 19, 40, 30}};

TEST(ExrCli, AssembledPartsGiveTheBytesOfTheWholeRender) {
    const test::TempDir dir("raylane_exr_cli_");
    for (const char* aov : {"color", "depth", "bvh-cost"}) {
        const Whole whole = render_whole(dir.path, std::string("--aov ") + aov);
        const std::string parts = write_parts(dir.path, whole.part, pieces, whole.part.info);
        for (const auto& file : {whole.png, whole.pfm, whole.exr}) {
            const std::filesystem::path out = dir.path / ("out" + file.extension().string());
            const CliRun r = run("assemble" + parts + " -o " + out.string());
            ASSERT_EQ(r.code, 0) << r.err;
            EXPECT_NE(r.out.find("frame      40x30 from 5 parts"), std::string::npos) << r.out;
            EXPECT_EQ(file_bytes(out), file_bytes(file)) << aov << " " << file;
            EXPECT_GT(file_bytes(out).size(), 100u);
        }
    }
}

TEST(ExrCli, AssembledReportToneMappingMatchesTheWholeRender) {
    const test::TempDir dir("raylane_exr_cli_");
    const std::filesystem::path scene = dir.path / "report.json";
    test::write_file(scene, R"({"tonemap": "report",
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
                   "resolution": [40, 30]},
        "materials": {"hot": {"c_d": [3, 1, 0.2]}},
        "objects": [{"shape": "sphere", "center": [0, 0, 5], "radius": 2, "material": "hot"}],
        "lights": [{"type": "point", "position": [0, 5, 0], "intensity": 200}]})");
    const Whole whole = render_whole(dir.path, scene.string());
    EXPECT_EQ(part_setting(whole.part.info, "tonemap"), "report");
    // the EXR holds the linear render, before the clamp the PNG gets
    float largest = 0.0f;
    for (const vec3& p : whole.part.image.layers[0].film.pixels)
        largest = std::max({largest, p.x, p.y, p.z});
    EXPECT_GT(largest, 1.0f);
    const std::string parts = write_parts(dir.path, whole.part, pieces, whole.part.info);
    const std::filesystem::path out = dir.path / "out.png";
    ASSERT_EQ(run("assemble" + parts + " -o " + out.string()).code, 0);
    EXPECT_EQ(file_bytes(out), file_bytes(whole.png));
}

/// Runs assemble on `parts`; expects exit code 2 and one line holding each of `words`.
void expect_refused(const std::string& parts, const std::vector<std::string>& words) {
    const CliRun r = run("assemble" + parts + " -o " +
                         (std::filesystem::temp_directory_path() / "raylane_never.png").string());
    EXPECT_EQ(r.code, 2) << parts;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    for (const std::string& w : words)
        EXPECT_NE(r.err.find(w), std::string::npos) << w << ": " << r.err;
    EXPECT_FALSE(
        std::filesystem::exists(std::filesystem::temp_directory_path() / "raylane_never.png"));
}

TEST(ExrCli, AssembleRefusesOverlapsGapsAndMismatchesWithOneLine) {
    const test::TempDir dir("raylane_exr_cli_");
    const Whole whole = render_whole(dir.path, "");
    const PartInfo& info = whole.part.info;
    const std::string p = (dir.path / "overlap" / "part").string();

    // overlap: the third piece one pixel wider to the left
    std::vector<Rect> overlap = pieces;
    overlap[2].x0 = 7;
    expect_refused(write_parts(dir.path / "overlap", whole.part, overlap, info),
                   {p + "1.exr and " + p + "2.exr overlap", "pixels x 7, y 0"});

    // gap: the last piece left out
    const std::vector<Rect> gap(pieces.begin(), pieces.end() - 1);
    expect_refused(write_parts(dir.path / "gap", whole.part, gap, info),
                   {"no part holds the pixels x 7-39, y 19-29 of the 40x30 frame"});

    // another scene, another spp, another frame size
    const std::string first = write_parts(dir.path / "a", whole.part, {pieces[0]}, info);
    PartInfo scene = info;
    scene.scene = "0000000000000000";
    const std::string other_scene =
        write_parts(dir.path / "b", whole.part, {pieces.begin() + 1, pieces.end()}, scene);
    expect_refused(first + other_scene, {"rendered from another scene than", "scene hash 0000"});
    PartInfo spp = info;
    set_part_setting(spp, "spp", "64");
    const std::string other_spp =
        write_parts(dir.path / "c", whole.part, {pieces.begin() + 1, pieces.end()}, spp);
    expect_refused(first + other_spp, {"spp 64, but ", "part0.exr has spp 2"});
    Part bigger = whole.part;
    bigger.image.width = 41;
    const std::string other_size =
        write_parts(dir.path / "d", bigger, {pieces.begin() + 1, pieces.end()}, info);
    expect_refused(first + other_size, {"a part of a 41x30 frame", "part0.exr of a 40x30 frame"});

    // other channels: a depth part among colour parts
    Part depth = whole.part;
    depth.image.layers[0].name = "depth";
    depth.image.layers[0].channels = {"Z"};
    const std::string other_channels =
        write_parts(dir.path / "e", depth, {pieces.begin() + 1, pieces.end()}, info);
    expect_refused(first + other_channels, {"channels depth.Z, but ", "has R, G, B"});
}

TEST(ExrCli, AssembleRefusesTruncatedGarbageHalfAndForeignFiles) {
    const test::TempDir dir("raylane_exr_cli_");
    const Whole whole = render_whole(dir.path, "");
    const std::string parts = write_parts(dir.path, whole.part, pieces, whole.part.info);
    const std::filesystem::path last = dir.path / "part4.exr";
    const std::string bytes = file_bytes(last);
    test::write_bytes(last, std::string_view(bytes).substr(0, bytes.size() - 40));
    expect_refused(parts, {last.string() + ": not a readable EXR"});
    test::write_bytes(last, "not an image");
    expect_refused(parts, {last.string() + ": not a readable EXR"});
    // a whole frame in halves, and an EXR that is no part
    expect_refused(" " + whole.exr.string(), {whole.exr.string() + ": holds 16-bit halves"});
    ExrImage foreign = make_exr_image(4, 4);
    foreign.layers.push_back({"", {"R", "G", "B"}, make_film(4, 4)});
    write_exr(last.string(), foreign);
    expect_refused(parts, {last.string() + ": not a Raylane part"});
    expect_refused(" " + (dir.path / "none.exr").string(), {"none.exr: no such file"});
}

TEST(ExrCli, AssembleCommandLineErrorsGiveOneLine) {
    const CliRun help = run("assemble --help");
    EXPECT_EQ(help.code, 0);
    EXPECT_NE(help.out.find("--exr-float"), std::string::npos) << help.out;
    for (const char* args : {"assemble", "assemble part.exr", "assemble part.exr -o frame.jpg",
                             "assemble part.exr -o /no/such/dir/frame.png"}) {
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
    }
}

TEST(ExrCli, AssembleOfAllAovsNeedsAnExr) {
    const test::TempDir dir("raylane_exr_cli_");
    const std::filesystem::path all = dir.path / "all.exr";
    ASSERT_EQ(run(small + "--aov all --exr-float -o " + all.string()).code, 0);
    const std::filesystem::path half = dir.path / "all_half.exr";
    ASSERT_EQ(run(small + "--aov all -o " + half.string()).code, 0);
    const Part whole = read_part(all.string());
    const std::string parts = write_parts(dir.path, whole, pieces, whole.info);
    const CliRun png = run("assemble" + parts + " -o " + (dir.path / "all.png").string());
    EXPECT_EQ(png.code, 2);
    EXPECT_EQ(lines(png.err), 1u) << png.err;
    EXPECT_NE(png.err.find("use -o FILE.exr"), std::string::npos) << png.err;
    const std::filesystem::path out = dir.path / "out.exr";
    const CliRun exr = run("assemble" + parts + " -o " + out.string());
    ASSERT_EQ(exr.code, 0) << exr.err;
    EXPECT_EQ(file_bytes(out), file_bytes(half));
}

}  // namespace
}  // namespace raylane
