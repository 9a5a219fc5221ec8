// Tests of traverse/slab_scalar.h: the robust slab test on boundary cases (face-plane origins,
// zero and -0.0 direction components, zero-thickness boxes) and its conservativeness against
// the watertight triangle test.
#include "traverse/slab_scalar.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "traverse/triangle_scalar.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int conservative_rays = 5000;
#else
constexpr int conservative_rays = 100000;
#endif

struct SlabResult {
    bool hit = false;
    float t_near = 0.0f;
};

SlabResult slab(vec3 org, vec3 dir, vec3 lo, vec3 hi, float t_min = 0.0f, float t_max = infinity) {
    Ray ray;
    ray.org = org;
    ray.dir = dir;
    SlabResult r;
    r.hit = intersect_slab(make_slab_ray(ray), lo, hi, t_min, t_max, r.t_near);
    return r;
}

const vec3 unit_lo(0.0f), unit_hi(1.0f);

TEST(SlabTest, FarScaleIsOnePlusTwoGammaThree) {
    EXPECT_GT(slab_far_scale, 1.0f);
    EXPECT_NEAR(static_cast<double>(slab_far_scale), 1.0 + 6.0 * 0x1.0p-24, 0x1.0p-23);
}

TEST(SlabTest, ReturnsTheEntryDistanceClampedToTMin) {
    SlabResult r = slab(vec3(-1.0f, 0.5f, 0.5f), vec3(1, 0, 0), unit_lo, unit_hi);
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.t_near, 1.0f);
    r = slab(vec3(-1.0f, 0.5f, 0.5f), vec3(4, 0, 0), unit_lo, unit_hi);
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.t_near, 0.25f);
    r = slab(vec3(0.5f), vec3(0.3f, -0.2f, 0.1f), unit_lo, unit_hi, 0.125f);  // origin inside
    EXPECT_TRUE(r.hit);
    EXPECT_EQ(r.t_near, 0.125f);
}

TEST(SlabTest, MissesBoxesBehindBesideAndBeyondTMax) {
    EXPECT_FALSE(slab(vec3(2.0f, 0.5f, 0.5f), vec3(1, 0, 0), unit_lo, unit_hi).hit);
    EXPECT_FALSE(slab(vec3(-1.0f, 2.0f, 0.5f), vec3(1, 0, 0), unit_lo, unit_hi).hit);
    EXPECT_FALSE(slab(vec3(-1.0f, 0.5f, 0.5f), vec3(1, 0, 0), unit_lo, unit_hi, 0.0f, 0.5f).hit);
    EXPECT_FALSE(slab(vec3(-1.0f, -1.0f, 0.5f), vec3(1, -1, 0), unit_lo, unit_hi).hit);
    // The interval is closed: an entry exactly at t_max counts.
    EXPECT_TRUE(slab(vec3(-1.0f, 0.5f, 0.5f), vec3(1, 0, 0), unit_lo, unit_hi, 0.0f, 1.0f).hit);
}

TEST(SlabTest, CountsRaysInAFacePlaneAsHitsWithoutNan) {
    // Every axis-aligned direction (with +0.0 and -0.0 in the other components), from origins on
    // the face planes (y = 0, y = 1, ...) inside the face's extent and outside the box.
    const float zero[2] = {0.0f, -0.0f};
    int cases = 0;
    for (int axis = 0; axis < 3; ++axis) {
        for (const float sign : {1.0f, -1.0f}) {
            for (const float z0 : zero) {
                for (const float z1 : zero) {
                    vec3 dir(z0);
                    dir[(axis + 1) % 3] = z1;
                    dir[axis] = sign;
                    for (int plane_axis = 0; plane_axis < 3; ++plane_axis) {
                        if (plane_axis == axis) continue;
                        for (const float plane : {0.0f, 1.0f}) {
                            vec3 org(0.5f);
                            org[axis] = sign > 0.0f ? -2.0f : 3.0f;  // outside, heading in
                            org[plane_axis] = plane;
                            const SlabResult r = slab(org, dir, unit_lo, unit_hi);
                            EXPECT_TRUE(r.hit);
                            EXPECT_EQ(r.t_near, 2.0f);
                            // the same ray starting inside the box
                            org[axis] = 0.5f;
                            const SlabResult in = slab(org, dir, unit_lo, unit_hi);
                            EXPECT_TRUE(in.hit);
                            EXPECT_EQ(in.t_near, 0.0f);
                            // origin on the plane, but beside the face: miss
                            org[3 - axis - plane_axis] = 1.5f;
                            const SlabResult beside = slab(org, dir, unit_lo, unit_hi);
                            EXPECT_FALSE(beside.hit);
                            EXPECT_FALSE(std::isnan(beside.t_near));
                            cases += 3;
                        }
                    }
                }
            }
        }
    }
    EXPECT_EQ(cases, 3 * 2 * 4 * 2 * 2 * 3);
}

TEST(SlabTest, TreatsNegativeZeroLikeAnyNegativeComponent) {
    // dir.x = -0.0 gives inv_dir.x = -inf; ordering by inv_dir keeps the x slab open for an
    // origin inside it and on either of its planes.
    for (const float ox : {0.0f, 0.5f, 1.0f}) {
        for (const float dx : {0.0f, -0.0f}) {
            const SlabResult r =
                slab(vec3(ox, 0.5f, -1.0f), vec3(dx, 0.0f, 1.0f), unit_lo, unit_hi);
            EXPECT_TRUE(r.hit) << ox << " " << dx;
            EXPECT_EQ(r.t_near, 1.0f);
        }
        EXPECT_FALSE(slab(vec3(ox - 2.0f, 0.5f, -1.0f), vec3(-0.0f, 0, 1), unit_lo, unit_hi).hit);
    }
}

TEST(SlabTest, HitsZeroThicknessBoxesAtEveryAngle) {
    // A flat node (lo.y == hi.y) crossed at 0, 45 and 89.9 degrees from its normal.
    const vec3 lo(0.0f, 0.5f, 0.0f), hi(1.0f, 0.5f, 1.0f);
    const int n = 64;
    for (const float angle_deg : {0.0f, 45.0f, 89.9f}) {
        const double angle = angle_deg * 3.14159265358979 / 180.0;
        const vec3 dir(static_cast<float>(std::sin(angle) * 0.8),
                       static_cast<float>(-std::cos(angle)),
                       static_cast<float>(std::sin(angle) * 0.6));
        int hits = 0;
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; j <= n; ++j) {
                // grid over the footprint, edges included (exactly representable points)
                const vec3 target(float(i) / n, 0.5f, float(j) / n);
                const vec3 org = target - 2.0f * dir;
                const SlabResult r = slab(org, dir, lo, hi);
                const bool inside = i > 0 && i < n && j > 0 && j < n;
                if (r.hit) ++hits;
                if (inside || angle_deg == 0.0f) {
                    EXPECT_TRUE(r.hit) << angle_deg << " " << i << " " << j;
                }
                EXPECT_FALSE(std::isnan(r.t_near));
            }
        }
        EXPECT_GE(hits, (n - 1) * (n - 1));
    }
    // A ray lying in the flat node's plane (dir.y = 0, origin on it) counts as touching it.
    EXPECT_TRUE(slab(vec3(-1.0f, 0.5f, 0.5f), vec3(1, 0, 0), lo, hi).hit);
    EXPECT_FALSE(slab(vec3(-1.0f, 0.5f, 2.0f), vec3(1, 0, 0), lo, hi).hit);
}

// --- conservativeness --------------------------------------------------------------------------

struct Tri {
    vec3 a, b, c;
};

/// Triangles inside [0, 1]^3: the box's own 12 faces, a floor of two triangles at y = 0.5, and
/// random triangles inside, some lying in a face plane.
std::vector<Tri> make_triangles_in_unit_box() {
    std::vector<Tri> tris;
    const vec3 v[8] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(1, 1, 0),
                       vec3(0, 0, 1), vec3(1, 0, 1), vec3(0, 1, 1), vec3(1, 1, 1)};
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        tris.push_back({v[q[0]], v[q[1]], v[q[2]]});
        tris.push_back({v[q[0]], v[q[2]], v[q[3]]});
    }
    tris.push_back({vec3(0, 0.5f, 0), vec3(1, 0.5f, 0), vec3(1, 0.5f, 1)});
    tris.push_back({vec3(0, 0.5f, 0), vec3(1, 0.5f, 1), vec3(0, 0.5f, 1)});
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (int i = 0; i < 24; ++i) {
        Tri t{vec3(uni(rng), uni(rng), uni(rng)), vec3(uni(rng), uni(rng), uni(rng)),
              vec3(uni(rng), uni(rng), uni(rng))};
        if (i % 3 == 0) {  // in a face plane
            const int axis = i % 9 / 3;
            const float plane = i % 2 ? 1.0f : 0.0f;
            t.a[axis] = t.b[axis] = t.c[axis] = plane;
        }
        tris.push_back(t);
    }
    return tris;
}

/// Random rays at the unit box: origins around it (some on its face planes, some inside),
/// aimed at points on its faces, edges and corners or inside, with zero, -0.0 and denormal
/// direction components mixed in.
Ray adversarial_ray(std::mt19937& rng) {
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    std::uniform_int_distribution<int> pick(0, 7);
    auto coord = [&]() {
        switch (pick(rng)) {
            case 0:
                return 0.0f;
            case 1:
                return 1.0f;
            default:
                return uni(rng);
        }
    };
    Ray ray;
    vec3 target(coord(), coord(), coord());
    ray.org = vec3(-2.0f) + 5.0f * vec3(uni(rng), uni(rng), uni(rng));
    if (pick(rng) == 0) ray.org[pick(rng) % 3] = pick(rng) % 2 ? 1.0f : 0.0f;
    if (pick(rng) == 0) ray.org = vec3(uni(rng), uni(rng), uni(rng));
    ray.dir = target - ray.org;
    const int k = pick(rng) % 3;
    switch (pick(rng)) {
        case 0:
            ray.dir[k] = 0.0f;
            break;
        case 1:
            ray.dir[k] = -0.0f;
            break;
        case 2:
            ray.dir[k] = pick(rng) % 2 ? 1e-40f : -1e-40f;
            break;
        default:
            break;
    }
    return ray;
}

TEST(SlabTest, NeverMissesABoxWhoseTrianglesAreHit) {
    const std::vector<Tri> tris = make_triangles_in_unit_box();
    std::mt19937 rng(8);
    int rays_with_hits = 0, misses = 0, nan_t = 0;
    for (int i = 0; i < conservative_rays; ++i) {
        const Ray ray = adversarial_ray(rng);
        const WatertightRay wr = make_watertight_ray(ray);
        float t_first = infinity;
        for (const Tri& tri : tris) {
            float t, u, v;
            if (intersect_triangle(wr, tri.a, tri.b, tri.c, ray.t_min, ray.t_max, t, u, v))
                t_first = std::min(t_first, t);
        }
        if (t_first == infinity) continue;
        ++rays_with_hits;
        float t_near = 0.0f;
        const bool hit =
            intersect_slab(make_slab_ray(ray), unit_lo, unit_hi, ray.t_min, ray.t_max, t_near);
        if (!hit) ++misses;
        if (std::isnan(t_near)) ++nan_t;
    }
    EXPECT_GT(rays_with_hits, conservative_rays / 4);
    EXPECT_EQ(misses, 0) << "of " << rays_with_hits;
    EXPECT_EQ(nan_t, 0);
}

}  // namespace
}  // namespace raylane
