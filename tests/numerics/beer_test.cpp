// Numerical stability suite, shading (numerics.md §10): Beer's law of
// shade/optics_scalar.h (beer_transmittance) and its packet twin in optics_packet.h on a grid of
// absorbances and distances from 0 through tiny and huge to infinity, against pow in double;
// then a rendered index-matched absorbing sphere, whose every pixel is L filter^chord.
//
// Raylane states absorbance as a per-unit-distance transmittance `filter` = exp(-sigma), so the
// grid's sigma in {0, tiny, 1, large, inf} is filter in {1, 1 - 2^-24, 1/e, 1e-30 .. FLT_MIN, 0}
// (sigma = 6e-8 is the smallest absorbance a float filter can hold).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

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

const float flt_min = std::numeric_limits<float>::min();

/// Valid filters in increasing order (sigma from infinity down to 0).
const std::vector<float> filters = {0.0f,   flt_min,           1e-30f, 1e-3f, 0.3678794f, 0.5f,
                                    0.999f, 1.0f - 0x1.0p-24f, 1.0f};
/// Valid distances in increasing order: 0, a denormal, tiny, 1, large, huge, infinite.
const std::vector<float> distances = {0.0f, 1e-40f, 1e-9f, 1.0f, 1e3f, 1e30f, flt_max, inf_f};
/// Inputs no scene should produce, which must still give a transmittance in [0, 1]: a denormal
/// filter (0 under the harness's denormals-are-zero, as in every render thread), filters outside
/// [0, 1], negative, NaN and -0 distances.
const std::vector<float> odd_filters = {1e-40f, -0.5f, 1.5f, nan_f, inf_f, -inf_f, -0.0f};
const std::vector<float> odd_distances = {-0.0f, -1.0f, -inf_f, nan_f};

/// filter^distance in double with Beer's conventions: d = 0 -> 1, f = 1 -> 1 (also for d = inf),
/// f = 0 and d > 0 -> 0, d = inf and f < 1 -> 0.
double beer_ref(float f, float d) {
    if (d == 0.0f || f == 1.0f) return 1.0;
    if (f == 0.0f) return 0.0;
    return std::pow(double(f), double(d));
}

/// exp(d log f) in float: log's rounding (|ln f| relative) grows by the factor |ln T|, plus the
/// final rounding; values below FLT_MIN flush to zero.
double beer_tolerance(double ref) {
    const double amp = ref > 0 ? std::fabs(std::log(ref)) : 0.0;
    return 2.4e-7 * (2 + amp) * ref + double(flt_min);
}

std::string beer_where(float f, float d) {
    char buf[80];
    std::snprintf(buf, sizeof buf, "filter %.9g, distance %.9g", double(f), double(d));
    return buf;
}

TEST(BeerGrid, StaysInTheUnitIntervalAndFollowsThePowerLaw) {
    double worst = 0;
    for (float f : filters) {
        for (float d : distances) {
            const float t = beer_transmittance(vec3(f), d).x;
            const std::string at = beer_where(f, d);
            ASSERT_TRUE(t >= 0.0f && t <= 1.0f) << at << ": T = " << t;
            // the denormal distance is 0 under denormals-are-zero; T = 1 either way
            const double ref = d == 1e-40f ? 1.0 : beer_ref(f, d);
            EXPECT_NEAR(t, ref, beer_tolerance(ref)) << at;
            if (ref > 1e-30) worst = std::max(worst, std::fabs(t - ref) / ref);
        }
    }
    // sigma = 0 along an infinite path (a ray leaving an open mesh from inside): exp(-0 inf)
    EXPECT_EQ(beer_transmittance(vec3(1.0f), inf_f), vec3(1.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.0f), 0.0f), vec3(1.0f)) << "sigma = inf over d = 0";
    EXPECT_EQ(beer_transmittance(vec3(0.0f), inf_f), vec3(0.0f));
    std::printf("beer grid: max relative error against pow %.3g\n", worst);
}

TEST(BeerGrid, IsMonotoneInBothArguments) {
    for (size_t i = 0; i < filters.size(); ++i) {
        for (size_t j = 0; j < distances.size(); ++j) {
            const float t = beer_transmittance(vec3(filters[i]), distances[j]).x;
            if (j > 0) {
                EXPECT_LE(t, beer_transmittance(vec3(filters[i]), distances[j - 1]).x)
                    << beer_where(filters[i], distances[j]) << ": longer paths absorb more";
            }
            if (i > 0) {
                EXPECT_GE(t, beer_transmittance(vec3(filters[i - 1]), distances[j]).x)
                    << beer_where(filters[i], distances[j]) << ": clearer media absorb less";
            }
        }
    }
}

TEST(BeerGrid, NeverReturnsNaNForInputsOutsideItsDomain) {
    std::vector<float> all_f = filters, all_d = distances;
    all_f.insert(all_f.end(), odd_filters.begin(), odd_filters.end());
    all_d.insert(all_d.end(), odd_distances.begin(), odd_distances.end());
    for (float f : all_f) {
        for (float d : all_d) {
            const vec3 t = beer_transmittance(vec3(f, 0.5f, 1.0f), d);
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(t[c] >= 0.0f && t[c] <= 1.0f) << beer_where(f, d) << " channel " << c;
        }
    }
}

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class BeerGridPacket : public ::testing::Test {};
TYPED_TEST_SUITE(BeerGridPacket, Widths, WidthName);

/// Each filter with the distances spread over the lanes. Decisions (T exactly 0, T exactly 1)
/// are identical; values within (16 + 4 |ln T|) ulps (xsimd's exp, brdf_packet_test.cpp) plus
/// FLT_MIN; W = 1 is the scalar bit for bit.
TYPED_TEST(BeerGridPacket, MatchesTheScalarOnTheWholeGrid) {
    constexpr int W = TypeParam::value;
    std::vector<float> all_f = filters, all_d = distances;
    all_f.insert(all_f.end(), odd_filters.begin(), odd_filters.end());
    all_d.insert(all_d.end(), odd_distances.begin(), odd_distances.end());
    while (all_d.size() % W != 0) all_d.push_back(1.0f);
    double worst = 0;
    for (float f : all_f) {
        const vec3 filter(f, 0.5f, 1.0f - 0x1.0p-24f);
        for (size_t i = 0; i < all_d.size(); i += W) {
            const vfloat<W> d = load<W>(all_d.data() + i);
            const Vec3<W> t = beer_transmittance<W>(filter, d);
            for (int k = 0; k < W; ++k) {
                const float dk = all_d[i + size_t(k)];
                const vec3 s = beer_transmittance(filter, dk);
                const vec3 p(get(t.x, k), get(t.y, k), get(t.z, k));
                for (int c = 0; c < 3; ++c) {
                    const std::string at = beer_where(filter[c], dk);
                    ASSERT_TRUE(p[c] >= 0.0f && p[c] <= 1.0f) << at << ": T = " << p[c];
                    if constexpr (W == 1) {
                        EXPECT_EQ(std::bit_cast<uint32_t>(p[c]), std::bit_cast<uint32_t>(s[c]))
                            << at;
                    } else {
                        EXPECT_EQ(p[c] == 0.0f, s[c] == 0.0f) << at;
                        EXPECT_EQ(p[c] == 1.0f, s[c] == 1.0f) << at;
                        const double amp = s[c] > 0 ? std::fabs(std::log(double(s[c]))) : 0.0;
                        EXPECT_NEAR(p[c], s[c], (16 + 4 * amp) * 0x1.0p-23 * s[c] + flt_min) << at;
                        if (s[c] > 1e-30f)
                            worst = std::max(worst, std::fabs(double(p[c]) - s[c]) / s[c]);
                    }
                }
            }
        }
    }
    std::printf("W=%d beer: max relative deviation from the scalar %.3g\n", W, worst);
}

// ---- rendered: an index-matched absorbing sphere ----------------------------------------------

/// A glass sphere of index 1 (no bending, R = 0) with filter (0.5, 1, 0): sigma = ln 2, 0 and
/// infinity per channel. Background L everywhere. Camera at distance 4, 33 x 33 pixels.
SceneData absorbing_sphere() {
    SceneData s;
    s.camera.position = vec3(0.0f, 0.0f, -4.0f);
    s.camera.look_at = vec3(0.0f);
    s.camera.fov_deg = 34.0f;
    s.camera.width = 33;
    s.camera.height = 33;
    s.background = vec3(0.75f);
    Material glass;
    glass.refractive = true;
    glass.ior = 1.0f;
    glass.filter = vec3(0.5f, 1.0f, 0.0f);
    s.materials.push_back(glass);
    s.spheres.push_back(Sphere{vec3(0.0f), 1.0f});
    Object o;
    o.kind = ShapeKind::sphere;
    s.objects.push_back(o);
    return s;
}

/// Each pixel against L filter^chord, the chord of the pixel-centre ray through the sphere in
/// double, within the offset's effect on the chord. Pixels whose chord is under 0.05 (the
/// silhouette, where the chord's slope is unbounded) only have to lie in [0, L]; the clear channel
/// is L exactly everywhere.
void expect_absorbing_sphere(const SceneData& s, const RenderResult& r, const std::string& path) {
    EXPECT_EQ(r.stats.bad_samples(), 0u) << path;
    const CameraFrame frame = make_camera_frame(s.camera);
    const double l = s.background.x;
    int interior = 0;
    double worst = 0;
    for (int y = 0; y < s.camera.height; ++y) {
        for (int x = 0; x < s.camera.width; ++x) {
            const Ray ray = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const glm::dvec3 o(ray.org), d = glm::normalize(glm::dvec3(ray.dir));
            const double b = glm::dot(o, d), disc = b * b - (glm::dot(o, o) - 1.0);
            const double chord = disc > 0 ? 2 * std::sqrt(disc) : 0.0;
            const vec3 v = r.film.at(x, y);
            const std::string at = path + " pixel " + std::to_string(x) + "," + std::to_string(y);
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(v[c] >= 0.0f && v[c] <= l + 1e-6) << at;
            EXPECT_EQ(v.y, float(l)) << at << ": sigma = 0 absorbs nothing";
            if (chord < 0.05) continue;
            ++interior;
            // the segment inside starts at the refracted ray's origin, moved off the surface by
            // up to 256 ulps (core/offset.h, 256 * 2^-23 at unit scale) along the normal: the
            // chord changes by up to 2 offset / cos(theta) = 4 offset / chord
            const double red = l * std::pow(0.5, chord);
            const double offset = 256 * 0x1.0p-23;
            EXPECT_NEAR(v.x, red, red * std::log(2.0) * (4 * offset / chord + 1e-6) + 1e-6) << at;
            EXPECT_EQ(v.z, 0.0f) << at << ": sigma = inf absorbs everything";
            worst = std::max(worst, std::fabs(v.x - red) / red);
        }
    }
    EXPECT_GT(interior, 100) << path;
    std::printf("%s: absorbing sphere, %d interior pixels, max relative error %.3g\n", path.c_str(),
                interior, worst);
}

TEST(BeerRender, IndexMatchedAbsorbingSphereTransmitsFilterToTheChordLength) {
    const SceneData s = absorbing_sphere();
    const Accel accel = build_accel(s, BuildParams{});
    expect_absorbing_sphere(s, render_scalar(s, accel, RenderParams{}), "scalar");
}

TYPED_TEST(BeerGridPacket, IndexMatchedAbsorbingSphereTransmitsFilterToTheChordLength) {
    constexpr int W = TypeParam::value;
    const SceneData s = absorbing_sphere();
    const Accel accel = build_accel(s, BuildParams{});
    const RenderResult packet = render_packet_width<W>(s, accel, RenderParams{});
    expect_absorbing_sphere(s, packet, "packet W=" + std::to_string(W));
    const RenderResult scalar = render_scalar(s, accel, RenderParams{});
    for (size_t i = 0; i < packet.film.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float a = packet.film.pixels[i][c], b = scalar.film.pixels[i][c];
            EXPECT_NEAR(a, b, 1e-5f * std::max(b, 1e-3f)) << "pixel " << i << " channel " << c;
        }
    }
}

}  // namespace
}  // namespace raylane
