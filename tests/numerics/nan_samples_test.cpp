// numerics.md §18: a NaN or infinite sample never reaches the image. Each is classified by its
// bits, counted (NaN and Inf apart), left out of its pixel, and both paths count the same.
// The command line's --strict is tested in tests/app/cli_test.cpp.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/bvh.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "render/sample_sum_packet.h"
#include "render/sample_sum_scalar.h"
#include "report/compare.h"
#include "scene/scene.h"
#include "simd/lanes.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

TEST(SampleKind, ClassifiesByTheBits) {
    const float tiny = std::numeric_limits<float>::denorm_min();
    const float big = std::numeric_limits<float>::max();
    const float snan = std::numeric_limits<float>::signaling_NaN();
    const float neg_nan = std::bit_cast<float>(0xffc00001u);
    EXPECT_EQ(sample_kind(vec3(0.0f, -0.0f, 1.0f)), SampleKind::finite);
    EXPECT_EQ(sample_kind(vec3(tiny, big, -big)), SampleKind::finite);
    EXPECT_EQ(sample_kind(vec3(inf_f, 0.0f, 0.0f)), SampleKind::inf);
    EXPECT_EQ(sample_kind(vec3(0.0f, -inf_f, 0.0f)), SampleKind::inf);
    EXPECT_EQ(sample_kind(vec3(0.0f, 0.0f, nan_f)), SampleKind::nan);
    EXPECT_EQ(sample_kind(vec3(inf_f, snan, 0.0f)), SampleKind::nan);  // NaN wins over Inf
    EXPECT_EQ(sample_kind(vec3(neg_nan, 1.0f, 1.0f)), SampleKind::nan);
}

template <class T>
class SampleKindPacket : public ::testing::Test {};
TYPED_TEST_SUITE(SampleKindPacket, Widths, WidthName);

TYPED_TEST(SampleKindPacket, ClassifiesEveryLaneAsTheScalar) {
    constexpr int W = TypeParam::value;
    const float values[] = {0.0f,
                            -0.0f,
                            1.0f,
                            nan_f,
                            -nan_f,
                            inf_f,
                            -inf_f,
                            std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(),
                            std::bit_cast<float>(0x7f800001u)};
    constexpr int n = static_cast<int>(std::size(values));
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            alignas(64) float x[W], y[W], z[W];
            for (int i = 0; i < W; ++i) {
                x[i] = values[(a + i) % n];
                y[i] = values[(b + 3 * i) % n];
                z[i] = values[(a + b + i) % n];
            }
            vmask<W> is_nan, is_inf;
            sample_kinds<W>(load_vec3<W>(x, y, z), is_nan, is_inf);
            for (int i = 0; i < W; ++i) {
                const SampleKind k = sample_kind(vec3(x[i], y[i], z[i]));
                EXPECT_EQ(get(is_nan, i), k == SampleKind::nan) << a << " " << b << " " << i;
                EXPECT_EQ(get(is_inf, i), k == SampleKind::inf) << a << " " << b << " " << i;
            }
        }
}

/// The built-in scene with one material's diffuse colour NaN (an object of it is in view).
SceneData scene_with_nan_material() {
    SceneData scene = make_builtin_scene();
    scene.camera.height = scene.camera.height * 64 / scene.camera.width;
    scene.camera.width = 64;
    scene.materials.at(0).c_d = vec3(0.5f, nan_f, 0.5f);
    return scene;
}

TEST(NanSamples, AreCountedLeftOutAndTheSameInBothPaths) {
    const SceneData scene = scene_with_nan_material();
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.spp = 3;
    const RenderResult a = render_scalar(scene, accel, p);
    const RenderResult b = render_packet(scene, accel, p);
    EXPECT_GE(a.stats.nan_samples, 1u);
    EXPECT_EQ(a.stats.inf_samples, 0u);
    EXPECT_EQ(a.stats.nan_samples, b.stats.nan_samples);
    EXPECT_EQ(a.stats.inf_samples, b.stats.inf_samples);
    for (const RenderResult* r : {&a, &b})
        for (const vec3& c : r->film.pixels)
            ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    // the other pixels still agree, and the image is not blank
    const ImageDiff d = diff_images(a.film, b.film);
    EXPECT_LE(d.max_abs, 1e-5);
    double sum = 0.0;
    for (const vec3& c : a.film.pixels) sum += c.x + c.y + c.z;
    EXPECT_GT(sum, 1.0);
}

TEST(NanSamples, ACleanSceneCountsNone) {
    SceneData scene = make_builtin_scene();
    scene.camera.height = scene.camera.height * 64 / scene.camera.width;
    scene.camera.width = 64;
    const Accel accel = build_accel(scene, BuildParams{});
    RenderParams p;
    p.spp = 2;
    for (const RenderResult& r : {render_scalar(scene, accel, p), render_packet(scene, accel, p)}) {
        EXPECT_EQ(r.stats.nan_samples, 0u);
        EXPECT_EQ(r.stats.inf_samples, 0u);
    }
}

}  // namespace
}  // namespace raylane
