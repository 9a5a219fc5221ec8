// Tests of traverse/{sphere,box,cylinder,plane}_scalar.h: analytic answers, misses, origins
// inside, tangent and parallel rays, and the stiff cases of numerics.md §4-§7.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "support/float_values.h"
#include "traverse/box_scalar.h"
#include "traverse/cylinder_scalar.h"
#include "traverse/plane_scalar.h"
#include "traverse/sphere_scalar.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int disc_rays = 2000;
constexpr int rim_rays = 10000;
constexpr int shape_oracle_rays = 5000;
#else
constexpr int disc_rays = 20000;
constexpr int rim_rays = 100000;
constexpr int shape_oracle_rays = 100000;
#endif

using test::nan_f;

Ray make_ray(vec3 org, vec3 dir, float t_min = 0.0f, float t_max = infinity) {
    Ray r;
    r.org = org;
    r.dir = dir;
    r.t_min = t_min;
    r.t_max = t_max;
    return r;
}

/// Distance from x to the next float away from zero.
double ulp(double x) {
    const float f = static_cast<float>(std::abs(x));
    return static_cast<double>(std::nextafter(f, infinity) - f);
}

/// Unit vectors u, v completing w to an orthonormal frame (double, for test geometry).
void frame(glm::dvec3 w, glm::dvec3& u, glm::dvec3& v) {
    const glm::dvec3 a = std::abs(w.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    u = glm::normalize(glm::cross(a, w));
    v = glm::cross(w, u);
}

// --- sphere ------------------------------------------------------------------------------------

/// Nearest root in (t_min, t_max) of the textbook quadratic in double, on the float inputs.
double sphere_oracle(const Sphere& s, const Ray& ray) {
    const glm::dvec3 f = glm::dvec3(ray.org) - glm::dvec3(s.center), d(ray.dir);
    const double a = glm::dot(d, d), b = glm::dot(f, d);
    const double c = glm::dot(f, f) - double(s.radius) * double(s.radius);
    const double disc = b * b - a * c;
    if (disc < 0.0) return INFINITY;
    const double t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
    if (t0 > ray.t_min && t0 < ray.t_max) return t0;
    if (t1 > ray.t_min && t1 < ray.t_max) return t1;
    return INFINITY;
}

TEST(IntersectSphere, HitsHeadOnAtTheExactDistanceWithOutwardNormal) {
    const Sphere s{vec3(1.0f, 2.0f, 3.0f), 2.0f};
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(1.0f, 2.0f, -5.0f), vec3(0, 0, 1))), 6.0f);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(1.0f, 2.0f, -5.0f), vec3(0, 0, 4))), 1.5f);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(1.0f, 9.0f, 3.0f), vec3(0, -0.5f, 0))), 10.0f);
    const LocalGeometry g = geometry_sphere(s, vec3(1.0f, 2.0f, 1.0f));
    EXPECT_EQ(g.normal, vec3(0.0f, 0.0f, -1.0f));
}

TEST(IntersectSphere, MatchesTheAnalyticHitOffAxis) {
    // Unit sphere, ray along z at x = 0.6: hits z = -0.8, normal (0.6, 0, -0.8).
    const Sphere s{vec3(0.0f), 1.0f};
    const Ray ray = make_ray(vec3(0.6f, 0.0f, -5.0f), vec3(0, 0, 1));
    const float t = intersect_sphere(s, ray);
    EXPECT_NEAR(t, 4.2, 4 * ulp(4.2));
    EXPECT_NEAR(t, sphere_oracle(s, ray), 2 * ulp(4.2));
    const LocalGeometry g = geometry_sphere(s, ray.org + t * ray.dir);
    EXPECT_NEAR(g.normal.x, 0.6f, 4e-7f);
    EXPECT_EQ(g.normal.y, 0.0f);
    EXPECT_NEAR(g.normal.z, -0.8f, 4e-7f);
    EXPECT_NEAR(glm::length(g.normal), 1.0f, 2e-7f);
}

TEST(IntersectSphere, MissesBesideAndBehind) {
    const Sphere s{vec3(0.0f), 1.0f};
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(1.5f, 0.0f, -5.0f), vec3(0, 0, 1))), infinity);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 0.0f, 5.0f), vec3(0, 0, 1))), infinity);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0, 0, 1), 0.0f, 4.0f)),
              infinity);  // open interval: t = 4 is not < t_max
}

TEST(IntersectSphere, ReturnsTheFarRootFromInside) {
    const Sphere s{vec3(0.0f), 2.0f};
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f), vec3(1, 0, 0))), 2.0f);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 1.0f, 0.0f), vec3(0, 2, 0))), 0.5f);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 0.0f, -4.0f), vec3(0, 0, 1), 2.0f)), 6.0f);
    // From a point on the surface going in (refraction): the far side, t > 0.
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 0.0f, -2.0f), vec3(0, 0, 1))), 4.0f);
}

TEST(IntersectSphere, TangentRaysGiveADefinedResult) {
    const Sphere s{vec3(0.0f), 1.0f};
    // Discriminant exactly 0: one touching point at t = 5, or a miss; never NaN.
    const float t = intersect_sphere(s, make_ray(vec3(1.0f, 0.0f, -5.0f), vec3(0, 0, 1)));
    EXPECT_FALSE(std::isnan(t));
    EXPECT_TRUE(t == infinity || std::abs(t - 5.0f) <= 4 * ulp(5.0)) << t;
    // Tangent from a point on the surface (b = 0, disc = 0, q = 0): no hit, no NaN.
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(1.0f, 0.0f, 0.0f), vec3(0, 0, 1))), infinity);
}

TEST(IntersectSphere, NanAndZeroDirectionsNeverHit) {
    const Sphere s{vec3(0.0f), 1.0f};
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0.0f))), infinity);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0, nan_f, 1))), infinity);
    EXPECT_EQ(intersect_sphere(s, make_ray(vec3(nan_f), vec3(0, 0, 1))), infinity);
}

TEST(IntersectSphere, UvFollowsAzimuthAndPolarAngle) {
    const Sphere s{vec3(0.0f), 2.0f};
    EXPECT_EQ(geometry_sphere(s, vec3(0.0f, 2.0f, 0.0f)).uv.y, 0.0f);
    EXPECT_NEAR(geometry_sphere(s, vec3(0.0f, -2.0f, 0.0f)).uv.y, 1.0f, 1e-7f);
    const vec2 uv_x = geometry_sphere(s, vec3(2.0f, 0.0f, 0.0f)).uv;
    EXPECT_EQ(uv_x.x, 0.0f);
    EXPECT_NEAR(uv_x.y, 0.5f, 1e-7f);
    EXPECT_NEAR(geometry_sphere(s, vec3(0.0f, 0.0f, 2.0f)).uv.x, 0.25f, 1e-7f);
    EXPECT_NEAR(geometry_sphere(s, vec3(-2.0f, 0.0f, 0.0f)).uv.x, 0.5f, 1e-7f);
    EXPECT_NEAR(geometry_sphere(s, vec3(0.0f, 0.0f, -2.0f)).uv.x, 0.75f, 1e-7f);
}

/// Distance of the hit point o + t d (in double, from the float t) from the sphere's surface, in
/// ulps of the largest magnitude involved (|p|, |center|, r): numerics.md §4 asks for <= 4.
double surface_error_ulps(const Sphere& s, const Ray& ray, float t) {
    const glm::dvec3 p = glm::dvec3(ray.org) + double(t) * glm::dvec3(ray.dir);
    const double scale =
        std::max({glm::length(p), glm::length(glm::dvec3(s.center)), double(s.radius)});
    return std::abs(glm::length(p - glm::dvec3(s.center)) - s.radius) / ulp(scale);
}

/// Rays from the origin at a sphere of radius r at distance D, aimed at random points of the
/// disc of radius 0.95 r (all must hit, on the surface within 4 ulps, t within 8 ulps of the
/// double oracle) and of the annulus 1.05 r - 1.2 r (all must miss). numerics.md §4.
void expect_sphere_coverage(float distance, float radius, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::normal_distribution<double> normal;
    int hits = 0, misses = 0, wrong_hits = 0, inaccurate = 0;
    double worst_ulps = 0.0;
    for (int i = 0; i < disc_rays; ++i) {
        const glm::dvec3 w = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
        glm::dvec3 e1, e2;
        frame(w, e1, e2);
        const Sphere s{vec3(w * double(distance)), radius};
        const bool inside = i % 2 == 0;
        const double rho = radius * (inside ? 0.95 * std::sqrt(uni(rng)) : 1.05 + 0.15 * uni(rng));
        const double phi = 2.0 * 3.14159265358979 * uni(rng);
        const glm::dvec3 target =
            glm::dvec3(s.center) + rho * (std::cos(phi) * e1 + std::sin(phi) * e2);
        const Ray ray = make_ray(vec3(0.0f), vec3(target));
        const float t = intersect_sphere(s, ray);
        if (inside) {
            if (t == infinity) {
                ++misses;
                continue;
            }
            ++hits;
            const double t_exact = sphere_oracle(s, ray);
            const double err = std::abs(t - t_exact) / ulp(t_exact);
            worst_ulps = std::max(worst_ulps, err);
            if (err > 8.0 || surface_error_ulps(s, ray, t) > 4.0) ++inaccurate;
        } else if (t != infinity) {
            ++wrong_hits;
        }
    }
    EXPECT_EQ(misses, 0) << "D = " << distance << ", r = " << radius;
    EXPECT_EQ(wrong_hits, 0) << "D = " << distance << ", r = " << radius;
    EXPECT_EQ(hits, disc_rays / 2);
    EXPECT_EQ(inaccurate, 0) << "worst " << worst_ulps << " ulps of t";
    std::printf("D = %g, r = %g: worst error %.2f ulps of t\n", double(distance), double(radius),
                worst_ulps);
}

TEST(IntersectSphere, CoversFarSpheresExactly) {
    expect_sphere_coverage(1e2f, 1.0f, 1);
    expect_sphere_coverage(1e3f, 1.0f, 2);
    expect_sphere_coverage(1e4f, 1.0f, 3);
}

TEST(IntersectSphere, CoversATinySphereNearTheCamera) { expect_sphere_coverage(1.0f, 1e-3f, 4); }

TEST(IntersectSphere, HitsAHugeGroundSphereOnItsSurface) {
    // r = 1e5 ground, camera 1 unit above it: c = |f|^2 - r^2 cancels (2e5 next to 1e10), so
    // the test carries f and c past float's rounding: every downward ray hits, t is within 1e-6
    // relative of the double oracle, and the hit point lies on the surface within 4 ulps of the
    // sphere's scale.
    const Sphere s{vec3(0.0f, -1e5f, 0.0f), 1e5f};
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        const Ray ray = make_ray(vec3(uni(rng), 1.0f, uni(rng)),
                                 vec3(uni(rng), -0.5f * (uni(rng) + 1.5f), uni(rng)));
        const double t_exact = sphere_oracle(s, ray);
        const float t = intersect_sphere(s, ray);
        ASSERT_NE(t, infinity);
        EXPECT_GT(t, 0.0f);
        EXPECT_LE(std::abs(double(t) - t_exact), 1e-6 * t_exact) << i << " " << t << " " << t_exact;
        EXPECT_LE(surface_error_ulps(s, ray, t), 4.0) << i << " " << t << " " << t_exact;
    }
}

// --- box ---------------------------------------------------------------------------------------

TEST(IntersectBox, HitsFacesAtTheExactDistanceWithTheirNormal) {
    const Box b{vec3(-1.0f), vec3(1.0f)};
    const vec3 dirs[] = {vec3(1, 0, 0),  vec3(-1, 0, 0), vec3(0, 1, 0),
                         vec3(0, -1, 0), vec3(0, 0, 1),  vec3(0, 0, -1)};
    for (const vec3 d : dirs) {
        const Ray ray = make_ray(vec3(0.25f, -0.5f, 0.125f) - 5.0f * d, 2.0f * d);
        const float t = intersect_box(b, ray);
        const float along = glm::dot(vec3(0.25f, -0.5f, 0.125f), d);
        EXPECT_EQ(t, (4.0f - along) / 2.0f);
        EXPECT_EQ(geometry_box(b, ray.org + t * ray.dir).normal, -d);
    }
}

TEST(IntersectBox, BreaksEdgeAndCornerTiesXThenYThenZ) {
    const Box b{vec3(-1.0f), vec3(1.0f)};
    const Ray corner = make_ray(vec3(-3.0f), vec3(1.0f));
    const float t = intersect_box(b, corner);
    EXPECT_EQ(t, 2.0f);
    EXPECT_EQ(geometry_box(b, corner.org + t * corner.dir).normal, vec3(-1, 0, 0));
    EXPECT_EQ(geometry_box(b, vec3(1.0f, 1.0f, 0.0f)).normal, vec3(1, 0, 0));
    EXPECT_EQ(geometry_box(b, vec3(0.0f, -1.0f, 1.0f)).normal, vec3(0, -1, 0));
    EXPECT_EQ(geometry_box(b, vec3(0.5f, 0.0f, 1.0f)).normal, vec3(0, 0, 1));
    // zero thickness: the lo face wins
    EXPECT_EQ(geometry_box(Box{vec3(0.0f), vec3(1.0f, 0.0f, 1.0f)}, vec3(0.5f, 0.0f, 0.5f)).normal,
              vec3(0, -1, 0));
}

TEST(IntersectBox, UvSpansEachFace) {
    const Box b{vec3(0.0f, 0.0f, 0.0f), vec3(2.0f, 4.0f, 8.0f)};
    EXPECT_EQ(geometry_box(b, vec3(0.0f, 1.0f, 6.0f)).uv, vec2(0.25f, 0.75f));  // x: (y, z)
    EXPECT_EQ(geometry_box(b, vec3(1.5f, 4.0f, 2.0f)).uv, vec2(0.25f, 0.75f));  // y: (z, x)
    EXPECT_EQ(geometry_box(b, vec3(0.5f, 3.0f, 8.0f)).uv, vec2(0.25f, 0.75f));  // z: (x, y)
}

TEST(IntersectBox, MissesBesideBehindAndBeyondTMax) {
    const Box b{vec3(-1.0f), vec3(1.0f)};
    EXPECT_EQ(intersect_box(b, make_ray(vec3(0.0f, 2.0f, -5.0f), vec3(0, 0, 1))), infinity);
    EXPECT_EQ(intersect_box(b, make_ray(vec3(0.0f, 0.0f, 5.0f), vec3(0, 0, 1))), infinity);
    EXPECT_EQ(intersect_box(b, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0, 0, 1), 0.0f, 4.0f)),
              infinity);
    EXPECT_EQ(intersect_box(b, make_ray(vec3(-3.0f, 0.0f, -3.0f), vec3(1, 0, -1))), infinity);
}

TEST(IntersectBox, ReturnsTheExitFromInside) {
    const Box b{vec3(-1.0f), vec3(1.0f)};
    const Ray ray = make_ray(vec3(0.0f, 0.5f, 0.0f), vec3(0, 0, -4));
    const float t = intersect_box(b, ray);
    EXPECT_EQ(t, 0.25f);
    EXPECT_EQ(geometry_box(b, ray.org + t * ray.dir).normal, vec3(0, 0, -1));
    EXPECT_EQ(intersect_box(b, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0, 0, 1), 4.5f)), 6.0f);
}

TEST(IntersectBox, HandlesZeroAndNegativeZeroComponentsAndFacePlaneOrigins) {
    const Box b{vec3(-1.0f), vec3(1.0f)};
    for (const float z : {0.0f, -0.0f}) {
        EXPECT_EQ(intersect_box(b, make_ray(vec3(0.5f, -0.5f, -5.0f), vec3(z, z, 1))), 4.0f);
        EXPECT_EQ(intersect_box(b, make_ray(vec3(2.0f, 0.0f, -5.0f), vec3(z, 0, 1))), infinity);
        // Origin in the face plane y = 1 (or y = -1) with d.y = +-0: the slab's 0 * inf = NaN
        // counts as inside (the numerics.md §2 convention), so the ray grazes the face.
        for (const float y : {1.0f, -1.0f}) {
            const float t = intersect_box(b, make_ray(vec3(0.0f, y, -5.0f), vec3(0, z, 1)));
            EXPECT_EQ(t, 4.0f);
        }
    }
    EXPECT_EQ(intersect_box(b, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0.0f))), infinity);
    EXPECT_EQ(intersect_box(b, make_ray(vec3(0.0f, 0.0f, -5.0f), vec3(0, nan_f, 1))), infinity);
}

TEST(IntersectBox, HitsAZeroThicknessBoxAtEveryAngle) {
    // numerics.md §7: a quad as a box with lo.y == hi.y.
    const Box b{vec3(-1.0f, 0.25f, -1.0f), vec3(1.0f, 0.25f, 1.0f)};
    const int n = 64;
    for (const float angle_deg : {0.0f, 45.0f, 89.9f}) {
        const double angle = angle_deg * 3.14159265358979 / 180.0;
        const vec3 dir(static_cast<float>(std::sin(angle) * 0.6),
                       static_cast<float>(-std::cos(angle)),
                       static_cast<float>(std::sin(angle) * 0.8));
        int hits = 0, rays = 0;
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; j <= n; ++j) {
                // head-on: the grid includes the edges (exact); oblique: cell centres
                const bool head_on = angle_deg == 0.0f;
                if (!head_on && (i == n || j == n)) continue;
                const float off = head_on ? 0.0f : 0.5f;
                const vec3 target(-1.0f + 2.0f * (float(i) + off) / n, 0.25f,
                                  -1.0f + 2.0f * (float(j) + off) / n);
                const Ray ray = make_ray(target - 3.0f * dir, dir);
                const float t = intersect_box(b, ray);
                ++rays;
                if (t == infinity) continue;
                ++hits;
                EXPECT_NEAR(t, 3.0f, 1e-5f);
                if (i == 0 || j == 0 || i == n || j == n) continue;  // edges: x or z wins the tie
                EXPECT_EQ(std::abs(geometry_box(b, ray.org + t * ray.dir).normal.y), 1.0f);
            }
        }
        EXPECT_EQ(hits, rays) << angle_deg << " degrees";
    }
    // A ray lying in the plane of the zero-thickness slab misses, like a ray in a plane (§6).
    EXPECT_EQ(intersect_box(b, make_ray(vec3(-3.0f, 0.25f, 0.0f), vec3(1, 0, 0))), infinity);
}

// --- cylinder ----------------------------------------------------------------------------------

TEST(IntersectCylinder, HitsTheSideAtTheExactDistance) {
    const Cylinder c{1.0f, 2.0f};
    const Ray ray = make_ray(vec3(-5.0f, 1.0f, 0.0f), vec3(2, 0, 0));
    const float t = intersect_cylinder(c, ray);
    EXPECT_EQ(t, 2.0f);
    const LocalGeometry g = geometry_cylinder(c, ray.org + t * ray.dir);
    EXPECT_EQ(g.normal, vec3(-1, 0, 0));
    EXPECT_NEAR(g.uv.x, 0.5f, 1e-7f);
    EXPECT_EQ(g.uv.y, 0.5f);
    // from inside: the far side
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(0.0f, 1.0f, 0.0f), vec3(0, 0, 1))), 1.0f);
}

TEST(IntersectCylinder, HitsTheCapsAlongTheAxis) {
    const Cylinder c{1.0f, 2.0f};
    // from above: the top cap at the exact distance, normal +y
    Ray ray = make_ray(vec3(0.0f, 5.0f, 0.0f), vec3(0, -1, 0));
    float t = intersect_cylinder(c, ray);
    EXPECT_EQ(t, 3.0f);
    EXPECT_EQ(geometry_cylinder(c, ray.org + t * ray.dir).normal, vec3(0, 1, 0));
    // from below, off the axis, non-unit direction
    ray = make_ray(vec3(0.5f, -4.0f, -0.25f), vec3(0, 2, 0));
    t = intersect_cylinder(c, ray);
    EXPECT_EQ(t, 2.0f);
    EXPECT_EQ(geometry_cylinder(c, ray.org + t * ray.dir).normal, vec3(0, -1, 0));
    // from inside: the far cap, t > 0, both ways
    for (const float dy : {1.0f, -1.0f}) {
        ray = make_ray(vec3(0.0f, 0.5f, 0.0f), vec3(0, dy, 0));
        t = intersect_cylinder(c, ray);
        EXPECT_EQ(t, dy > 0.0f ? 1.5f : 0.5f);
        EXPECT_EQ(geometry_cylinder(c, ray.org + t * ray.dir).normal, vec3(0, dy, 0));
    }
    // oblique through the top cap
    ray = make_ray(vec3(0.0f, 5.0f, 0.0f), vec3(0.125f, -1.0f, 0.0f));
    t = intersect_cylinder(c, ray);
    EXPECT_EQ(t, 3.0f);
    EXPECT_EQ(geometry_cylinder(c, ray.org + t * ray.dir).normal, vec3(0, 1, 0));
}

TEST(IntersectCylinder, RaysParallelToTheAxisOutsideMissWithoutNan) {
    const Cylinder c{1.0f, 2.0f};
    for (const float dy : {1.0f, -1.0f}) {
        for (const float x : {1.01f, -1.01f, 5.0f}) {
            EXPECT_EQ(
                intersect_cylinder(c, make_ray(vec3(x, 1.0f - 5.0f * dy, 0.0f), vec3(0, dy, 0))),
                infinity);
            EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(0.0f, 1.0f, x), vec3(-0.0f, dy, 0))),
                      infinity);
        }
        // exactly at the radius: defined (the closed disc contains it), never NaN
        const float t =
            intersect_cylinder(c, make_ray(vec3(1.0f, 1.0f - 5.0f * dy, 0.0f), vec3(0, dy, 0)));
        EXPECT_FALSE(std::isnan(t));
        EXPECT_TRUE(t == infinity || t == 4.0f) << t;
    }
}

TEST(IntersectCylinder, MissesAboveBesideAndBehind) {
    const Cylinder c{1.0f, 2.0f};
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(-5.0f, 3.0f, 0.0f), vec3(1, 0, 0))), infinity);
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(-5.0f, 1.0f, 1.5f), vec3(1, 0, 0))), infinity);
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(-5.0f, 1.0f, 0.0f), vec3(-1, 0, 0))), infinity);
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(-5.0f, 1.0f, 0.0f), vec3(1, 0, 0), 0.0f, 4.0f)),
              infinity);
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(-5.0f, 1.0f, 0.0f), vec3(0.0f))), infinity);
    EXPECT_EQ(intersect_cylinder(c, make_ray(vec3(-5.0f, 1.0f, 0.0f), vec3(1, nan_f, 0))),
              infinity);
}

TEST(IntersectCylinder, RaysInACapPlaneGiveADefinedResult) {
    const Cylinder c{1.0f, 2.0f};
    for (const float y : {0.0f, 2.0f}) {
        for (const float z : {0.0f, -0.0f}) {
            // d.y = +-0 with the origin in the cap plane: 0 / 0 leaves the slab open, the ray
            // grazes the cap and enters through the rim
            const float t = intersect_cylinder(c, make_ray(vec3(-5.0f, y, 0.5f), vec3(1, z, 0)));
            EXPECT_FALSE(std::isnan(t));
            EXPECT_NEAR(t, 5.0 - std::sqrt(0.75), 4 * ulp(4.134));
        }
    }
}

TEST(IntersectCylinder, CoversBothRimsWithoutLeaks) {
    // numerics.md §5: rays aimed at random points of both rims, from outside in directions that
    // enter the solid there (at least 3 degrees from both the side and the cap), and from inside.
    const Cylinder c{0.75f, 1.5f};
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    std::normal_distribution<float> normal;
    int outside_misses = 0, inside_misses = 0, nan_t = 0;
    for (int i = 0; i < rim_rays; ++i) {
        const float phi = 6.2831853f * uni(rng);
        const bool top = i % 2 == 0;
        const vec3 n_side(std::cos(phi), 0.0f, std::sin(phi));
        const vec3 rim = c.radius * n_side + vec3(0.0f, top ? c.height : 0.0f, 0.0f);
        const float n_cap = top ? 1.0f : -1.0f;
        // from outside
        vec3 d;
        do {
            d = glm::normalize(vec3(normal(rng), normal(rng), normal(rng)));
        } while (!(glm::dot(d, n_side) < -0.05f && d.y * n_cap < -0.05f));
        const float t_out = intersect_cylinder(c, make_ray(rim - (0.5f + 4.0f * uni(rng)) * d, d));
        if (t_out == infinity) ++outside_misses;
        // from inside
        const vec3 org(0.6f * c.radius * (2.0f * uni(rng) - 1.0f),
                       c.height * (0.1f + 0.8f * uni(rng)),
                       0.6f * c.radius * (2.0f * uni(rng) - 1.0f));
        const float t_in = intersect_cylinder(c, make_ray(org, rim - org));
        if (t_in == infinity) ++inside_misses;
        if (std::isnan(t_out) || std::isnan(t_in)) ++nan_t;
        if (t_in != infinity) {
            EXPECT_NEAR(t_in, 1.0f, 1e-5f);
        }
    }
    EXPECT_EQ(outside_misses, 0);
    EXPECT_EQ(inside_misses, 0);
    EXPECT_EQ(nan_t, 0);
}

/// Textbook cylinder in double: side roots with 0 <= y <= h, caps with x^2 + z^2 <= r^2.
/// Returns the nearest t > 0 and the part hit (0 side, 1 bottom, 2 top), or infinity.
double cylinder_oracle(const Cylinder& cyl, const Ray& ray, int& part) {
    const glm::dvec3 o(ray.org), d(ray.dir);
    const double r = cyl.radius, h = cyl.height;
    double best = INFINITY;
    const double a = d.x * d.x + d.z * d.z, b = o.x * d.x + o.z * d.z;
    const double c = o.x * o.x + o.z * o.z - r * r, disc = b * b - a * c;
    if (a > 0.0 && disc >= 0.0) {
        for (const double t : {(-b - std::sqrt(disc)) / a, (-b + std::sqrt(disc)) / a}) {
            const double y = o.y + t * d.y;
            if (t > 0.0 && t < best && y >= 0.0 && y <= h) best = t, part = 0;
        }
    }
    for (int k = 0; k < 2; ++k) {
        const double t = ((k == 0 ? 0.0 : h) - o.y) / d.y;
        const double x = o.x + t * d.x, z = o.z + t * d.z;
        if (t > 0.0 && t < best && x * x + z * z <= r * r) best = t, part = 1 + k;
    }
    return best;
}

TEST(IntersectCylinder, MatchesADoubleOracleOnRaysAtInteriorPoints) {
    // Rays at random points well inside the solid must hit; t and the part (side or cap, from the
    // normal) agree with the oracle wherever its hit point is not within 1e-4 of a rim.
    const Cylinder c{0.8f, 1.7f};
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    std::normal_distribution<float> normal;
    int checked_parts = 0;
    for (int i = 0; i < shape_oracle_rays; ++i) {
        const vec3 w = glm::normalize(vec3(normal(rng), normal(rng), normal(rng)));
        const float ang = 6.2831853f * uni(rng), rho = 0.9f * c.radius * std::sqrt(uni(rng));
        const vec3 target(rho * std::cos(ang), c.height * (0.05f + 0.9f * uni(rng)),
                          rho * std::sin(ang));
        const Ray ray =
            make_ray(target + (2.0f + 3.0f * uni(rng)) * w, target - (target + 3.0f * w));
        int part = -1;
        const double t_exact = cylinder_oracle(c, ray, part);
        const float t = intersect_cylinder(c, ray);
        ASSERT_NE(t, infinity) << i;
        EXPECT_NEAR(t, t_exact, 1e-5 * t_exact) << i;
        const glm::dvec3 p = glm::dvec3(ray.org) + t_exact * glm::dvec3(ray.dir);
        const double to_rim = std::min(std::abs(p.y), std::abs(p.y - c.height)) +
                              std::abs(std::sqrt(p.x * p.x + p.z * p.z) - c.radius);
        if (to_rim < 1e-4) continue;
        const vec3 n = geometry_cylinder(c, ray.org + t * ray.dir).normal;
        const int got = n.y == 0.0f ? 0 : (n.y < 0.0f ? 1 : 2);
        EXPECT_EQ(got, part) << i;
        ++checked_parts;
    }
    EXPECT_GT(checked_parts, shape_oracle_rays * 9 / 10);
}

// --- plane -------------------------------------------------------------------------------------

TEST(IntersectPlane, HitsFromBothSidesAtTheExactDistance) {
    const Plane p{vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f)};
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(3.0f, 6.0f, -2.0f), vec3(0, -1, 0))), 5.0f);
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(3.0f, 6.0f, -2.0f), vec3(0, -2, 0))), 2.5f);
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(3.0f, -4.0f, -2.0f), vec3(1, 1, 0))), 5.0f);
    const LocalGeometry g = geometry_plane(p, vec3(3.0f, 1.0f, -2.0f));
    EXPECT_EQ(g.normal, vec3(0, 1, 0));  // the plane's normal on both sides
}

TEST(IntersectPlane, MissesBehindAndOutsideTheInterval) {
    const Plane p{vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)};
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 5.0f, 0.0f), vec3(0, 1, 0))), infinity);
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 5.0f, 0.0f), vec3(0, -1, 0), 0.0f, 5.0f)),
              infinity);
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 5.0f, 0.0f), vec3(0, -1, 0), 5.0f)), infinity);
}

TEST(IntersectPlane, ParallelAndInPlaneRaysMissWithoutNan) {
    const Plane p{vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)};
    for (const float z : {0.0f, -0.0f}) {
        EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 1.0f, 0.0f), vec3(1, z, 0))), infinity);
        EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 0.0f, 0.0f), vec3(1, z, 0))), infinity);
        EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, -0.0f, 7.0f), vec3(0, z, 1))), infinity);
    }
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 1.0f, 0.0f), vec3(0.0f))), infinity);
    EXPECT_EQ(intersect_plane(p, make_ray(vec3(0.0f, 1.0f, 0.0f), vec3(0, nan_f, 0))), infinity);
}

TEST(IntersectPlane, TinySlopesGiveAFiniteHitOrAMiss) {
    const Plane p{vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)};
    for (const float dy : {-1e-30f, -1e-45f, -1e-38f}) {
        for (const float y : {1.0f, 1e-30f, 0.0f}) {
            const float t = intersect_plane(p, make_ray(vec3(0.0f, y, 0.0f), vec3(1, dy, 0)));
            EXPECT_FALSE(std::isnan(t));
            EXPECT_TRUE(t == infinity || (std::isfinite(t) && t > 0.0f)) << t;
        }
    }
}

TEST(IntersectPlane, ShadowRayFromThePlaneIsNotOccludedByIt) {
    const Plane p{vec3(1.0f, 2.0f, 3.0f), glm::normalize(vec3(1.0f, 2.0f, 2.0f))};
    const Ray shadow = make_ray(p.point, vec3(1.0f, 2.0f, 2.0f), 0.0f, 1.0f);
    EXPECT_EQ(intersect_plane(p, shadow), infinity);
}

TEST(IntersectPlane, UvIsAFixedOrthonormalFrame) {
    const vec3 normals[] = {vec3(0, 1, 0),
                            vec3(0, 0, 1),
                            vec3(0, 0, -1),
                            glm::normalize(vec3(1e-8f, 0.0f, -1.0f)),
                            glm::normalize(vec3(1.0f, -2.0f, 0.5f)),
                            vec3(-1, 0, 0)};
    for (const vec3 n : normals) {
        const Plane p{vec3(1.0f, -2.0f, 0.5f), n};
        const vec2 e1 = geometry_plane(p, p.point + vec3(1.0f, 0.0f, 0.0f)).uv;
        const vec2 e2 = geometry_plane(p, p.point + vec3(0.0f, 1.0f, 0.0f)).uv;
        const vec2 e3 = geometry_plane(p, p.point + vec3(0.0f, 0.0f, 1.0f)).uv;
        // Rows of [t1; t2] as seen through uv: orthonormal and orthogonal to n.
        const vec3 t1(e1.x, e2.x, e3.x), t2(e1.y, e2.y, e3.y);
        EXPECT_NEAR(glm::length(t1), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(t2), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t1, t2), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t1, n), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t2, n), 0.0f, 1e-6f);
        EXPECT_GT(glm::dot(glm::cross(t1, t2), n), 0.999f);  // right-handed around n
        EXPECT_EQ(geometry_plane(p, p.point).uv, vec2(0.0f));
    }
}

}  // namespace
}  // namespace raylane
