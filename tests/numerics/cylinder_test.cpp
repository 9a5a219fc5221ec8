// numerics.md §5 : rays along the axis of a capped cylinder, at its rims and
// grazing its side (traverse/cylinder_scalar.h, cylinder_packet.h): exact cap hits, no NaN, no
// leak at the rims, and t against the double instantiation as the oracle.
#include <gtest/gtest.h>

#include <random>

#include "support/geometry_support.h"
#include "traverse/cylinder_packet.h"
#include "traverse/cylinder_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

const Cylinder cyl{0.8f, 2.5f};

std::vector<float> packet_cylinder_t(const std::vector<Ray>& rays, auto w) {
    constexpr int W = decltype(w)::value;
    return packet_shape<W>(cyl, rays, [](const Cylinder& c, const RayPacket<W>& p, vmask<W> a) {
        return intersect_cylinder<W>(c, p, a);
    });
}

void expect_packet_agrees(const std::vector<Ray>& rays, const std::vector<float>& scalar) {
    for_each_width([&](auto w) {
        EXPECT_EQ(shape_disagreements(scalar, packet_cylinder_t(rays, w)), 0u)
            << "W = " << decltype(w)::value;
    });
}

/// Along the axis (a = 0, the side quadratic is skipped) onto the top cap from above: the cap at
/// the exact distance with normal +y; from inside, the far cap, t > 0, normal -y or +y.
TEST(Cylinder, RaysAlongTheAxisHitTheCapsAtTheExactDistance) {
    std::vector<Ray> rays;
    std::vector<float> scalar;
    for (vec3 xz : {vec3(0.0f), vec3(0.3f, 0.0f, -0.2f), vec3(-0.79f, 0.0f, 0.0f)}) {
        const Ray down{xz + vec3(0.0f, 6.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f)};
        const float t = intersect_cylinder(cyl, down);
        EXPECT_EQ(t, 6.0f - 2.5f);
        EXPECT_EQ(geometry_cylinder(cyl, down.org + t * down.dir).normal, vec3(0.0f, 1.0f, 0.0f));
        const Ray up_inside{xz + vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f)};
        const float t_in = intersect_cylinder(cyl, up_inside);
        EXPECT_EQ(t_in, 1.5f);
        EXPECT_EQ(geometry_cylinder(cyl, up_inside.org + t_in * up_inside.dir).normal,
                  vec3(0.0f, 1.0f, 0.0f));
        const Ray down_inside{xz + vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, -3.0f, 0.0f)};
        const float t_down = intersect_cylinder(cyl, down_inside);
        EXPECT_EQ(t_down, 1.0f / 3.0f);
        EXPECT_EQ(geometry_cylinder(cyl, down_inside.org + t_down * down_inside.dir).normal,
                  vec3(0.0f, -1.0f, 0.0f));
        for (const Ray& r : {down, up_inside, down_inside}) {
            rays.push_back(r);
            scalar.push_back(intersect_cylinder(cyl, r));
        }
    }
    expect_packet_agrees(rays, scalar);
}

/// Parallel to the axis outside the disc (radius 1.01 r): a miss, no NaN. At radius exactly r:
/// the closed disc holds the ray, so it hits the cap's rim; never NaN. Both paths.
TEST(Cylinder, AxisParallelRaysAtAndBeyondTheRadiusGiveNoNaN) {
    std::vector<Ray> rays;
    std::vector<float> scalar;
    for (float angle_deg = 0.0f; angle_deg < 360.0f; angle_deg += 15.0f) {
        const float a = glm::radians(angle_deg);
        for (float dy : {-1.0f, 1.0f}) {
            const float y = dy < 0.0f ? 4.0f : -1.5f;
            const Ray beyond{
                vec3(1.01f * cyl.radius * std::cos(a), y, 1.01f * cyl.radius * std::sin(a)),
                vec3(0.0f, dy, 0.0f)};
            EXPECT_EQ(intersect_cylinder(cyl, beyond), infinity);
            rays.push_back(beyond);
            scalar.push_back(infinity);
        }
    }
    // exactly on the radius: (r, 0) and (0, -r) are exact
    for (vec3 rim : {vec3(cyl.radius, 0.0f, 0.0f), vec3(0.0f, 0.0f, -cyl.radius)}) {
        for (float dy : {-1.0f, 1.0f}) {
            const Ray on{rim + vec3(0.0f, dy < 0.0f ? 4.0f : -1.5f, 0.0f), vec3(0.0f, dy, 0.0f)};
            const float t = intersect_cylinder(cyl, on);
            EXPECT_FALSE(is_nan_bits(t));
            EXPECT_EQ(t, dy < 0.0f ? 4.0f - 2.5f : 1.5f) << "the closed disc holds its rim";
            rays.push_back(on);
            scalar.push_back(t);
        }
    }
    expect_packet_agrees(rays, scalar);
}

/// Random rays through points on both rims into the solid (toward an interior point): every
/// one hits at the rim (no leak between the side and cap predicates), with the double
/// instantiation's t to a few ulps, in both paths.
TEST(Cylinder, RimsDoNotLeak) {
    std::mt19937 rng(31);
    std::uniform_real_distribution<float> s01(0.0f, 1.0f);
    const size_t n = ray_count(100000);
    std::vector<Ray> rays;
    std::vector<float> scalar;
    size_t misses = 0, far_off = 0;
    int64_t worst = 0;
    for (size_t i = 0; i < n; ++i) {
        const double phi = 2.0 * 3.141592653589793 * s01(rng);
        const double y = i % 2 ? double(cyl.height) : 0.0;
        const glm::dvec3 rim(cyl.radius * std::cos(phi), y, cyl.radius * std::sin(phi));
        // an interior point at least 5 % of the radius and height inside
        const double rho = 0.95 * cyl.radius * std::sqrt(s01(rng)), psi = 6.283185307 * s01(rng);
        const glm::dvec3 q(rho * std::cos(psi), (0.05 + 0.9 * s01(rng)) * cyl.height,
                           rho * std::sin(psi));
        const glm::dvec3 d = glm::normalize(q - rim);
        const Ray r{vec3(rim - 5.0 * d), vec3(d), 0.0f, infinity};
        const float t = intersect_cylinder(cyl, r);
        misses += !(t < infinity);
        const double td = intersect_cylinder(cyl, ray_of<double>(r));
        if (t < infinity) {
            const int64_t u = ulp_distance(t, float(td));
            worst = std::max(worst, u);
            far_off += u > 4;
        }
        rays.push_back(r);
        scalar.push_back(t);
    }
    EXPECT_EQ(misses, 0u) << "of " << n << " rays into the rims";
    EXPECT_EQ(far_off, 0u) << "worst " << worst << " ulps from the double t";
    std::printf("[ measured ] cylinder rims: worst float t vs double oracle %lld ulps\n",
                static_cast<long long>(worst));
    expect_packet_agrees(rays, scalar);
}

/// Near-grazing rays at the side (perpendicular distance from the axis r (1 - e), e down to
/// 1e-6): t is ill-conditioned there, but the float hit point lies on the side within a few
/// ulps, and the decision matches the double oracle.
TEST(Cylinder, NearGrazingSideHitsStayOnTheSurface) {
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> s01(0.0f, 1.0f);
    const size_t n = ray_count(100000);
    std::vector<Ray> rays;
    std::vector<float> scalar;
    size_t decision = 0, off_surface = 0;
    double worst_surface = 0.0;
    int64_t worst_t = 0;
    for (size_t i = 0; i < n; ++i) {
        const double e = std::pow(10.0, -1.0 - 5.0 * s01(rng));
        const double phi = 6.283185307 * s01(rng);
        const glm::dvec3 across(std::cos(phi), 0.0, std::sin(phi));  // axis to closest approach
        const glm::dvec3 along(-std::sin(phi), 0.0, std::cos(phi));
        const double tilt = 0.3 * (s01(rng) - 0.5);
        const glm::dvec3 d = glm::normalize(along + glm::dvec3(0.0, tilt, 0.0));
        const glm::dvec3 closest =
            double(cyl.radius) * (1.0 - e) * across + glm::dvec3(0.0, 1.25, 0.0);
        const Ray r{vec3(closest - 4.0 * d), vec3(d), 0.0f, infinity};
        const float t = intersect_cylinder(cyl, r);
        const double td = intersect_cylinder(cyl, ray_of<double>(r));
        decision += (t < infinity) != (td < infinity_of<double>);
        if (t < infinity) {
            const glm::dvec3 p = glm::dvec3(r.org) + double(t) * glm::dvec3(r.dir);
            const double err = std::fabs(std::hypot(p.x, p.z) - double(cyl.radius));
            const double ulps = err / float_ulp(glm::length(p));
            worst_surface = std::max(worst_surface, ulps);
            off_surface += ulps > 4.0;
            worst_t = std::max(worst_t, ulp_distance(t, float(td)));
        }
        rays.push_back(r);
        scalar.push_back(t);
    }
    EXPECT_EQ(decision, 0u) << "hit/miss differs from the double oracle";
    EXPECT_EQ(off_surface, 0u) << "worst " << worst_surface << " ulps off the side";
    std::printf(
        "[ measured ] cylinder near-grazing: worst surface error %.3g ulps, worst t vs "
        "double %lld ulps\n",
        worst_surface, static_cast<long long>(worst_t));
    expect_packet_agrees(rays, scalar);
}

}  // namespace
}  // namespace raylane
