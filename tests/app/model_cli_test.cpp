// Tests of the command line on a model file: `render MODEL`, `scene MODEL`, `info MODEL`, and a
// file that is neither a scene nor a model.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "image/pfm.h"
#include "support/cli_run.h"
#include "support/models.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

using test::CliRun;
using test::lines;
using test::run;
using test::slurp;
using test::TempDir;
using test::write_file;

const std::string bunny = std::string(RAYLANE_SHARED_DIR) + "/models/bunny.ply";

TEST(ModelCli, RenderModelShowsTheModelLit) {
    if (!std::filesystem::exists(bunny)) RAYLANE_MODEL_MISSING() << bunny << " is not available";
    TempDir dir("raylane_model_cli_");
    const std::string pfm = (dir.path / "bunny.pfm").string();
    const CliRun r = run("render " + bunny + " --width 160 -o " + pfm);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("scene      " + bunny), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("resolution 160x90"), std::string::npos) << r.out;
    const std::optional<Film> film = read_pfm(pfm, 160, 90);
    ASSERT_TRUE(film.has_value());
    // lit and not flat: the model in the middle differs from the floor at the bottom corners
    double sum = 0.0, lo = 1e30, hi = -1e30;
    for (const vec3& c : film->pixels) {
        ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
        const double y = (c.x + c.y + c.z) / 3.0;
        sum += y, lo = std::min(lo, y), hi = std::max(hi, y);
    }
    EXPECT_GT(sum / double(film->pixels.size()), 0.05);
    EXPECT_GT(hi - lo, 0.2);
}

TEST(ModelCli, TheSceneCommandPrintsWhatRenderRenders) {
    if (!std::filesystem::exists(bunny)) RAYLANE_MODEL_MISSING() << bunny << " is not available";
    TempDir dir("raylane_model_cli_");
    const CliRun s = run("scene " + bunny);
    ASSERT_EQ(s.code, 0) << s.err;
    write_file(dir.path / "bunny.json", s.out);
    const std::string a = (dir.path / "a.png").string(), b = (dir.path / "b.png").string();
    const CliRun ra = run("render " + bunny + " --width 96 -q -o " + a);
    const CliRun rb =
        run("render " + (dir.path / "bunny.json").string() + " --width 96 -q -o " + b);
    ASSERT_EQ(ra.code, 0) << ra.err;
    ASSERT_EQ(rb.code, 0) << rb.err;
    const std::string bytes = slurp(a);
    EXPECT_GT(bytes.size(), 100u);
    EXPECT_EQ(bytes, slurp(b)) << "the printed scene renders the same image";
}

TEST(ModelCli, InfoAndCompareTakeAModel) {
    if (!std::filesystem::exists(bunny)) RAYLANE_MODEL_MISSING() << bunny << " is not available";
    const CliRun info = run("info " + bunny);
    ASSERT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("wide tree"), std::string::npos) << info.out;
    const CliRun compare = run("compare " + bunny + " --width 48");
    EXPECT_EQ(compare.code, 0) << compare.err << compare.out;
}

TEST(ModelCli, AFileThatIsNeitherSceneNorModelSaysWhatWasExpected) {
    TempDir dir("raylane_model_cli_");
    write_file(dir.path / "notes.txt", "hello\n");
    const CliRun r = run("render " + (dir.path / "notes.txt").string());
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(r.err, "raylane: " + (dir.path / "notes.txt").string() +
                         ": neither a scene nor a model: expected a JSON scene (.json) or a "
                         "model (.obj, .ply, .obj.gz, .ply.gz)\n");
    const CliRun s = run("scene " + (dir.path / "notes.txt").string());
    EXPECT_EQ(s.code, 2);
    EXPECT_NE(s.err.find("not a model: expected an .obj or .ply file"), std::string::npos) << s.err;
}

/// A folder given as the scene: every command says so in the same words (and Python too,
/// tests/python/test_scene.py).
TEST(ModelCli, AFolderGivenAsTheSceneSaysItIsAFolder) {
    TempDir dir("raylane_model_cli_");
    const std::string folder = dir.path.string();
    for (const char* command : {"render ", "compare ", "info ", "scene "}) {
        const CliRun r = run(command + folder);
        EXPECT_EQ(r.code, 2) << command;
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find(folder + ": is a folder, not a scene (.json) or a model (.obj, .ply)"),
                  std::string::npos)
            << command << r.err;
    }
}

TEST(ModelCli, RenderWarnsOfAnUnlitSceneACameraThatSeesNothingAndABlackImage) {
    TempDir dir("raylane_model_cli_");
    write_file(dir.path / "away.json",
               R"({"version": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, -10],
                   "fov_deg": 40, "resolution": [32, 24]},
                   "materials": {"m": {"c_d": [1, 0, 0]}},
                   "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                                "material": "m"}],
                   "lights": []})");
    const CliRun r = run("render " + (dir.path / "away.json").string() + " -q -o " +
                         (dir.path / "away.png").string());
    EXPECT_EQ(r.code, 0) << r.err;
    for (const char* w :
         {"warning    the scene has no lights", "warning    the camera sees no object",
          "warning    every pixel is black"})
        EXPECT_NE(r.out.find(w), std::string::npos) << w << "\n" << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir.path / "away.png")) << "the render still runs";
}

TEST(ModelCli, ADepthPfmIsInSceneUnitsAndItsPngNamesItsScale) {
    // a unit sphere 5 in front of the camera: the centre pixel's ray hits it at 4
    TempDir dir("raylane_model_cli_");
    write_file(dir.path / "ball.json",
               R"({"version": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0],
                   "fov_deg": 40, "resolution": [33, 33]},
                   "materials": {"m": {"c_d": [1, 1, 1]}},
                   "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                                "material": "m"}],
                   "lights": [{"type": "point", "position": [0, 5, -5]}]})");
    const std::string scene = (dir.path / "ball.json").string();
    const std::string pfm = (dir.path / "d.pfm").string();
    const CliRun raw = run("render " + scene + " --aov depth -o " + pfm);
    ASSERT_EQ(raw.code, 0) << raw.err;
    EXPECT_NE(raw.out.find("values     raw depth"), std::string::npos) << raw.out;
    const std::optional<Film> film = read_pfm(pfm, 33, 33);
    ASSERT_TRUE(film.has_value());
    EXPECT_NEAR(film->at(16, 16).x, 4.0f, 1e-5f);
    EXPECT_EQ(film->at(0, 0).x, 0.0f) << "a miss";
    const CliRun png = run("render " + scene + " --aov depth -o " + (dir.path / "d.png").string());
    ASSERT_EQ(png.code, 0) << png.err;
    EXPECT_NE(png.out.find("scale      depth: log scale, white at 4, black at "), std::string::npos)
        << png.out;
}

TEST(ModelCli, ThePngBytesDoNotDependOnTheThreadCount) {
    if (!std::filesystem::exists(bunny)) RAYLANE_MODEL_MISSING() << bunny << " is not available";
    TempDir dir("raylane_model_cli_");
    std::string first;
    for (int threads : {1, 2}) {
        const std::string n = std::to_string(threads);
        const std::string png = (dir.path / (n + ".png")).string();
        const CliRun r = run("render " + bunny + " --width 200 -q --threads " + n + " -o " + png);
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string bytes = slurp(png);
        ASSERT_GT(bytes.size(), 1000u);
        if (first.empty())
            first = bytes;
        else
            EXPECT_EQ(bytes, first) << "threads " << threads;
    }
}

}  // namespace
}  // namespace raylane
