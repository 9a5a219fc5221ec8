// Numerical stability suite, shading (numerics.md §14): light samples of
// shade/lights_scalar.h and lights_packet.h from shading points on a point light, at tiny
// distances from it, on the plane of area lights, exactly on area-light samples and behind the
// lights; rendered scenes with lights lying on and inside surfaces; and the point light over a
// diffuse plane against its analytic irradiance I h / (h^2 + x^2)^(3/2).
// Raylane's area lights are sets of point lights (intensity / d^2 each, no cosine at the light,
// scene.h), so there is no area-to-solid-angle pdf to diverge at grazing or behind the light.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/offset.h"
#include "render/camera_rays.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "shade/lights_packet.h"
#include "shade/lights_scalar.h"
#include "simd/lanes.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

using dvec3 = glm::dvec3;

/// One light sample request: the light, the shading point, the sample (i of n) and uniforms.
struct Query {
    Light light;
    vec3 origin;
    int i = 0, n = 1;
    float u1 = 0.5f, u2 = 0.5f, u3 = 0.5f;
    std::string what;
};

Light point_light(vec3 p, float intensity) {
    Light l;
    l.kind = LightKind::point;
    l.position = p;
    l.intensity = intensity;
    return l;
}

Light area_light(LightKind kind, float intensity) {
    Light l;
    l.kind = kind;
    l.position = kind == LightKind::disk ? vec3(0.5f, 2.0f, -0.25f) : vec3(-0.5f, 2.0f, -1.0f);
    l.edge_u = kind == LightKind::box ? vec3(1.0f, 0.5f, 2.0f) : vec3(1.0f, 0.0f, 0.0f);
    l.edge_v = vec3(0.0f, 0.0f, 2.0f);
    l.direction = vec3(0.0f, -1.0f, 0.0f);
    l.radius = 0.75f;
    l.samples = 9;
    l.intensity = intensity;
    return l;
}

/// Shading points on, near and behind every kind of light. Points that coincide with the
/// sample exactly are made from the scalar sample point, which the packet path reproduces bit
/// for bit for rectangles, boxes and the disc's centre (no transcendental function there).
std::vector<Query> queries() {
    std::vector<Query> out;
    const float tiny[] = {1.0f,   1e-3f,    1e-10f, 1e-15f, 1e-18f,
                          3e-19f, 1.2e-19f, 8e-20f, 1e-30f, 1e-40f};
    for (float intensity : {1.0f, 1e3f, 1e6f}) {
        for (vec3 at : {vec3(0.0f), vec3(1.0f, 2.0f, 3.0f), vec3(-3e4f, 1e4f, 5e3f)}) {
            const Light l = point_light(at, intensity);
            out.push_back({l, at, 0, 1, 0.5f, 0.5f, 0.5f, "point light at the shading point"});
            for (float d : tiny) {
                for (vec3 dir : {vec3(1, 0, 0), vec3(0, -1, 0), glm::normalize(vec3(1, 1, -1))}) {
                    const vec3 o = at + d * dir;
                    if (o == at) continue;  // d below the position's ulp
                    char what[96];
                    std::snprintf(what, sizeof what, "point light at (%g, %g, %g), %g away, I %g",
                                  double(at.x), double(at.y), double(at.z), double(d),
                                  double(intensity));
                    out.push_back({l, o, 0, 1, 0.5f, 0.5f, 0.5f, what});
                }
            }
        }
    }
    for (LightKind kind : {LightKind::rect, LightKind::disk, LightKind::box}) {
        for (float intensity : {1.0f, 1e3f}) {
            const Light l = area_light(kind, intensity);
            const std::string name = kind == LightKind::rect   ? "rect"
                                     : kind == LightKind::disk ? "disk"
                                                               : "box";
            for (int i = 0; i < l.samples; ++i) {
                const float u1 = 0.1f * float(i), u2 = 1.0f - 0.1f * float(i), u3 = 0.37f;
                const vec3 p = area_light_point(l, stratified_square(i, l.samples, u1, u2), u3);
                // exactly on the sample: disc samples other than the centre differ by ulps
                // between the paths (vector cos / sin), so only its centre is used there
                if (kind != LightKind::disk)
                    out.push_back({l, p, i, l.samples, u1, u2, u3, name + " on its sample"});
                // in the light's plane (grazing), just in front, behind, and far behind
                for (vec3 off :
                     {vec3(0.3f, 0.0f, 0.1f), vec3(0.0f, 1e-6f, 0.0f), vec3(0.0f, -1e-6f, 0.0f),
                      vec3(0.0f, 5.0f, 0.0f), vec3(2.0f, 0.0f, 0.0f)}) {
                    out.push_back({l, p + off, i, l.samples, u1, u2, u3, name + " near/behind"});
                }
            }
            if (kind == LightKind::disk) {
                // the disc's centre is the sample of (1/2, 1/2): stratum 4 of 9 at jitter 1/2
                out.push_back({l, l.position, 4, 9, 0.5f, 0.5f, 0.5f, "disk on its centre sample"});
            }
        }
    }
    return out;
}

/// A valid sample must be usable as it is: finite unit direction, finite positive distance and
/// factor. An invalid one is only allowed where no usable sample exists: the point sits on the
/// light (d^2 == 0) or is so close that I / d^2 overflows.
void expect_usable(const Query& q, const LightSample& s, const std::string& path) {
    const std::string at = path + " " + q.what;
    const vec3 p = q.light.kind == LightKind::point
                       ? q.light.position
                       : area_light_point(q.light, stratified_square(q.i, q.n, q.u1, q.u2), q.u3);
    const vec3 to = p - q.origin;
    const float d2 = glm::dot(to, to);
    if (!s.valid) {
        EXPECT_TRUE(d2 == 0.0f || !(q.light.intensity / d2 < infinity))
            << at << ": no sample although d^2 = " << d2;
        return;
    }
    EXPECT_TRUE(finite3(s.dir)) << at;
    EXPECT_NEAR(glm::length(dvec3(s.dir)), 1.0, 1e-6) << at;
    EXPECT_TRUE(std::isfinite(s.distance) && s.distance > 0.0f) << at << ": " << s.distance;
    EXPECT_TRUE(std::isfinite(s.factor) && s.factor > 0.0f)
        << at << ": factor " << s.factor << " at d^2 = " << d2;
}

TEST(LightExtremes, SamplesOnAndNearLightsAreFiniteOrAbsent) {
    int invalid = 0, valid = 0;
    for (const Query& q : queries()) {
        const LightSample s = sample_light(q.light, q.origin, q.i, q.n, q.u1, q.u2, q.u3);
        expect_usable(q, s, "scalar");
        (s.valid ? valid : invalid) += 1;
    }
    std::printf("light queries: %d valid, %d on the light\n", valid, invalid);
    EXPECT_GT(invalid, 10);
}

// ---- rendered -------------------------------------------------------------------------------

/// A floor plane and a sphere resting on it, with every light placed badly: a point light on the
/// floor, one on the sphere's surface, one inside the sphere, a rectangle lying in the floor, a
/// box light half under the floor, a disc light centred on the sphere's top, and a directional
/// light grazing the floor.
SceneData lights_on_surfaces() {
    SceneData s;
    s.camera.position = vec3(0.0f, 2.0f, -6.0f);
    s.camera.look_at = vec3(0.0f, 0.5f, 0.0f);
    s.camera.fov_deg = 50.0f;
    s.camera.width = 40;
    s.camera.height = 30;
    Material m;
    m.c_d = vec3(0.8f);
    m.k_s = 0.5f;
    m.exponent = 100.0f;
    s.materials.push_back(m);
    s.planes.push_back(Plane{vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)});
    s.spheres.push_back(Sphere{vec3(0.0f, 1.0f, 0.0f), 1.0f});
    Object plane;
    plane.kind = ShapeKind::plane;
    s.objects.push_back(plane);
    s.objects.push_back(Object{});                         // the sphere
    Light l = point_light(vec3(1.5f, 0.0f, -1.0f), 5.0f);  // on the floor
    s.lights.push_back(l);
    l.position = vec3(0.0f, 1.0f, -1.0f);  // on the sphere (exactly representable)
    l.color = vec3(1.0f, 0.0f, 0.5f);      // a zero channel: 0 * inf would be NaN
    s.lights.push_back(l);
    l.position = vec3(0.0f, 1.0f, 0.0f);  // inside the sphere
    s.lights.push_back(l);
    Light rect = area_light(LightKind::rect, 3.0f);
    rect.position = vec3(-2.0f, 0.0f, -2.0f);  // in the floor's plane
    rect.edge_u = vec3(4.0f, 0.0f, 0.0f);
    rect.edge_v = vec3(0.0f, 0.0f, 3.0f);
    s.lights.push_back(rect);
    Light box = area_light(LightKind::box, 2.0f);
    box.position = vec3(1.0f, -0.5f, -2.0f);  // straddles the floor
    box.edge_u = vec3(1.0f, 1.0f, 1.0f);
    s.lights.push_back(box);
    Light disk = area_light(LightKind::disk, 2.0f);
    disk.position = vec3(0.0f, 2.0f, 0.0f);  // centred on the sphere's top
    disk.direction = vec3(0.0f, 1.0f, 0.0f);
    s.lights.push_back(disk);
    Light sun;
    sun.kind = LightKind::directional;
    sun.direction = glm::normalize(vec3(1.0f, 1e-6f, 0.0f));  // grazing the floor
    s.lights.push_back(sun);
    return s;
}

void expect_finite_image(const RenderResult& r, const std::string& path) {
    EXPECT_EQ(r.stats.nan_samples, 0u) << path;
    EXPECT_EQ(r.stats.inf_samples, 0u) << path;
    for (size_t i = 0; i < r.film.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = r.film.pixels[i][c];
            ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << path << " pixel " << i << ": " << v;
        }
    EXPECT_GT(r.stats.shadow_rays, 0u) << path;
}

TEST(LightExtremes, LightsLyingOnAndInsideSurfacesRenderWithoutNaN) {
    const SceneData s = lights_on_surfaces();
    const Accel accel = build_accel(s, BuildParams{});
    RenderParams p;
    p.spp = 2;
    expect_finite_image(render_scalar(s, accel, p), "scalar");
}

/// A white diffuse plane (Phong material: k_d c_d cos / d^2, no 1/pi) seen from straight above,
/// under a point light of intensity I at height h: each pixel is I h / (h^2 + x^2)^(3/2) at its
/// hit point (a case error-vs-time.md's "Analytic references" leaves to this test). Light is
/// gathered from the shadow-ray origin, 2^-16 times the camera ray's reach above the plane
/// (core/offset.h, near y = 0), which lowers the light by that much: a relative error up to
/// 3 offset / h, allowed for.
SceneData lit_plane(float h) {
    SceneData s;
    s.camera.position = vec3(0.0f, 3.0f, 0.0f);
    s.camera.look_at = vec3(0.0f);
    s.camera.up = vec3(0.0f, 0.0f, 1.0f);
    s.camera.fov_deg = 90.0f;
    s.camera.width = 31;
    s.camera.height = 31;
    Material m;
    m.c_d = vec3(1.0f);
    m.k_s = 0.0f;
    s.materials.push_back(m);
    s.planes.push_back(Plane{vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)});
    Object o;
    o.kind = ShapeKind::plane;
    s.objects.push_back(o);
    s.lights.push_back(point_light(vec3(0.0f, h, 0.0f), 2.0f));
    return s;
}

void expect_irradiance(const SceneData& s, const RenderResult& r, const std::string& path) {
    const CameraFrame frame = make_camera_frame(s.camera);
    const double h = s.lights[0].position.y, intensity = s.lights[0].intensity;
    double worst = 0;
    for (int y = 0; y < s.camera.height; ++y) {
        for (int x = 0; x < s.camera.width; ++x) {
            const Ray ray = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const dvec3 o(ray.org), d(ray.dir);
            const double t = -o.y / d.y;
            const double offset = 0x1.0p-16 * double(ray_reach(ray, float(t)));
            const dvec3 p = o + d * t;
            const double r2 = p.x * p.x + p.z * p.z;
            const double e = intensity * h / std::pow(h * h + r2, 1.5);
            const float v = r.film.at(x, y).x;
            EXPECT_NEAR(v, e, e * (1e-5 + 3 * offset / h)) << path << " pixel " << x << "," << y;
            worst = std::max(worst, std::fabs(v - e) / e);
        }
    }
    std::printf("%s: point light at height %g over a plane, max relative error %.2e\n",
                path.c_str(), h, worst);
}

TEST(LightExtremes, PointLightOverAPlaneGivesTheAnalyticIrradiance) {
    for (float h : {1.0f, 0.01f}) {
        const SceneData s = lit_plane(h);
        expect_irradiance(s, render_scalar(s, build_accel(s, BuildParams{}), RenderParams{}),
                          "scalar");
    }
}

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class LightExtremesPacket : public ::testing::Test {};
TYPED_TEST_SUITE(LightExtremesPacket, Widths, WidthName);

/// The queries through sample_light<W>, grouped by light (the light and the sample index are
/// uniform across a packet): the same valid decisions as the scalar; direction, distance and
/// factor bit for bit for point, rectangle and box lights and at W = 1, within 4 ulps per
/// vector cos / sin for discs; every valid lane usable.
TYPED_TEST(LightExtremesPacket, MatchesTheScalarOnAndNearLights) {
    constexpr int W = TypeParam::value;
    for (const Query& q : queries()) {
        float ox[W], oy[W], oz[W], u1[W], u2[W], u3[W];
        for (int k = 0; k < W; ++k) {
            // lane 0 is the query; the others are the same light from points 1 .. W - 1 away
            const vec3 o = q.origin + vec3(0.0f, float(k), 0.0f);
            ox[k] = o.x, oy[k] = o.y, oz[k] = o.z;
            u1[k] = q.u1, u2[k] = q.u2, u3[k] = q.u3;
        }
        const LightSamplePacket<W> p = sample_light<W>(q.light, load_vec3<W>(ox, oy, oz), q.i, q.n,
                                                       load<W>(u1), load<W>(u2), load<W>(u3));
        for (int k = 0; k < W; ++k) {
            Query lane = q;
            lane.origin = vec3(ox[k], oy[k], oz[k]);
            const LightSample s = sample_light(q.light, lane.origin, q.i, q.n, q.u1, q.u2, q.u3);
            const std::string at = "W=" + std::to_string(W) + " " + q.what;
            ASSERT_EQ(get(p.valid, k), s.valid) << at;
            if (!s.valid) continue;
            LightSample ps;
            ps.valid = true;
            ps.dir = vec3(get(p.dir.x, k), get(p.dir.y, k), get(p.dir.z, k));
            ps.distance = get(p.distance, k);
            ps.factor = get(p.factor, k);
            expect_usable(lane, ps, "packet W=" + std::to_string(W));
            if (W == 1 || q.light.kind != LightKind::disk) {
                EXPECT_EQ(ps.dir, s.dir) << at;
                EXPECT_EQ(std::bit_cast<uint32_t>(ps.distance), std::bit_cast<uint32_t>(s.distance))
                    << at;
                EXPECT_EQ(std::bit_cast<uint32_t>(ps.factor), std::bit_cast<uint32_t>(s.factor))
                    << at;
            } else {
                // the disc point moves by ~4 ulps of the radius: relative to the distance
                const double rel = 4 * 0x1.0p-23 * (1 + q.light.radius / double(s.distance));
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(ps.dir[c], s.dir[c], 2 * rel) << at;
                EXPECT_NEAR(ps.distance, s.distance, rel * s.distance) << at;
                EXPECT_NEAR(ps.factor, s.factor, 2 * rel * s.factor) << at;
            }
        }
    }
}

TYPED_TEST(LightExtremesPacket, LightsLyingOnAndInsideSurfacesRenderAsTheScalar) {
    constexpr int W = TypeParam::value;
    const SceneData s = lights_on_surfaces();
    const Accel accel = build_accel(s, BuildParams{});
    RenderParams p;
    p.spp = 2;
    const RenderResult packet = render_packet_width<W>(s, accel, p);
    expect_finite_image(packet, "packet W=" + std::to_string(W));
    const RenderResult scalar = render_scalar(s, accel, p);
    EXPECT_EQ(packet.stats.shadow_rays, scalar.stats.shadow_rays);
    for (size_t i = 0; i < packet.film.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float a = packet.film.pixels[i][c], b = scalar.film.pixels[i][c];
            EXPECT_NEAR(a, b, 1e-5f * std::max(1.0f, b)) << "W=" << W << " pixel " << i;
        }
}

TYPED_TEST(LightExtremesPacket, PointLightOverAPlaneGivesTheAnalyticIrradiance) {
    constexpr int W = TypeParam::value;
    for (float h : {1.0f, 0.01f}) {
        const SceneData s = lit_plane(h);
        expect_irradiance(s,
                          render_packet_width<W>(s, build_accel(s, BuildParams{}), RenderParams{}),
                          "packet W=" + std::to_string(W));
    }
}

}  // namespace
}  // namespace raylane
