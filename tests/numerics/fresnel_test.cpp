// Numerical stability suite, shading (numerics.md §9): the exact dielectric
// Fresnel term and refraction of shade/optics_scalar.h and their packet twins in optics_packet.h,
// on a grid of indices (1, 1.0001, 1.5, 4 and their inverses) and cosines (0, tiny, near the
// critical angle, 1, 1 + 1 ulp, garbage), against a double oracle. The eta = 1 sphere is rendered
// in tests/render/render_features_test.cpp (RenderFeatures.GlassOfIndexOneIsInvisible).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/offset.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "shade/optics_packet.h"
#include "shade/optics_scalar.h"
#include "simd/lanes.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

constexpr double float_eps = 0x1.0p-24;  // unit roundoff of float

const float etas[] = {1.0f, 1.0001f, 1.5f, 4.0f, 1.0f / 1.0001f, 1.0f / 1.5f, 0.25f};

/// Exact unpolarised Fresnel in double for float inputs (numerics.md §9): R from the reflection
/// amplitudes, T independently from the transmission amplitudes (Stokes), so that R + T = 1 is a
/// real check. ci is clamped to [0, 1]; total internal reflection when sin^2_t >= 1 (which
/// includes ci = 0 at eta = 1: grazing, nothing enters).
struct FresnelRef {
    double r = 1, t = 0, sin2_t = 1;
    bool tir = true;
};

FresnelRef fresnel_ref(float cos_i, float eta_f) {
    FresnelRef out;
    const double ci = std::clamp(double(cos_i), 0.0, 1.0), eta = eta_f;
    out.sin2_t = (1.0 - ci * ci) / (eta * eta);
    if (out.sin2_t >= 1.0) return out;
    out.tir = false;
    if (ci == 0.0) return out;  // grazing, eta != 1: R = 1, T = 0
    const double ct = std::sqrt(1.0 - out.sin2_t);
    const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
    out.r = 0.5 * (rs * rs + rp * rp);
    const double ts = 2 * ci / (ci + eta * ct), tp = 2 * ci / (eta * ci + ct);
    out.t = eta * ct / ci * 0.5 * (ts * ts + tp * tp);
    return out;
}

/// Tolerance of the float R: the only rounding that matters is that of cos^2_t =
/// ((eta - 1)(eta + 1) + ci^2) / eta^2 (a few ulps of its terms), amplified by dR / d(cos^2_t),
/// which diverges like 1 / cos_t at the critical angle. Plus 1e-6 for the rest.
double r_tolerance(float cos_i, float eta_f) {
    const double ci = std::clamp(double(cos_i), 0.0, 1.0), eta = eta_f;
    const double c2 = 1.0 - (1.0 - ci * ci) / (eta * eta);
    if (!(c2 > 0.0) || ci == 0.0) return 1e-6;
    auto r_of = [&](double cos2_t) {
        const double ct = std::sqrt(std::max(cos2_t, 0.0));
        const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
        return 0.5 * (rs * rs + rp * rp);
    };
    const double err = 8 * float_eps * (std::fabs((eta - 1) * (eta + 1)) + ci * ci) / (eta * eta);
    const double slope = std::fabs(r_of(c2 + err) - r_of(std::max(c2 - err, 0.0)));
    return 1e-6 + slope;
}

/// The cosine grid: exact ends, tiny values, 1 + 1 ulp (a dot product of unit vectors), values
/// that are not cosines, and the floats around each critical angle of the eta grid.
std::vector<float> cosine_grid() {
    std::vector<float> c = {0.0f,
                            -0.0f,
                            0x1.0p-126f,
                            1e-30f,
                            1e-7f,
                            1e-4f,
                            0.01f,
                            0.1f,
                            0.5f,
                            0.7071f,
                            0.9f,
                            0.999f,
                            1.0f,
                            1.5f,
                            -1e-7f,
                            -0.5f,
                            -1.0f,
                            nan_f,
                            inf_f,
                            -inf_f,
                            std::nextafter(1.0f, 0.0f),
                            std::nextafter(1.0f, 2.0f)};
    for (float eta : etas) {
        if (!(eta < 1.0f)) continue;
        float critical = float(std::sqrt(1.0 - double(eta) * eta));
        for (int k = 0; k < 4; ++k) critical = std::nextafter(critical, 0.0f);
        for (int k = 0; k < 9; ++k, critical = std::nextafter(critical, 1.0f))
            c.push_back(critical);
        for (double rel : {1e-6, 1e-4, 1e-2}) {
            const double cc = std::sqrt(1.0 - double(eta) * eta);
            c.push_back(float(cc * (1 + rel)));
            c.push_back(float(cc * (1 - rel)));
        }
    }
    return c;
}

std::string fresnel_where(float ci, float eta) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "cos_i %.9g (bits %08x), eta %.9g", double(ci),
                  std::bit_cast<uint32_t>(ci), double(eta));
    return buf;
}

TEST(FresnelGrid, ConservesEnergyWithoutNaNForEveryIndexAndCosine) {
    int checked = 0;
    double worst_sum = 0, worst_r = 0;
    for (float eta : etas) {
        for (float ci : cosine_grid()) {
            const std::string at = fresnel_where(ci, eta);
            const float r = fresnel_dielectric(ci, eta);
            ASSERT_FALSE(std::isnan(r)) << at;
            EXPECT_TRUE(r >= 0.0f && r <= 1.0f) << at << ": R = " << r;
            if (std::isnan(ci)) {
                EXPECT_EQ(r, 1.0f) << "a NaN cosine is treated as grazing";
                continue;
            }
            const FresnelRef ref = fresnel_ref(ci, eta);
            const double tol = r_tolerance(ci, eta);
            // away from the TIR decision boundary the float path must decide as the oracle does
            if (std::fabs(ref.sin2_t - 1.0) > 1e-5) {
                EXPECT_NEAR(r, ref.r, tol) << at;
                EXPECT_NEAR(double(r) + ref.t, 1.0, tol) << at << ": R + T";
                worst_r = std::max(worst_r, std::fabs(r - ref.r));
                worst_sum = std::max(worst_sum, std::fabs(double(r) + ref.t - 1.0));
                ++checked;
            }
            if (eta == 1.0f && ci > 0.0f) {
                EXPECT_EQ(r, 0.0f) << at << ": index-matched";
            }
            // the three-argument form with the oracle's cos_t agrees with the two-argument form
            if (!ref.tir && ci > 0.0f) {
                const float ct = float(std::sqrt(1.0 - ref.sin2_t));
                EXPECT_NEAR(fresnel_dielectric(ci, eta, ct), ref.r, tol + 1e-6) << at;
            }
        }
    }
    EXPECT_GT(checked, 150);
    std::printf("fresnel grid: %d points, max |R - R_ref| %.3g, max |R + T_ref - 1| %.3g\n",
                checked, worst_r, worst_sum);
}

TEST(FresnelGrid, RisesContinuouslyToOneAtTheCriticalAngle) {
    for (float eta : {1.0f / 1.0001f, 1.0f / 1.5f, 0.25f}) {
        const double cc = std::sqrt(1.0 - double(eta) * eta);        // cos of the critical angle
        const double cb = 1.0 / std::sqrt(1.0 + double(eta) * eta);  // cos of Brewster's angle
        // from Brewster's angle (R dips there, r_p = 0) to the critical angle R only rises
        float previous = 0.0f;
        for (double rel : {1.0, 0.5, 0.1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
            const float ci = float(cc + (cb - cc) * rel);
            const float r = fresnel_dielectric(ci, eta);
            EXPECT_GE(r, previous) << fresnel_where(ci, eta);
            previous = r;
        }
        // the last float cosine that still refracts, and the first that does not
        float ci = float(cc);
        while (fresnel_dielectric(ci, eta) == 1.0f) ci = std::nextafter(ci, 1.0f);
        while (fresnel_dielectric(std::nextafter(ci, 0.0f), eta) < 1.0f)
            ci = std::nextafter(ci, 0.0f);
        const float last = fresnel_dielectric(ci, eta);
        EXPECT_GT(last, 0.99f) << fresnel_where(ci, eta) << ": no jump at the TIR boundary";
        EXPECT_LT(last, 1.0f);
        EXPECT_EQ(fresnel_dielectric(std::nextafter(ci, 0.0f), eta), 1.0f);
        EXPECT_NEAR(double(ci), cc, 1e-6) << "the boundary sits at the critical angle";
        std::printf("eta %.6g: last refracting cos_i %.9g (critical %.9g), R there %.6f\n",
                    double(eta), double(ci), cc, double(last));
    }
}

TEST(FresnelGrid, RefractsWithoutNaNAndDecidesTotalInternalReflectionAsTheOracle) {
    const vec3 n(0.0f, 0.0f, 1.0f);
    for (float eta : etas) {
        for (float c : cosine_grid()) {
            if (!(c >= 0.0f && c <= 1.0f)) continue;
            const float s = float(std::sqrt(std::max(0.0, 1.0 - double(c) * c)));
            const vec3 d(s, 0.0f, -c);  // cos_i = -d.n = c exactly
            vec3 t(nan_f);
            float cos_t = nan_f;
            const bool refracts = refract_direction(d, n, eta, t, cos_t);
            const std::string at = fresnel_where(c, eta);
            ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << at;
            ASSERT_TRUE(cos_t >= 0.0f && cos_t <= 1.0f) << at << ": cos_t " << cos_t;
            const FresnelRef ref = fresnel_ref(c, eta);
            if (eta == 1.0f) {
                EXPECT_TRUE(refracts) << at;
                EXPECT_EQ(t, d) << at << ": eta = 1 goes straight on";
                continue;
            }
            if (std::fabs(ref.sin2_t - 1.0) > 1e-5) {
                EXPECT_EQ(refracts, !ref.tir) << at;
            }
            if (!refracts) {
                EXPECT_EQ(t, reflect_direction(d, n)) << at;
                EXPECT_EQ(cos_t, 0.0f) << at;
                EXPECT_EQ(fresnel_dielectric(c, eta), 1.0f) << at;
            } else {
                EXPECT_NEAR(glm::length(t), 1.0f, 2e-6f) << at;
                EXPECT_LE(t.z, 0.0f) << at << ": the refracted ray continues below";
                EXPECT_NEAR(-t.z, cos_t, 2e-6f) << at;
            }
        }
    }
}

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class FresnelGridPacket : public ::testing::Test {};
TYPED_TEST_SUITE(FresnelGridPacket, Widths, WidthName);

/// No transcendental function is involved, so every lane must equal the scalar bit for bit:
/// R, the TIR decision, the refracted direction and cos_t.
TYPED_TEST(FresnelGridPacket, MatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    struct Case {
        float c, eta;
    };
    std::vector<Case> cases;
    for (float eta : etas)
        for (float c : cosine_grid()) cases.push_back({c, eta});
    while (cases.size() % W != 0) cases.push_back(cases.front());
    const vec3 n(0.0f, 0.0f, 1.0f);
    for (size_t i = 0; i < cases.size(); i += W) {
        float cs[W], es[W], dx[W], dz[W], zeros[W], ones[W];
        for (int k = 0; k < W; ++k) {
            const Case& c = cases[i + size_t(k)];
            cs[k] = c.c, es[k] = c.eta, zeros[k] = 0.0f, ones[k] = 1.0f;
            const float cc = std::clamp(c.c, 0.0f, 1.0f);  // NaN -> 0 here: d must be finite
            dz[k] = -(cc == cc ? cc : 0.0f);
            dx[k] = float(std::sqrt(std::max(0.0, 1.0 - double(dz[k]) * dz[k])));
        }
        const vfloat<W> c = load<W>(cs), eta = load<W>(es);
        const vfloat<W> r = fresnel_dielectric<W>(c, eta);
        const Vec3<W> d = load_vec3<W>(dx, zeros, dz), nn = load_vec3<W>(zeros, zeros, ones);
        Vec3<W> t;
        vfloat<W> cos_t;
        const vmask<W> refracts = refract_direction<W>(d, nn, eta, t, cos_t);
        for (int k = 0; k < W; ++k) {
            const Case& cs1 = cases[i + size_t(k)];
            const std::string at = fresnel_where(cs1.c, cs1.eta);
            EXPECT_EQ(std::bit_cast<uint32_t>(get(r, k)),
                      std::bit_cast<uint32_t>(fresnel_dielectric(cs1.c, cs1.eta)))
                << at;
            vec3 ts;
            float cts;
            const vec3 ds(dx[k], 0.0f, dz[k]);
            EXPECT_EQ(get(refracts, k), refract_direction(ds, n, cs1.eta, ts, cts)) << at;
            EXPECT_EQ(vec3(get(t.x, k), get(t.y, k), get(t.z, k)), ts) << at;
            EXPECT_EQ(get(cos_t, k), cts) << at;
        }
    }
}

// ---- rendered: a glass slab and its infinite series of internal bounces ----------------------

/// numerics.md §9: a glass slab (index 1.5, thickness 0.5, filter (0.5, 0.8, 1) per unit) in
/// front of an emitting wall of radiance 1, black background, seen almost head-on (field of view
/// 0.5 degrees), depth limit 64. Light reaches the camera only through the slab, after 0, 2, 4 ...
/// internal reflections, so each pixel is the series
///   (1 - R)^2 a / (1 - R^2 a^2),  a = filter^(L / cos_t),
/// R the exact Fresnel reflectance at the pixel ray's incidence (the same at both faces).
SceneData glass_slab(float thickness) {
    SceneData s;
    s.camera.position = vec3(0.0f, 0.0f, -4.0f);
    s.camera.look_at = vec3(0.0f);
    s.camera.fov_deg = 0.5f;
    s.camera.width = 9;
    s.camera.height = 9;
    s.background = vec3(0.0f);
    s.shading.max_refraction_depth = 64;
    Material glass;
    glass.refractive = true;
    glass.ior = 1.5f;
    glass.filter = vec3(0.5f, 0.8f, 1.0f);
    Material wall;
    wall.emission = vec3(1.0f);
    s.materials = {glass, wall};
    s.boxes.push_back(Box{vec3(-1.0f, -1.0f, 0.0f), vec3(1.0f, 1.0f, thickness)});
    s.boxes.push_back(Box{vec3(-5.0f, -5.0f, 2.0f), vec3(5.0f, 5.0f, 2.1f)});
    for (uint32_t i = 0; i < 2; ++i) {
        Object o;
        o.kind = ShapeKind::box;
        o.shape = i;
        o.material = i;
        s.objects.push_back(o);
    }
    return s;
}

void expect_slab_series(const SceneData& s, const RenderResult& r, const std::string& path) {
    EXPECT_EQ(r.stats.bad_samples(), 0u) << path;
    const CameraFrame frame = make_camera_frame(s.camera);
    const double thickness = s.boxes[0].hi.z, eta = s.materials[0].ior;
    double worst = 0;
    for (int y = 0; y < s.camera.height; ++y) {
        for (int x = 0; x < s.camera.width; ++x) {
            const Ray ray = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const glm::dvec3 d = glm::normalize(glm::dvec3(ray.dir));
            const FresnelRef f = fresnel_ref(float(d.z), float(eta));
            ASSERT_FALSE(f.tir);
            const double cos_t = std::sqrt(1.0 - f.sin2_t), length = thickness / cos_t;
            // each end of the inside segment starts at an offset origin, up to 2^-16 reach from
            // the face (core/offset.h; the face coordinate z is near 0): the length changes by
            // up to two such offsets over cos_t
            const double reach = ray_reach(ray, 4.0f / float(d.z)) + 2.0;
            const double dl = 2 * 0x1.0p-16 * reach / cos_t;
            const vec3 v = r.film.at(x, y);
            for (int c = 0; c < 3; ++c) {
                const double sigma = -std::log(double(s.materials[0].filter[c]));
                const double a = std::exp(-sigma * length);
                const double expected = (1 - f.r) * (1 - f.r) * a / (1 - f.r * f.r * a * a);
                const double tol = expected * (1e-5 + sigma * dl);
                EXPECT_NEAR(v[c], expected, tol)
                    << path << " pixel " << x << "," << y << " channel " << c;
                worst = std::max(worst, std::fabs(v[c] - expected) / expected);
            }
        }
    }
    // the clear channel: (1 - R) / (1 + R) = 0.923 at normal incidence, nothing like 1 - R
    EXPECT_NEAR(r.film.at(4, 4).z, (1 - 0.04) / (1 + 0.04), 1e-5) << path;
    std::printf("%s: glass slab, max relative error %.3g against the infinite series\n",
                path.c_str(), worst);
}

TEST(FresnelSlab, TransmitsTheInfiniteSeriesOfInternalReflections) {
    const SceneData s = glass_slab(0.5f);
    const Accel accel = build_accel(s, BuildParams{});
    expect_slab_series(s, render_scalar(s, accel, RenderParams{}), "scalar");
}

TYPED_TEST(FresnelGridPacket, SlabTransmitsTheInfiniteSeriesOfInternalReflections) {
    constexpr int W = TypeParam::value;
    const SceneData s = glass_slab(0.5f);
    const Accel accel = build_accel(s, BuildParams{});
    expect_slab_series(s, render_packet_width<W>(s, accel, RenderParams{}),
                       "packet W=" + std::to_string(W));
}

// ---- nested glass: a sample's ray tree stays bounded (scene.h: glass_fork_depth) -------------

/// A camera inside two nested glass boxes, looking at two concentric glass spheres: nearly every
/// ray meets glass again, so without glass_fork_depth each interaction doubles the rays (this
/// 2x2 image traced 551,120 glass rays at depth 28, and ran out of memory at depth 64).
SceneData nested_glass(int depth, const std::string& more_shading = "") {
    return load_scene_from_string(
        R"({"version": 1,
            "camera": {"position": [0, 1, -5], "look_at": [0, 0.5, 0], "fov_deg": 60,
                       "resolution": [2, 2], "spp": 1},
            "materials": {"glass": {"refraction": {"ior": 1.5}}},
            "objects": [
              {"shape": "sphere", "center": [0, 0.5, 0], "radius": 1, "material": "glass"},
              {"shape": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "glass"},
              {"shape": "box", "min": [-10, -10, -10], "max": [10, 10, 10], "material": "glass"},
              {"shape": "box", "min": [-11, -11, -11], "max": [11, 11, 11], "material": "glass"}],
            "lights": [{"type": "point", "position": [-3, 5, -4], "intensity": 40}],
            "shading": {"max_refraction_depth": )" +
            std::to_string(depth) + more_shading + "}}",
        "nested_glass.json");
}

/// The most glass rays one camera sample can trace at a depth limit: a full binary tree while
/// paths fork (2 + 4 + ... + 2^F rays), then 2^F paths of one ray per interaction.
uint64_t glass_ray_bound(int depth) {
    const int f = std::min(depth, glass_fork_depth);
    return (uint64_t(2) << f) - 2 + (uint64_t(1) << f) * uint64_t(depth - f);
}

TEST(FresnelNested, GlassInGlassTracesABoundedTreeAtEveryDepthLimit) {
    for (const int depth : {4, 28, 64}) {
        const SceneData s = nested_glass(depth);
        const Accel accel = build_accel(s, BuildParams{});
        const RenderResult r = render_scalar(s, accel, RenderParams{});
        const uint64_t rays = r.stats.reflection_rays + r.stats.refraction_rays;
        EXPECT_GT(rays, 4u * uint64_t(depth)) << depth;         // the glass is met again and again
        ASSERT_LE(rays, 4u * glass_ray_bound(depth)) << depth;  // (the next depth: 2^64 rays)
        EXPECT_EQ(r.stats.bad_samples(), 0u) << depth;
    }
}

TYPED_TEST(FresnelGridPacket, NestedGlassTracesTheScalarTree) {
    constexpr int W = TypeParam::value;
    // the depths, and past the fork limit with each switch of the glass term
    const std::vector<std::pair<int, std::string>> cases = {
        {4, ""},
        {28, ""},
        {64, ""},
        {28, R"(, "reflection": false)"},
        {28, R"(, "refraction": false)"},
        {28, R"(, "reflected_color": [1, 0, 1])"}};
    for (const auto& [depth, shading] : cases) {
        const SceneData s = nested_glass(depth, shading);
        const Accel accel = build_accel(s, BuildParams{});
        const RenderResult scalar = render_scalar(s, accel, RenderParams{});
        ASSERT_LE(scalar.stats.reflection_rays + scalar.stats.refraction_rays,
                  4u * glass_ray_bound(depth));  // (the next depth: 2^64 rays)
        const RenderResult packet = render_packet_width<W>(s, accel, RenderParams{});
        ASSERT_EQ(packet.stats.reflection_rays, scalar.stats.reflection_rays) << depth << shading;
        ASSERT_EQ(packet.stats.refraction_rays, scalar.stats.refraction_rays) << depth << shading;
        for (size_t i = 0; i < scalar.film.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(packet.film.pixels[i][c], scalar.film.pixels[i][c],
                            1e-5f * scalar.film.pixels[i][c] + 1e-7f)
                    << depth << shading << " pixel " << i;
    }
}

}  // namespace
}  // namespace raylane
