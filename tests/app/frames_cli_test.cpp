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
    const CliRun r = run("render " + turntable + " --width 48 --frames 3..5 -o " + pattern);
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

/// A range past the animation's end stops at its last frame (a job array of K frames a job: the
/// last job's range need not be worked out).
TEST(FramesCli, ARangePastTheEndStopsAtTheLastFrame) {
    TempDir dir("raylane_frames_");
    const std::string pattern = (dir.path / "f_%02d.png").string();
    const CliRun r = run("render " + turntable + " --width 24 --frames 70..75 -o " + pattern);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("frames     70..71 of the animation's 0..71"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir.path / "f_70.png"));
    EXPECT_TRUE(std::filesystem::exists(dir.path / "f_71.png"));
    EXPECT_FALSE(std::filesystem::exists(dir.path / "f_72.png"));
}

TEST(FramesCli, BadFramesAndPartsGiveOneLine) {
    TempDir dir("raylane_frames_");
    const std::string out = " -o " + (dir.path / "x.png").string();
    const std::string frames = " -o " + (dir.path / "x_%04d.png").string();
    const std::pair<std::string, std::string> cases[] = {
        {turntable + " --frames 2..1" + frames, "ends before it starts"},
        {turntable + " --frames a..b" + frames, "expected A..B, A or all"},
        {turntable + " --frames 72..75" + frames, "the scene's animation has 72 frames (0..71)"},
        {turntable + " --frames 72" + frames, "the scene's animation has 72 frames (0..71)"},
        {"--frames 1..2" + frames, "has 1 frame (0)"},
        {turntable + " --frames 0..2" + out, "3 frames need a frame number in the file name"},
        {turntable + " --frames 0..2 -o " + (dir.path / "x_%s.png").string(),
         "a '%' in a file name starts the frame number"},
        {turntable + " --frames 0..2 -o " + (dir.path / "x_%d_%d.png").string(),
         "more than one frame number"},
        {"--width 40 --height 30 --crop 0 0 0 5" + out, "is not a rectangle X0 Y0 X1 Y1 inside"},
        {"--width 40 --height 30 --crop 0 0 41 5" + out, "inside the 40x30 frame"},
        {"--width 40 --height 30 --tile 3/3" + out,
         "--tile 3/3: I must be below N: a frame cut into 3 parts has parts 0 to 2"},
        {"--width 40 --height 30 --tile 5/4" + out, "--tile 5/4: I must be below N"},
        {"--width 40 --height 30 --tile 0/0" + out, "--tile 0/0: N, the number of parts, must be"},
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

/// The parts of --tile I/N for N = 1, 2, 7 and 16, and of crops that cut the frame at odd
/// places, joined by `assemble`: the bytes of the whole frame's PNG and PFM. The built-in scene
/// and the glass bunny (secondary rays in the wavefront).
TEST(FramesCli, PartsAssembleToTheWholeFrame) {
    TempDir dir("raylane_frames_");
    for (const std::string& scene :
         {std::string(), std::string(RAYLANE_SOURCE_DIR "/scenes/fig10_glass_bunny.json")}) {
        const std::string args = "render -q " + scene + " --width 80 --height 64 --spp 2";
        const std::string png = (dir.path / "whole.png").string();
        const std::string pfm = (dir.path / "whole.pfm").string();
        ASSERT_EQ(run(args + " -o " + png).code, 0);
        ASSERT_EQ(run(args + " -o " + pfm).code, 0);
        auto assemble_equals_whole = [&](const std::string& parts, const std::string& what) {
            for (const std::string& whole : {png, pfm}) {
                const std::string out =
                    (dir.path / ("joined" + std::filesystem::path(whole).extension().string()))
                        .string();
                const CliRun a = run("assemble " + parts + " -o " + out);
                ASSERT_EQ(a.code, 0) << what << ": " << a.err;
                EXPECT_TRUE(slurp(out) == slurp(whole)) << scene << ", " << what << ", " << out;
            }
        };
        for (int n : {1, 2, 7, 16}) {
            std::string parts;
            for (int i = 0; i < n; ++i) {
                const std::string part =
                    (dir.path / ("part" + std::to_string(i) + ".exr")).string();
                const CliRun r = run(args + " --tile " + std::to_string(i) + "/" +
                                     std::to_string(n) + " -o " + part);
                ASSERT_EQ(r.code, 0) << r.err;
                parts += " " + part;
            }
            assemble_equals_whole(parts, std::to_string(n) + " tiles");
            for (int i = 0; i < n; ++i)
                std::filesystem::remove(dir.path / ("part" + std::to_string(i) + ".exr"));
        }
        // one pixel, the rest of its row, one column, and the rest
        const char* crops[] = {"0 0 1 1", "1 0 80 1", "0 1 1 64", "1 1 80 64"};
        std::string parts;
        for (int i = 0; i < 4; ++i) {
            const std::string part = (dir.path / ("crop" + std::to_string(i) + ".exr")).string();
            ASSERT_EQ(run(args + " --crop " + crops[i] + " -o " + part).code, 0);
            parts += " " + part;
        }
        assemble_equals_whole(parts, "crops");
    }
}

}  // namespace
