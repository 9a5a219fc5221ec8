// Tests of `raylane render` on animations and parts of a frame: --frames, --crop, --tile.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "image/pfm.h"
#include "support/cli_run.h"
#include "support/temp_dir.h"

namespace {

using raylane::test::CliRun;
using raylane::test::lines;
using raylane::test::run;
using raylane::test::slurp;
using raylane::test::TempDir;

const std::string turntable = RAYLANE_SOURCE_DIR "/scenes/dragon_turntable.json";

TEST(FramesCli, FramesAreFilesOfTheirOwnAndTheSameWhoeverRendersThem) {
    TempDir dir("raylane_frames_");
    const std::string pattern = (dir.path / "f_%03d.png").string();
    const CliRun r = run("render " + turntable + " -q --width 48 --frames 3..5 -o " + pattern);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("frames     3..5 of the animation's 0..71"), std::string::npos) << r.out;
    for (int f = 3; f <= 5; ++f)
        EXPECT_TRUE(std::filesystem::exists(dir.path / ("f_00" + std::to_string(f) + ".png")));
    EXPECT_FALSE(std::filesystem::exists(dir.path / "f_002.png"));
    // the camera moved: every frame differs
    const std::string f3 = slurp(dir.path / "f_003.png"), f4 = slurp(dir.path / "f_004.png");
    EXPECT_NE(f3, f4);
    // frame 4 alone is frame 4 of the sequence
    const std::string alone = (dir.path / "alone.png").string();
    ASSERT_EQ(run("render " + turntable + " -q --width 48 --frames 4 -o " + alone).code, 0);
    EXPECT_EQ(slurp(alone), f4);
}

TEST(FramesCli, BadFramesAndPartsGiveOneLine) {
    TempDir dir("raylane_frames_");
    const std::string out = " -o " + (dir.path / "x.png").string();
    const std::string frames = " -o " + (dir.path / "x_%04d.png").string();
    const std::pair<std::string, std::string> cases[] = {
        {turntable + " --frames 2..1" + frames, "ends before it starts"},
        {turntable + " --frames a..b" + frames, "expected A..B, A or all"},
        {turntable + " --frames 0..72" + frames, "the scene's animation has 72 frames (0..71)"},
        {"--frames 0..1" + frames, "has 1 frame (0)"},
        {turntable + " --frames 0..2" + out, "3 frames need a frame number in the file name"},
        {turntable + " --frames 0..2 -o " + (dir.path / "x_%s.png").string(),
         "a '%' in a file name starts the frame number"},
        {turntable + " --frames 0..2 -o " + (dir.path / "x_%d_%d.png").string(),
         "more than one frame number"},
        {"--width 40 --height 30 --crop 0 0 0 5" + out, "is not a rectangle X0 Y0 X1 Y1 inside"},
        {"--width 40 --height 30 --crop 0 0 41 5" + out, "inside the 40x30 frame"},
        {"--width 40 --height 30 --tile 3/3" + out, "expected I/N"},
        {"--width 40 --height 30 --tile 1" + out, "expected I/N"},
        {"--width 40 --height 30 --tile 0/7" + out, "a part would hold no tile (at most 6)"},
        {"--width 40 --height 30 --tile 0/2 --crop 0 0 5 5" + out, "give one of them"},
    };
    for (const auto& [args, text] : cases) {
        const CliRun r = run("render -q " + args);
        EXPECT_EQ(r.code, 2) << args << ": " << r.err;
        EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
        EXPECT_NE(r.err.find(text), std::string::npos) << args << ": " << r.err;
    }
    EXPECT_EQ(run("render -q --crop 1 2 3" + out).code, 2);  // four numbers or none
}

/// A crop written as PFM holds the pixels of the whole frame's PFM, bit for bit, for odd
/// rectangles: one pixel, one row, the whole frame.
TEST(FramesCli, CropHoldsTheWholeFramesPixels) {
    TempDir dir("raylane_frames_");
    const std::string whole = (dir.path / "whole.pfm").string();
    ASSERT_EQ(run("render -q --width 41 --height 27 --spp 2 -o " + whole).code, 0);
    const std::optional<raylane::Film> w = raylane::read_pfm(whole, 41, 27);
    ASSERT_TRUE(w.has_value());
    const int rects[][4] = {{7, 9, 8, 10}, {0, 26, 41, 27}, {0, 0, 41, 27}, {5, 3, 38, 20}};
    for (const auto& r : rects) {
        const std::string crop = (dir.path / "crop.pfm").string();
        const std::string args = std::to_string(r[0]) + " " + std::to_string(r[1]) + " " +
                                 std::to_string(r[2]) + " " + std::to_string(r[3]);
        const CliRun c =
            run("render -q --width 41 --height 27 --spp 2 --crop " + args + " -o " + crop);
        ASSERT_EQ(c.code, 0) << c.err;
        const std::optional<raylane::Film> p = raylane::read_pfm(crop, r[2] - r[0], r[3] - r[1]);
        ASSERT_TRUE(p.has_value()) << args;
        for (int y = r[1]; y < r[3]; ++y)
            for (int x = r[0]; x < r[2]; ++x)
                ASSERT_EQ(std::memcmp(&w->at(x, y), &p->at(x - r[0], y - r[1]), 12), 0)
                    << args << ": pixel " << x << ", " << y;
    }
}

}  // namespace
