// numerics.md §4 : far, tiny and huge spheres (traverse/sphere_scalar.h,
// sphere_packet.h): rays at the disc hit, rays at the annulus miss, hit points lie on the
// surface within a few ulps, against the double instantiation as the oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/offset.h"
#include "support/geometry_support.h"
#include "traverse/sphere_packet.h"
#include "traverse/sphere_scalar.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// A sphere seen from the origin at distance `dist` (centre along an oblique direction), and
/// rays from the origin to uniform random points of the disc (through the centre, facing the
/// viewer) between radii r_lo and r_hi.
struct FarSphere {
    const char* name;
    float radius;
    float dist;
};

const FarSphere far_spheres[] = {{"unit sphere at 1e2", 1.0f, 1e2f},
                                 {"unit sphere at 1e3", 1.0f, 1e3f},
                                 {"unit sphere at 1e4", 1.0f, 1e4f},
                                 {"r = 1e-3 at 1", 1e-3f, 1.0f}};

Sphere place(const FarSphere& fs) {
    return {vec3(glm::normalize(glm::dvec3(0.3, -0.2, 1.0)) * double(fs.dist)), fs.radius};
}

std::vector<Ray> disc_rays(const Sphere& s, vec3 eye, double r_lo, double r_hi, size_t n,
                           uint32_t seed) {
    const glm::dvec3 c(s.center), w = glm::normalize(c - glm::dvec3(eye));
    const glm::dvec3 u = glm::normalize(glm::cross(w, glm::dvec3(0, 1, 0))), v = glm::cross(w, u);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> s01(0.0, 1.0);
    std::vector<Ray> rays;
    for (size_t i = 0; i < n; ++i) {
        // uniform in the annulus r_lo..r_hi (r_lo = 0: the disc)
        const double rho = std::sqrt(r_lo * r_lo + s01(rng) * (r_hi * r_hi - r_lo * r_lo));
        const double phi = 2.0 * 3.141592653589793 * s01(rng);
        const glm::dvec3 target =
            c + double(s.radius) * rho * (std::cos(phi) * u + std::sin(phi) * v);
        rays.push_back({eye, vec3(glm::normalize(target - glm::dvec3(eye))), 0.0f, infinity});
    }
    return rays;
}

std::vector<float> packet_sphere_t(const Sphere& s, const std::vector<Ray>& rays, auto w) {
    constexpr int W = decltype(w)::value;
    return packet_shape<W>(s, rays, [](const Sphere& sp, const RayPacket<W>& p, vmask<W> a) {
        return intersect_sphere<W>(sp, p, a);
    });
}

TEST(Sphere, FarAndTinySpheresAreHitInsideTheDiscAndMissedOutside) {
    const size_t n = ray_count(100000);
    for (const FarSphere& fs : far_spheres) {
        SCOPED_TRACE(fs.name);
        const Sphere s = place(fs);
        const std::vector<Ray> inside = disc_rays(s, vec3(0.0f), 0.0, 0.95, n, 1);
        const std::vector<Ray> outside = disc_rays(s, vec3(0.0f), 1.05, 1.2, n, 2);
        std::vector<float> t_in, t_out;
        for (const Ray& r : inside) t_in.push_back(intersect_sphere(s, r));
        for (const Ray& r : outside) t_out.push_back(intersect_sphere(s, r));
        EXPECT_EQ(std::count(t_in.begin(), t_in.end(), infinity), 0) << "disc rays missed";
        EXPECT_EQ(std::count_if(t_out.begin(), t_out.end(), [](float t) { return t < infinity; }),
                  0)
            << "annulus rays hit";
        for_each_width([&](auto w) {
            SCOPED_TRACE("W = " + std::to_string(decltype(w)::value));
            EXPECT_EQ(shape_disagreements(t_in, packet_sphere_t(s, inside, w)), 0u);
            EXPECT_EQ(shape_disagreements(t_out, packet_sphere_t(s, outside, w)), 0u);
        });
    }
}

/// The float t against the double instantiation's t of the same ray, in float ulps of t: within
/// the 4 ulps numerics.md §0.3 allows between implementations.
TEST(Sphere, FloatDistanceIsWithinFourUlpsOfTheDoubleOracle) {
    const size_t n = ray_count(100000);
    int64_t worst = 0;
    for (const FarSphere& fs : far_spheres) {
        SCOPED_TRACE(fs.name);
        const Sphere s = place(fs);
        int64_t worst_here = 0;
        for (const Ray& r : disc_rays(s, vec3(0.0f), 0.0, 0.95, n, 3)) {
            const float t = intersect_sphere(s, r);
            const double td = intersect_sphere(s, ray_of<double>(r));
            ASSERT_LT(td, infinity_of<double>);
            worst_here = std::max(worst_here, ulp_distance(t, float(td)));
        }
        EXPECT_LE(worst_here, 4) << "float t vs double t, in ulps of t";
        worst = std::max(worst, worst_here);
    }
    std::printf("[ measured ] sphere: worst float t vs double oracle %lld ulps\n",
                static_cast<long long>(worst));
}

/// A ray from just above a huge sphere, and the depth the closed form gives in double from the
/// same float inputs.
struct NearSurfaceRay {
    std::string name;
    Ray ray;
    double t_exact;
};

/// The nearest root of |org + t dir - center|^2 = r^2 in double, for a ray starting outside the
/// sphere and heading into it: t = c / (-b + sqrt(b^2 - a c)) with f = org - center (exact in
/// double), a = dir . dir, b = f . dir, c = |f|^2 - r^2 (no cancellation for b < 0).
double closed_form_depth(const Sphere& s, const Ray& r) {
    const glm::dvec3 f = glm::dvec3(r.org) - glm::dvec3(s.center), d(r.dir);
    const double a = glm::dot(d, d), b = glm::dot(f, d);
    const double c = glm::dot(f, f) - double(s.radius) * double(s.radius);
    return c / (-b + std::sqrt(b * b - a * c));
}

/// Rays from height h above the sphere along `up` (a unit vector): straight down, and grazing at
/// k times the angle below the horizon at which the ray would touch the sphere, towards
/// `ahead`.
std::vector<NearSurfaceRay> near_surface_rays(const Sphere& s, double h, glm::dvec3 up,
                                              glm::dvec3 ahead) {
    const double r = double(s.radius);
    const vec3 eye(glm::dvec3(s.center) + (r + h) * up);
    std::vector<NearSurfaceRay> out;
    out.push_back({"straight down", {eye, vec3(-up), 0.0f, infinity}, 0.0});
    const double tangent = std::acos(r / (r + h));
    for (double k : {1.01, 1.1, 1.5, 2.0, 5.0, 20.0}) {
        const double angle = k * tangent;
        const vec3 dir(std::cos(angle) * ahead - std::sin(angle) * up);
        char name[64];
        std::snprintf(name, sizeof name, "grazing, %g x the tangent angle", k);
        out.push_back({name, {eye, dir, 0.0f, infinity}, 0.0});
    }
    for (NearSurfaceRay& n : out) n.t_exact = closed_form_depth(s, n.ray);
    return out;
}

/// numerics.md §4: a sphere of radius 1e4 seen from 1 above its surface. c = |f|^2 - r^2 is
/// 2e4 while |f|^2 is 1e8, so a c rounded in float loses 5e-5 of the depth straight down and
/// about 1e-3 at grazing angles. The depth must be within 1e-6 relative of the closed form,
/// straight down (t = 1) and at grazing angles, in an axis-aligned frame with exact coordinates
/// and in an oblique frame where org - center rounds; the packet path gives the same bits at
/// every width.
TEST(Sphere, HugeSphereSeenFromJustAboveGivesTheClosedFormDepth) {
    struct Frame {
        const char* name;
        Sphere sphere;
        glm::dvec3 up, ahead;
        bool exact;  ///< the origin is exactly 1 above the surface: t = 1 straight down
    };
    const glm::dvec3 oblique = glm::normalize(glm::dvec3(1.0, 2.0, -0.5));
    const Frame frames[] = {
        {"axis-aligned", {vec3(0.0f, -1e4f, 0.0f), 1e4f}, {0, 1, 0}, {1, 0, 0}, true},
        {"oblique",
         {vec3(123.4f, -5678.9f, 42.42f), 1e4f},
         oblique,
         glm::normalize(glm::cross(oblique, glm::dvec3(0, 0, 1))),
         false},
    };
    double worst = 0.0;
    for (const Frame& fr : frames) {
        SCOPED_TRACE(fr.name);
        const std::vector<NearSurfaceRay> cases =
            near_surface_rays(fr.sphere, 1.0, fr.up, fr.ahead);
        std::vector<Ray> rays;
        std::vector<float> scalar;
        for (const NearSurfaceRay& n : cases) {
            const float t = intersect_sphere(fr.sphere, n.ray);
            const double err = std::fabs(double(t) - n.t_exact) / n.t_exact;
            EXPECT_LE(err, 1e-6) << n.name << ": t " << t << ", closed form " << n.t_exact;
            std::printf(
                "[ measured ] sphere r = 1e4, 1 above, %s, %s: t %.9g, relative error %.3g\n",
                fr.name, n.name.c_str(), double(t), err);
            worst = std::max(worst, err);
            rays.push_back(n.ray);
            scalar.push_back(t);
        }
        if (fr.exact) {
            EXPECT_EQ(cases[0].t_exact, 1.0) << "straight down from 1 above";
        }
        for_each_width([&](auto w) {
            EXPECT_EQ(shape_disagreements(scalar, packet_sphere_t(fr.sphere, rays, w), 0), 0u)
                << "W = " << decltype(w)::value;
        });
    }
    std::printf("[ measured ] sphere r = 1e4 from 1 above: worst relative depth error %.3g\n",
                worst);
}

/// The hit point the renderer uses (surface_at: org + t dir, no re-projection) lies on the
/// sphere within 4 ulps of its magnitude (numerics.md §4), for far spheres seen from the origin
/// and for spheres at the origin seen from far away (the case where |p| ~ r but t ~ D).
TEST(Sphere, HitPointsLieOnTheSurfaceWithinFourUlps) {
    const size_t n = ray_count(20000);
    for (bool camera_far : {false, true}) {
        for (const FarSphere& fs : far_spheres) {
            SCOPED_TRACE(std::string(fs.name) +
                         (camera_far ? ", camera far, sphere at origin" : ", camera at origin"));
            Sphere s = place(fs);
            vec3 eye(0.0f);
            if (camera_far) {
                eye = -s.center;
                s.center = vec3(0.0f);
            }
            SceneData scene;
            scene.materials.push_back(Material{});
            scene.spheres.push_back(s);
            scene.objects.push_back(Object{});
            const Accel accel = build_accel(scene, BuildParams{});
            double worst = 0.0;
            size_t off = 0;
            for (const Ray& r : disc_rays(s, eye, 0.0, 0.99, n, 4)) {
                const Hit h = intersect_closest(scene, accel, r);
                ASSERT_TRUE(h.hit());
                const vec3 p = surface_at(scene, r, h).position;
                const double err =
                    std::fabs(glm::length(glm::dvec3(p) - glm::dvec3(s.center)) - double(s.radius));
                const double ulps = err / float_ulp(glm::length(glm::dvec3(p)));
                worst = std::max(worst, ulps);
                off += ulps > 4.0;
            }
            EXPECT_EQ(off, 0u) << "hit points off the surface by more than 4 ulps; worst " << worst
                               << " ulps";
            std::printf("[ measured ] sphere %s%s: worst surface error %.3g ulps of |p|\n", fs.name,
                        camera_far ? " (camera far)" : "", worst);
        }
    }
}

/// A sphere at the origin seen from 1e3 and 1e4 radii away, lit from the viewer's side: the
/// shadow ray from every visible lit point (offset_ray_origin along the normal, as shading does)
/// must not hit the sphere itself (acne <= 1e-5, numerics.md §3).
TEST(Sphere, FarViewedSpheresDoNotShadowThemselves) {
    const size_t n = ray_count(100000);
    for (float dist : {1e2f, 1e3f, 1e4f}) {
        SCOPED_TRACE("camera at " + std::to_string(dist));
        SceneData scene;
        scene.materials.push_back(Material{});
        scene.spheres.push_back({vec3(0.0f), 1.0f});
        scene.objects.push_back(Object{});
        const Accel accel = build_accel(scene, BuildParams{});
        const vec3 eye = vec3(glm::normalize(glm::dvec3(0.3, -0.2, -1.0)) * double(dist));
        const vec3 light = eye + vec3(0.0f, 2.0f * dist, 0.0f) * 0.1f;
        std::vector<Ray> shadow;
        for (const Ray& r : disc_rays(scene.spheres[0], eye, 0.0, 0.95, n, 5)) {
            const Hit h = intersect_closest(scene, accel, r);
            ASSERT_TRUE(h.hit());
            const SurfacePoint sp = surface_at(scene, r, h);
            const vec3 ng = glm::dot(sp.geometric_normal, r.dir) > 0.0f ? -sp.geometric_normal
                                                                        : sp.geometric_normal;
            // lit in exact arithmetic: the light is above the tangent plane at the true point
            const glm::dvec3 q = glm::normalize(glm::dvec3(sp.position));
            if (!(glm::dot(glm::dvec3(light) - q, q) > 1e-3 * dist)) continue;
            const vec3 o = offset_ray_origin(sp.position, ng, ray_reach(r, h.t));
            shadow.push_back({o, light - o, 0.0f, 1.0f});
        }
        ASSERT_GT(shadow.size(), n / 2);
        std::vector<uint8_t> scalar;
        for (const Ray& r : shadow) scalar.push_back(intersect_any(scene, accel, r));
        const size_t acne = size_t(std::count(scalar.begin(), scalar.end(), uint8_t{1}));
        const double fraction = double(acne) / double(shadow.size());
        std::printf("[ measured ] sphere seen from %g: acne %.3g (%zu of %zu)\n", double(dist),
                    fraction, acne, shadow.size());
        EXPECT_LE(fraction, 1e-5) << acne << " of " << shadow.size() << " lit points shadowed";
        for_each_width([&](auto w) {
            constexpr int W = decltype(w)::value;
            EXPECT_TRUE(packet_any<W>(scene, accel, shadow) == scalar) << "W = " << W;
        });
    }
}

/// From inside (a refracted ray), the far root: t > 0, ahead of the origin, within 4 ulps of the
/// double t (short exits near the surface too, where c = |f|^2 - r^2 cancels: 962 ulps before c
/// was carried past float's rounding), and the point o + t d (evaluated in double, so only the
/// intersection's error counts) on the sphere within 4 ulps of its magnitude.
TEST(Sphere, OriginInsideGivesTheFarRoot) {
    const Sphere s{vec3(1.5f, -2.0f, 0.25f), 0.75f};
    std::mt19937 rng(9);
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::vector<Ray> rays;
    std::vector<float> scalar;
    for (int i = 0; i < 5000; ++i) {
        const vec3 dir = glm::normalize(vec3(g(rng), g(rng), g(rng)));
        const vec3 off = glm::normalize(vec3(g(rng), g(rng), g(rng)));
        const float depth = i % 2 ? 0.999f : 0.3f;  // near the surface, or well inside
        const Ray r{s.center + (depth * s.radius) * off, dir, 0.0f, infinity};
        const float t = intersect_sphere(s, r);
        ASSERT_TRUE(t > 0.0f && t < infinity);
        EXPECT_LE(ulp_distance(t, float(intersect_sphere(s, ray_of<double>(r)))), 4)
            << "depth " << depth;
        const glm::dvec3 p = glm::dvec3(r.org) + double(t) * glm::dvec3(r.dir);
        const double err = std::fabs(glm::length(p - glm::dvec3(s.center)) - double(s.radius));
        EXPECT_LE(err, 4.0 * float_ulp(glm::length(p))) << "depth " << depth;
        rays.push_back(r);
        scalar.push_back(t);
    }
    for_each_width([&](auto w) {
        EXPECT_EQ(shape_disagreements(scalar, packet_sphere_t(s, rays, w)), 0u)
            << "W = " << decltype(w)::value;
    });
}

/// A tangent ray with an exactly zero discriminant: one hit (the double root), and restarted
/// just past it, none; never NaN, in both paths.
TEST(Sphere, TangentRayHitsAtMostOnceWithoutNaN) {
    struct Case {
        Sphere s;
        Ray r;
    };
    const Case cases[] = {
        {{vec3(0.0f), 1.0f}, {vec3(-5.0f, 1.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)}},
        {{vec3(0.0f), 2.0f}, {vec3(0.0f, -2.0f, 7.0f), vec3(0.0f, 0.0f, -1.0f)}},
        {{vec3(3.0f, 0.0f, 0.0f), 0.5f}, {vec3(3.5f, 4.0f, 0.0f), vec3(0.0f, -2.0f, 0.0f)}},
    };
    std::vector<Ray> rays;
    for (const Case& c : cases) {
        const float t = intersect_sphere(c.s, c.r);
        ASSERT_FALSE(is_nan_bits(t));
        ASSERT_LT(t, infinity) << "a tangent ray touches the closed sphere";
        const vec3 p = c.r.org + t * c.r.dir;
        EXPECT_NEAR(glm::length(p - c.s.center), c.s.radius, 1e-6f);
        Ray after = c.r;
        after.t_min = std::nextafter(t, infinity);
        EXPECT_EQ(intersect_sphere(c.s, after), infinity) << "a second hit on a tangent ray";
        rays.push_back(c.r);
        rays.push_back(after);
    }
    for (size_t k = 0; k < std::size(cases); ++k) {
        const Sphere& s = cases[k].s;
        const std::vector<Ray> two = {rays[2 * k], rays[2 * k + 1]};
        const std::vector<float> want = {intersect_sphere(s, two[0]), intersect_sphere(s, two[1])};
        for_each_width([&](auto w) {
            EXPECT_EQ(shape_disagreements(want, packet_sphere_t(s, two, w)), 0u)
                << "W = " << decltype(w)::value;
        });
    }
}

}  // namespace
}  // namespace raylane
