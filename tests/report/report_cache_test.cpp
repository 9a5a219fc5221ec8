// Tests of report/report_cache.cpp: converged references (the variance from their halves, the
// chunks) and their cache on disk (the key, saving and loading).
#include "report/report_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "report/report_metrics.h"
#include "support/report_scenes.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() { return test::fresh_temp_dir("raylane_report_"); }
using test::tiny_builtin;
using test::write_file;

TEST(ConvergedReference, VarianceFromHalvesPredictsTheSpreadOfIndependentReferences) {
    const SceneData scene = tiny_builtin();
    const Accel accel = build_accel(scene, BuildParams{});
    ReferenceParams p;
    p.spp = 64;
    p.chunk_spp = 16;
    const Reference a = render_converged_reference(scene, accel, p);
    p.seed = reference_seed + 1000;
    const Reference b = render_converged_reference(scene, accel, p);
    EXPECT_EQ(a.spp, 64);
    EXPECT_GT(a.variance, 0.0);
    // two independent references differ by 2 Var(ref) in mean square
    const double mse = compute_error(a.film, b.film).mse;
    EXPECT_GT(mse / (a.variance + b.variance), 0.5);
    EXPECT_LT(mse / (a.variance + b.variance), 2.0);
}

TEST(ConvergedReference, ChunksReportProgressAndRejectTooFewSamples) {
    const SceneData scene = tiny_builtin();
    const Accel accel = build_accel(scene, BuildParams{});
    ReferenceParams p;
    p.spp = 10;
    p.chunk_spp = 4;
    int calls = 0, last = 0, total = 0;
    const Reference r = render_converged_reference(scene, accel, p, [&](int done, int all) {
        ++calls;
        last = done;
        total = all;
    });
    EXPECT_EQ(calls, 3);  // 4 + 4 + 2
    EXPECT_EQ(last, total);
    EXPECT_EQ(r.spp, 10);
    p.spp = 3;
    EXPECT_THROW(render_converged_reference(scene, accel, p), std::invalid_argument);
}

TEST(ReferenceCache, KeyFollowsTheSceneItsFilesAndTheSettings) {
    const fs::path dir = temp_dir();
    write_file(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string scene_text =
        R"({"camera": {"position": [0,0,-3], "look_at": [0,0,0], "fov_deg": 60},
            "materials": {"m": {}},
            "objects": [{"shape": "mesh", "file": "tri.obj", "material": "m"}]})";
    write_file(dir / "scene.json", scene_text);
    const std::string scene = (dir / "scene.json").string();
    ReferenceParams p;
    const std::string key = reference_cache_key(scene, 32, 24, p);
    EXPECT_EQ(key.size(), 16u);
    EXPECT_EQ(reference_cache_key(scene, 32, 24, p), key);
    EXPECT_NE(reference_cache_key(scene, 32, 25, p), key);
    ReferenceParams q = p;
    q.spp = p.spp * 2;
    EXPECT_NE(reference_cache_key(scene, 32, 24, q), key);
    q = p;
    q.seed = p.seed + 1;
    EXPECT_NE(reference_cache_key(scene, 32, 24, q), key);
    // the mesh file changes (its time and size)
    fs::last_write_time(dir / "tri.obj",
                        fs::last_write_time(dir / "tri.obj") + std::chrono::seconds(5));
    const std::string key2 = reference_cache_key(scene, 32, 24, p);
    EXPECT_NE(key2, key);
    // the scene file changes
    write_file(dir / "scene.json", scene_text + " ");
    EXPECT_NE(reference_cache_key(scene, 32, 24, p), key2);
    EXPECT_THROW(reference_cache_key((dir / "missing.json").string(), 32, 24, p), InputError);
    fs::remove_all(dir);
}

TEST(ReferenceCache, SavedReferenceLoadsBackAndDamagedFilesAreMisses) {
    const fs::path dir = temp_dir();
    Reference r;
    r.film = make_film(5, 3);
    for (size_t i = 0; i < r.film.pixels.size(); ++i)
        r.film.pixels[i] = vec3(float(i), 0.5f * float(i), -1.0f / float(i + 1));
    r.kind = "converged";
    r.spp = 640;
    r.variance = 1.25e-7;
    const std::string file = (dir / "ref.pfm").string();
    save_reference(file, r, "build A");
    std::string build;
    const auto back = load_reference(file, 5, 3, &build);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->spp, 640);
    EXPECT_EQ(back->variance, 1.25e-7);
    EXPECT_EQ(build, "build A");
    EXPECT_EQ(back->film.pixels, r.film.pixels);
    EXPECT_FALSE(load_reference(file, 5, 4).has_value());                         // other size
    EXPECT_FALSE(load_reference((dir / "none.pfm").string(), 5, 3).has_value());  // missing
    fs::resize_file(file, fs::file_size(file) - 4);                               // truncated
    EXPECT_FALSE(load_reference(file, 5, 3).has_value());
    save_reference(file, r, "build A");
    write_file(file + ".txt", "something else\n");
    EXPECT_FALSE(load_reference(file, 5, 3).has_value());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace raylane
