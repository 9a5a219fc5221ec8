// Tests of render/render_packet.cpp against render/render_scalar.cpp: the same image (within
// rounding) and the same primary hits, at every packet width, on every scene in scenes/.
#include "render/render_packet.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>

#include "io/load_scene.h"
#include "render/primary_ids.h"
#include "render/render_scalar.h"
#include "report/compare.h"
#include "simd/simd.h"
#include "support/small_scene.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

// Agreement: shading runs the scalar formulas lane by lane; only pow (xsimd's vs std::pow) and
// the order of a few sums may differ, so colours agree to a few ulps of their magnitude:
// tested on ImageDiff::max_rel (relative above 1, absolute below).
constexpr double colour_tolerance = 1e-5;

template <class T>
class RenderPacket : public ::testing::Test {};
TYPED_TEST_SUITE(RenderPacket, Widths, WidthName);

/// The built-in scene, or scenes/NAME.json.
SceneData scene_named(const std::string& name) {
    return name == "builtin"
               ? make_builtin_scene()
               : load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
}

/// 50 x 29 pixels: the camera packets (4x4 at W = 16, 4x2 at 8, 2x2 at 4) are cut by the image's
/// right and bottom edges, in the one-pass kernel (the built-in scene) and in the wavefront
/// (the glass sphere, whose secondary rays fill queues from those packets). The wavefront takes
/// up to 16 samples at once: 19 samples make a full wavefront and a partial one (the glass sphere,
/// the glass bunny); the glossy sphere's hits spawn so many rays that it takes one at a time.
TYPED_TEST(RenderPacket, MatchesScalarWithJitteredSamples) {
    constexpr int W = TypeParam::value;
    const std::pair<const char*, int> cases[] = {{"builtin", 3},
                                                 {"fig05_refractive_sphere", 3},
                                                 {"fig05_refractive_sphere", 19},
                                                 {"fig10_glass_bunny", 19},
                                                 {"fig01b_glossy_sphere", 2}};
    for (const auto& [name, spp] : cases) {
        const std::string what = std::string(name) + ", " + std::to_string(spp) + " spp";
        SceneData scene;
        try {
            scene = scene_named(name);
        } catch (const std::exception& e) {
            ADD_FAILURE() << what << ": " << e.what();  // a missing model fails, never skips
            continue;
        }
        scene.camera.width = 50;
        scene.camera.height = 29;
        const Accel accel = build_accel(scene, BuildParams{});
        RenderParams p;
        p.spp = spp;
        const RenderResult a = render_scalar(scene, accel, p);
        const RenderResult b = render_packet_width<W>(scene, accel, p);
        const ImageDiff d = diff_images(a.film, b.film);
        EXPECT_LE(d.max_rel, colour_tolerance) << what;
        EXPECT_EQ(a.stats.shadow_rays, b.stats.shadow_rays) << what;
        EXPECT_EQ(a.stats.primary_rays, b.stats.primary_rays) << what;
        EXPECT_EQ(a.stats.total_rays(), b.stats.total_rays()) << what;
        double sum = 0;  // not a blank image
        for (const vec3& c : b.film.pixels) sum += c.x + c.y + c.z;
        EXPECT_GT(sum, 0.01 * double(b.film.pixels.size())) << what;
    }
}

/// In the one-pass kernel (the built-in scene) and in a kernel with secondary rays (the glass
/// sphere), whose AOVs take a sample at a time, not several in a wavefront.
TYPED_TEST(RenderPacket, AovsMatchScalar) {
    constexpr int W = TypeParam::value;
    for (const char* name : {"builtin", "fig05_refractive_sphere"}) {
        const SceneData scene = small_scene(scene_named(name), 64);
        const Accel accel = build_accel(scene, BuildParams{});
        for (Aov aov : {Aov::normal, Aov::depth, Aov::bvh_cost}) {
            RenderParams p;
            p.aov = aov;
            const RenderResult a = render_scalar(scene, accel, p);
            const RenderResult b = render_packet_width<W>(scene, accel, p);
            if (aov == Aov::bvh_cost) {
                // node counts differ by design (a packet visits a node while any lane is active);
                // both must count something for every pixel that sees the scene
                double sa = 0, sb = 0;
                for (size_t i = 0; i < a.film.pixels.size(); ++i) {
                    sa += a.film.pixels[i].x;
                    sb += b.film.pixels[i].x;
                }
                EXPECT_GT(sa, 0.0) << name;
                EXPECT_GE(sb, sa) << name;
            } else {
                EXPECT_LE(diff_images(a.film, b.film).max_abs, colour_tolerance)
                    << name << ", " << aov_name(aov);
            }
        }
    }
}

/// Bit for bit, in the one-pass kernel (the built-in scene) and in the wavefronts, whose samples
/// fix the order of each pixel's sums (the glass bunny and its area light: 19 samples make a
/// wavefront of 16 and one of 3).
TEST(RenderPacket, SameImageForOneAndTwoThreads) {
    for (const char* name : {"builtin", "fig10_glass_bunny"}) {
        const SceneData scene = small_scene(scene_named(name), 80);
        const Accel accel = build_accel(scene, BuildParams{});
        RenderParams p;
        p.spp = std::string(name) == "builtin" ? 2 : 19;
        p.threads = 1;
        const RenderResult one = render_packet(scene, accel, p);
        p.threads = 2;
        const RenderResult two = render_packet(scene, accel, p);
        EXPECT_EQ(one.film.pixels, two.film.pixels) << name;
    }
}

/// The tile size decides only how pixels are grouped, never their values: 75 x 43 pixels of the
/// built-in scene (one pass) and the dragon when its model is found, in tiles of 16, 12, 8, 5 and
/// 4 pixels, so full camera packets sit in tiles narrower than 16 and packets are cut by tile
/// and image edges; every image is the 16-pixel one bit for bit.
TEST(RenderPacket, SameImageForEveryTileSize) {
    for (const char* name : {"builtin", "dragon"}) {
        SceneData scene;
        try {
            scene = small_scene(scene_named(name), 75);
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
            continue;
        }
        scene.camera.height = 43;
        const Accel accel = build_accel(scene, BuildParams{});
        RenderParams p;
        p.spp = 2;
        p.threads = 2;
        const RenderResult reference = render_packet(scene, accel, p);
        for (const int tile_size : {12, 8, 5, 4}) {
            p.tile_size = tile_size;
            const RenderResult r = render_packet(scene, accel, p);
            ASSERT_EQ(r.film.pixels.size(), reference.film.pixels.size());
            for (size_t i = 0; i < r.film.pixels.size(); ++i)
                ASSERT_EQ(r.film.pixels[i], reference.film.pixels[i])
                    << name << ", tiles of " << tile_size << ", pixel " << i;
        }
    }
}

/// `raylane compare` on every scene of scenes/ (at a quarter of the width, to keep the suite
/// fast): the images agree within the tolerance and no primary hit differs.
TEST(RenderPacket, EverySceneFileAgreesWithTheScalarPath) {
    int scenes = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(RAYLANE_SOURCE_DIR) + "/scenes")) {
        if (entry.path().extension() != ".json") continue;
        SceneData scene;
        try {
            scene = load_scene(entry.path().string());
        } catch (const std::exception& e) {
            // only a missing model may skip a scene
            EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
            continue;
        }
#ifdef RAYLANE_SANITIZED
        scene = small_scene(scene, 96);
#else
        scene = small_scene(scene, std::max(64, scene.camera.width / 4));
#endif
        const Accel accel = build_accel(scene, BuildParams{});
        RenderParams p;
        p.spp = std::min(scene.camera.spp, 2);
        p.light_samples = 4;  // fewer area-light and glossy samples: the same code, less time
        p.glossy_samples = 3;
        const RenderResult a = render_scalar(scene, accel, p);
        const RenderResult b = render_packet(scene, accel, p);
        const ImageDiff d = diff_images(a.film, b.film);
        EXPECT_LE(d.max_rel, colour_tolerance) << entry.path();
        EXPECT_EQ(d.pixels_over_8bit, 0u) << entry.path();
        EXPECT_EQ(primary_id_mismatches(scene, accel), 0u) << entry.path();
        // strict: no scene of ours makes a NaN or infinite sample (numerics.md §18)
        EXPECT_EQ(a.stats.nan_samples + a.stats.inf_samples, 0u) << entry.path();
        EXPECT_EQ(b.stats.nan_samples + b.stats.inf_samples, 0u) << entry.path();
        // the image is not blank: a test on a black image proves nothing
        double sum = 0;
        for (const vec3& c : a.film.pixels) sum += c.x + c.y + c.z;
        EXPECT_GT(sum / double(a.film.pixels.size()), 0.01) << entry.path();
        ++scenes;
    }
    EXPECT_GE(scenes, 1);
}

}  // namespace
}  // namespace raylane
