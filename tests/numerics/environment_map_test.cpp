// Numerical stability suite, shading (numerics.md §15): the latitude-longitude
// environment map of shade/texture_scalar.h and texture_packet.h at the poles, on the seam at
// -x, where u is exactly 1, for tiny, huge, denormal and invalid directions, with garbage in
// inactive packet lanes; and the Whitted forms of the furnace test (error-vs-time.md, "Analytic
// references") in a constant environment map: a perfect mirror shows L everywhere, a clear glass
// sphere shows L (1 - (1 - R) R^(D - 1)) for refraction depth D, which is L as D grows.
// The white-Lambertian furnace needs diffuse surfaces lit by the environment, which the Whitted
// renderer does not compute (report/report_analytic.h), and Raylane has no environment importance
// sampling, so §15's pdf-integral test has nothing to run on.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "render/camera_rays.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "shade/texture_packet.h"
#include "shade/texture_scalar.h"
#include "simd/lanes.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

using dvec3 = glm::dvec3;

/// A W x H image whose texel (x, y) is (x, y, 100 + x + 10 y).
Texture coordinate_image(int width, int height, TextureFilter filter) {
    Texture t;
    t.width = width, t.height = height, t.filter = filter;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            t.texels.insert(t.texels.end(), {float(x), float(y), float(100 + x + 10 * y)});
    return t;
}

std::vector<Texture> textures() {
    std::vector<Texture> out;
    for (TextureFilter f : {TextureFilter::nearest, TextureFilter::bilinear})
        for (auto [w, h] : {std::pair{1, 1}, {2, 1}, {1, 2}, {7, 3}, {16, 8}})
            out.push_back(coordinate_image(w, h, f));
    return out;
}

/// Directions at the poles (with signed zeros and tiny or denormal x, z), on the seam at -x
/// (z = +-0, tiny, denormal: u = 1 or 0), at the horizon, at every magnitude from denormal to
/// FLT_MAX, and invalid ones (zero, NaN, infinite components).
std::vector<vec3> directions() {
    std::vector<vec3> base;
    for (float y : {1.0f, -1.0f}) {
        for (float x : {0.0f, -0.0f, 1e-30f, -1e-38f, 1e-40f, 1e-7f})
            for (float z : {0.0f, -0.0f, 1e-40f, -1e-30f, 1e-7f}) base.push_back(vec3(x, y, z));
    }
    for (float z : {0.0f, -0.0f, 1e-40f, -1e-40f, 1e-30f, -1e-30f, 1e-8f, -1e-8f, 1e-7f, -1e-6f})
        for (float y : {0.0f, 1e-7f, -0.5f}) base.push_back(vec3(-1.0f, y, z));
    base.push_back(vec3(1, 0, 0));
    base.push_back(vec3(0, 0, 1));
    base.push_back(vec3(0, 0, -1));
    std::mt19937_64 rng(31);
    std::normal_distribution<float> g;
    for (int i = 0; i < 500; ++i) base.push_back(vec3(g(rng), g(rng), g(rng)));
    std::vector<vec3> out;
    for (float scale : {1.0f, 1e-30f, 1e-38f, 1e30f, flt_max / 2, flt_max})
        for (const vec3& d : base) out.push_back(d * scale);
    for (vec3 bad :
         {vec3(0.0f), vec3(-0.0f), vec3(nan_f, 0, 1), vec3(0, nan_f, 0), vec3(inf_f, 0, 0),
          vec3(0, -inf_f, 0), vec3(1, inf_f, -inf_f), vec3(flt_max, flt_max, flt_max)})
        out.push_back(bad);
    return out;
}

/// The direction as the arithmetic sees it: the harness sets denormals-are-zero (as every
/// render thread does), so denormal components count as 0.
dvec3 as_seen(vec3 d) {
    auto flush = [](float c) { return std::fabs(c) < std::numeric_limits<float>::min() ? 0.0 : c; };
    return dvec3(flush(d.x), flush(d.y), flush(d.z));
}

bool valid_direction(vec3 d) {
    const bool finite = std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z);
    return finite && as_seen(d) != dvec3(0.0);
}

std::string str(vec3 d) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(d.x), double(d.y), double(d.z));
    return buf;
}

TEST(EnvironmentMapExtremes, EveryDirectionMapsIntoTheUnitSquareOrToNothing) {
    int u_one = 0, u_zero = 0, poles = 0;
    for (const vec3& d : directions()) {
        const vec2 uv = latlong_uv(d);
        if (!valid_direction(d)) {
            EXPECT_TRUE(std::isnan(uv.x) && std::isnan(uv.y)) << str(d) << ": no direction";
            continue;
        }
        ASSERT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f) << str(d) << ": u = " << uv.x;
        ASSERT_TRUE(uv.y >= 0.0f && uv.y <= 1.0f) << str(d) << ": v = " << uv.y;
        u_one += uv.x == 1.0f, u_zero += uv.x == 0.0f, poles += uv.y == 0.0f || uv.y == 1.0f;
        // the latitude is right (v = asin(y / |d|) / pi + 1/2, in double)
        const dvec3 dd = as_seen(d);
        const double m = std::max({std::fabs(dd.x), std::fabs(dd.y), std::fabs(dd.z)});
        const double v = std::asin((dd.y / m) / glm::length(dd / m)) / 3.141592653589793 + 0.5;
        EXPECT_NEAR(uv.y, v, 1e-6) << str(d);
    }
    EXPECT_GT(u_one, 10) << "u = 1.0 exactly is exercised";
    EXPECT_GT(u_zero, 10);
    EXPECT_GT(poles, 50);
    std::printf("environment directions: %d with u = 1, %d with u = 0, %d at a pole\n", u_one,
                u_zero, poles);
}

/// Every look-up reads texels of the image (ASan checks the reads) and returns a texel (nearest)
/// or a blend of texels (bilinear): each channel within the image's range; nothing NaN. The
/// poles read only the top or the bottom row, and a bilinear seam blends the last and the first
/// column alike from both sides.
TEST(EnvironmentMapExtremes, LookupsStayInsideTheImageAtPolesSeamAndUOne) {
    for (const Texture& t : textures()) {
        const std::string name = std::to_string(t.width) + "x" + std::to_string(t.height) +
                                 (t.filter == TextureFilter::nearest ? " nearest" : " bilinear");
        for (const vec3& d : directions()) {
            const vec3 c = environment_lookup(t, d);
            ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))
                << name << " " << str(d);
            if (std::isnan(latlong_uv(d).x)) {
                EXPECT_EQ(c, vec3(0.0f)) << name << " " << str(d) << ": no direction is black";
                continue;
            }
            EXPECT_TRUE(c.x >= 0.0f && c.x <= float(t.width - 1)) << name << " " << str(d);
            EXPECT_TRUE(c.y >= 0.0f && c.y <= float(t.height - 1)) << name << " " << str(d);
            EXPECT_GE(c.z, 100.0f) << name << " " << str(d);
            const vec2 uv = latlong_uv(d);
            if (uv.y == 1.0f) {
                EXPECT_EQ(c.y, 0.0f) << name << " " << str(d) << ": top row";
            }
            if (uv.y == 0.0f) {
                EXPECT_EQ(c.y, float(t.height - 1)) << name << " " << str(d) << ": bottom row";
            }
        }
        if (t.filter == TextureFilter::bilinear) {
            EXPECT_EQ(environment_lookup(t, vec3(-1, 0, 0.0f)),
                      environment_lookup(t, vec3(-1, 0, -0.0f)))
                << name << ": the seam from both sides";
        }
    }
}

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class EnvironmentMapExtremesPacket : public ::testing::Test {};
TYPED_TEST_SUITE(EnvironmentMapExtremesPacket, Widths, WidthName);

/// latlong_uv<W> and environment_lookup<W> against the scalar, bit for bit, with every other
/// lane inactive and holding garbage (NaN, infinite, huge): inactive lanes are 0 and gather
/// nothing out of bounds (ASan).
TYPED_TEST(EnvironmentMapExtremesPacket, MatchesTheScalarBitForBitWithGarbageInactiveLanes) {
    constexpr int W = TypeParam::value;
    const std::vector<vec3> dirs = directions();
    const vec3 garbage[] = {vec3(nan_f), vec3(inf_f, -inf_f, nan_f), vec3(0.0f),
                            vec3(-flt_max, 0, 0)};
    auto same = [](float a, float b) {
        return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) ||
               (std::isnan(a) && std::isnan(b));
    };
    for (const Texture& t : textures()) {
        for (size_t i = 0; i < dirs.size(); i += W) {
            float x[W], y[W], z[W];
            uint32_t active_bits = 0;
            for (int k = 0; k < W; ++k) {
                const size_t j = i + size_t(k);
                // at W > 1 every odd lane is inactive garbage
                const bool active = j < dirs.size() && (W == 1 || k % 2 == 0);
                const vec3 d = active ? dirs[j] : garbage[(j / 2) % 4];
                x[k] = d.x, y[k] = d.y, z[k] = d.z;
                if (active) active_bits |= 1u << k;
            }
            const Vec3<W> d = load_vec3<W>(x, y, z);
            const vmask<W> active = mask_from_bits<W>(active_bits);
            const Uv<W> uv = latlong_uv<W>(d);
            const Vec3<W> c = environment_lookup<W>(t, d, active);
            for (int k = 0; k < W; ++k) {
                const vec3 ds(x[k], y[k], z[k]);
                const vec2 uvs = latlong_uv(ds);
                EXPECT_TRUE(same(get(uv.u, k), uvs.x) && same(get(uv.v, k), uvs.y)) << str(ds);
                const vec3 cp(get(c.x, k), get(c.y, k), get(c.z, k));
                if ((active_bits >> k) & 1u) {
                    const vec3 cs = environment_lookup(t, ds);
                    EXPECT_TRUE(same(cp.x, cs.x) && same(cp.y, cs.y) && same(cp.z, cs.z))
                        << str(ds);
                } else {
                    EXPECT_EQ(cp, vec3(0.0f)) << "inactive lane " << k;
                }
            }
        }
    }
}

// ---- furnaces -------------------------------------------------------------------------------

/// A constant environment of radiance L (4 x 2, bilinear: the seam and the poles are blended
/// like any other texel), one convex object, no light.
SceneData furnace(const Material& m, ShapeKind kind) {
    SceneData s;
    s.camera.position = vec3(0.3f, 0.2f, -4.0f);
    s.camera.look_at = vec3(0.0f);
    s.camera.fov_deg = 36.0f;
    s.camera.width = 32;
    s.camera.height = 32;
    Texture env;
    env.width = 4, env.height = 2;
    env.texels.assign(size_t(4 * 2 * 3), 0.7f);
    s.textures.push_back(env);
    s.environment = 0;
    s.materials.push_back(m);
    Object o;
    o.kind = kind;
    if (kind == ShapeKind::sphere) s.spheres.push_back(Sphere{vec3(0.0f), 1.0f});
    if (kind == ShapeKind::box) s.boxes.push_back(Box{vec3(-0.8f), vec3(0.8f)});
    if (kind == ShapeKind::cylinder) s.cylinders.push_back(Cylinder{0.9f, 1.2f});
    s.objects.push_back(o);
    return s;
}

Material mirror_material() {
    Material m;
    m.k_d = 0.0f;
    m.reflection = 1.0f;
    m.fresnel = false;
    m.c_s = vec3(1.0f);
    return m;
}

/// Every pixel of the mirror furnace is L (within the bilinear blend's rounding).
void expect_mirror_furnace(const RenderResult& r, const std::string& path) {
    EXPECT_EQ(r.stats.bad_samples(), 0u) << path;
    EXPECT_GT(r.stats.reflection_rays, 100u) << path;
    double worst = 0;
    for (size_t i = 0; i < r.film.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(r.film.pixels[i][c], 0.7f, 1e-6 * 0.7) << path << " pixel " << i;
            worst = std::max(worst, std::fabs(r.film.pixels[i][c] - 0.7) / 0.7);
        }
    std::printf("%s: mirror furnace, max |pixel - L| / L = %.2e\n", path.c_str(), worst);
}

/// Exact dielectric Fresnel in double (numerics.md §9).
double fresnel_exact(double ci, double eta) {
    const double s2 = (1 - ci * ci) / (eta * eta);
    if (s2 >= 1) return 1;
    const double ct = std::sqrt(1 - s2);
    const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

/// Glass furnace: a clear sphere of index eta refracts and reflects with the same R at every
/// one of its interactions (the internal angle equals the refracted one), the camera ray's
/// interactions count 0, 1, ... and an interaction at depth >= D is black. So a pixel is
/// R L + (1 - R) (1 - R^(D - 1)) L = L (1 - (1 - R) R^(D - 1)) while D <= glass_fork_depth = F,
/// R from the pixel-centre ray's incidence in double, within the effect of the ray offsets on the
/// internal incidence. Deeper, interaction F goes on with its larger branch only (scene.h): the
/// ray out when R < 1/2, which ends the series at L (1 - (1 - R) R^F); the reflection inside when
/// R >= 1/2, which then never leaves (black at D): L (1 - (1 - R) R^(F - 1)).
/// Silhouette pixels (cos_i < 0.05), where R's slope is large, are left out.
void expect_glass_furnace(const SceneData& s, const RenderResult& r, const std::string& path) {
    EXPECT_EQ(r.stats.bad_samples(), 0u) << path;
    const CameraFrame frame = make_camera_frame(s.camera);
    const double l = 0.7, eta = s.materials[0].ior;
    const int depth = s.shading.max_refraction_depth;
    int inside = 0;
    double worst = 0, darkest = 1;
    for (int y = 0; y < s.camera.height; ++y) {
        for (int x = 0; x < s.camera.width; ++x) {
            const Ray ray = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const dvec3 o(ray.org), d = glm::normalize(dvec3(ray.dir));
            const double b = glm::dot(o, d), disc = b * b - (glm::dot(o, o) - 1.0);
            const vec3 v = r.film.at(x, y);
            for (int c = 0; c < 3; ++c)
                ASSERT_TRUE(v[c] >= 0.0f && v[c] <= l * (1 + 1e-6)) << path << " never above L";
            if (disc <= 0) continue;
            const dvec3 p = o + d * (-b - std::sqrt(disc));
            const double ci = -glm::dot(p, d);
            if (ci < 0.05) continue;
            ++inside;
            auto value = [&](double c) {
                const double rr = fresnel_exact(std::clamp(c, 0.0, 1.0), eta);
                if (depth <= glass_fork_depth) return l * (1 - (1 - rr) * std::pow(rr, depth - 1));
                return l * (1 - (1 - rr) * std::pow(rr, glass_fork_depth - (rr < 0.5 ? 0 : 1)));
            };
            const double want = value(ci);
            // each internal ray starts up to 256 ulps (3e-5 at unit scale, core/offset.h) inside
            // the surface, which moves its next incidence by up to offset / cos_t, i.e. the
            // equivalent outer cosine by eta^2 offset / cos_i; over the first few bounces
            const double shift = std::min(depth, 8) * eta * eta * 256 * 0x1.0p-23 / ci;
            const double tol = 1e-5 + 0.5 * std::fabs(value(ci + shift) - value(ci - shift));
            EXPECT_NEAR(v.x, want, tol) << path << " pixel " << x << "," << y << " cos " << ci;
            worst = std::max(worst, std::fabs(v.x - want));
            darkest = std::min(darkest, double(v.x) / l);
        }
    }
    EXPECT_GT(inside, 300) << path;
    std::printf("%s: glass furnace eta %.2f depth %d, darkest pixel %.6f L, max |error| %.2e\n",
                path.c_str(), eta, depth, darkest, worst);
}

std::vector<SceneData> glass_furnaces() {
    std::vector<SceneData> out;
    for (float eta : {1.5f, 4.0f}) {
        for (int depth : {4, 64}) {
            Material m;
            m.refractive = true;
            m.ior = eta;
            SceneData s = furnace(m, ShapeKind::sphere);
            s.shading.max_refraction_depth = depth;
            out.push_back(s);
        }
    }
    return out;
}

template <class Render>
void check_furnaces(Render render, const std::string& path) {
    for (ShapeKind kind : {ShapeKind::sphere, ShapeKind::box, ShapeKind::cylinder}) {
        const SceneData s = furnace(mirror_material(), kind);
        const char* shape = kind == ShapeKind::sphere ? " mirror sphere"
                            : kind == ShapeKind::box  ? " mirror box"
                                                      : " mirror cylinder";
        expect_mirror_furnace(render(s, build_accel(s, BuildParams{})), path + shape);
    }
    for (const SceneData& s : glass_furnaces())
        expect_glass_furnace(s, render(s, build_accel(s, BuildParams{})), path);
}

TEST(EnvironmentMapExtremes, FurnacesShowTheEnvironmentsRadiance) {
    check_furnaces(
        [](const SceneData& s, const Accel& a) { return render_scalar(s, a, RenderParams{}); },
        "scalar");
}

TYPED_TEST(EnvironmentMapExtremesPacket, FurnacesShowTheEnvironmentsRadiance) {
    constexpr int W = TypeParam::value;
    check_furnaces([](const SceneData& s,
                      const Accel& a) { return render_packet_width<W>(s, a, RenderParams{}); },
                   "packet W=" + std::to_string(W));
}

}  // namespace
}  // namespace raylane
