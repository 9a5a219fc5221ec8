// numerics.md §2 : the BVH slab test (traverse/slab_scalar.h, slab_packet.h)
// with axis-parallel rays, +-0 and denormal direction components, origins on face planes, and
// rays that graze boxes: conservative, never NaN, and the BVH answers as brute force does.
#include <gtest/gtest.h>

#include <random>

#include "support/adversarial_rays.h"
#include "support/geometry_support.h"
#include "traverse/box_packet.h"
#include "traverse/box_scalar.h"
#include "traverse/slab_packet.h"
#include "traverse/slab_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// Rays along +-x, +-y, +-z (with +-0 in the other components) whose origins lie exactly on a
/// face plane of [0, 1]^3, inside the box's extent on the other two axes (0, 0.5 and 1 each).
std::vector<Ray> face_plane_rays(bool inside_extent) {
    std::vector<Ray> rays;
    const float coords[] = {0.0f, 0.5f, 1.0f};
    const float outside[] = {-0.5f, 1.5f};
    for (int axis = 0; axis < 3; ++axis) {                        // the travel axis
        for (int plane_axis = 0; plane_axis < 3; ++plane_axis) {  // the face plane the origin is on
            if (plane_axis == axis) continue;
            const int other = 3 - axis - plane_axis;
            for (float plane : {0.0f, 1.0f}) {
                for (float sign : {1.0f, -1.0f}) {
                    for (float zero : {0.0f, -0.0f}) {
                        const auto& others = inside_extent
                                                 ? std::vector<float>(coords, coords + 3)
                                                 : std::vector<float>(outside, outside + 2);
                        for (float c : others) {
                            Ray r;
                            r.dir = vec3(zero);
                            r.dir[axis] = sign;
                            r.org[axis] = sign > 0.0f ? -2.0f : 3.0f;
                            r.org[plane_axis] = plane;
                            r.org[other] = c;
                            rays.push_back(r);
                        }
                    }
                }
            }
        }
    }
    return rays;
}

/// A ray in a face plane of the box counts as touching it (the closed convention) in the node
/// test and in the box primitive; the entry distance is a number, never NaN; the packet path
/// decides the same at every width.
TEST(Slab, RaysInFacePlanesTouchTheBoxAndNeverGiveNaN) {
    const vec3 lo(0.0f), hi(1.0f);
    const Box box{lo, hi};
    for (bool inside : {true, false}) {
        SCOPED_TRACE(inside ? "origins within the face" : "origins beside the face");
        const std::vector<Ray> rays = face_plane_rays(inside);
        std::vector<float> scalar_box;
        size_t wrong = 0, nan_near = 0;
        for (const Ray& r : rays) {
            float t_near = 0.0f;
            const bool hit = intersect_slab(make_slab_ray(r), lo, hi, r.t_min, r.t_max, t_near);
            wrong += hit != inside;
            nan_near += hit && is_nan_bits(t_near);
            const float t = intersect_box(box, r);
            wrong += (t < infinity) != inside;
            nan_near += is_nan_bits(t);
            if (inside) wrong += t != 2.0f;  // entry at the face 2 units ahead
            scalar_box.push_back(t);
        }
        EXPECT_GT(rays.size(), 50u);
        EXPECT_EQ(wrong, 0u);
        EXPECT_EQ(nan_near, 0u);
        for_each_width([&](auto w) {
            constexpr int W = decltype(w)::value;
            SCOPED_TRACE("W = " + std::to_string(W));
            const std::vector<float> packet =
                packet_shape<W>(box, rays, [](const Box& b, const RayPacket<W>& p, vmask<W> a) {
                    return intersect_box<W>(b, p, a);
                });
            EXPECT_EQ(shape_disagreements(scalar_box, packet), 0u);
            size_t slab_wrong = 0;
            for (size_t first = 0; first < rays.size(); first += W) {
                vmask<W> active;
                const RayPacket<W> p = make_packet<W>(rays, first, active);
                vfloat<W> t_near;
                const uint32_t b = bits(intersect_slab<W>(make_slab_ray<W>(p), lo, hi, p.t_min,
                                                          p.t_max, t_near, active));
                for (int i = 0; i < W && first + size_t(i) < rays.size(); ++i) {
                    const bool hit = (b >> i) & 1u;
                    slab_wrong += hit != inside || (hit && is_nan_bits(get(t_near, i)));
                }
            }
            EXPECT_EQ(slab_wrong, 0u);
        });
    }
}

/// The single oracle test of §2: the cube (12 triangles) and a 2-triangle floor in its bottom
/// plane (coplanar ties), through the two-level BVH, against brute force over every triangle.
TEST(Slab, BvhMatchesBruteForceOnAdversarialRays) {
    const SceneData scene =
        make_mesh_scene({make_cube_mesh(vec3(0.0f), vec3(1.0f)), make_floor_mesh(0.0f, 2.0f)});
    const Accel accel = build_accel(scene, BuildParams{1});
    const std::vector<Ray> rays = adversarial_rays(ray_count(1000000));
    std::vector<Hit> scalar(rays.size());
    size_t mismatches = 0, nan_t = 0, hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Hit b = brute_force_closest(scene, rays[i]);
        scalar[i] = intersect_closest(scene, accel, rays[i]);
        const Hit& h = scalar[i];
        hits += h.hit();
        nan_t += is_nan_bits(h.t);
        if (h.hit() != b.hit() || h.object != b.object || h.prim != b.prim ||
            (h.hit() && ulp_distance(h.t, b.t) > 1))
            ++mismatches;
        if (intersect_any(scene, accel, rays[i]) != b.hit()) ++mismatches;
    }
    EXPECT_GT(hits, rays.size() / 5);
    EXPECT_EQ(mismatches, 0u) << "of " << rays.size() << " rays";
    EXPECT_EQ(nan_t, 0u);
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        SCOPED_TRACE("W = " + std::to_string(W));
        EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(scene, accel, rays)), 0u);
        const std::vector<uint8_t> any = packet_any<W>(scene, accel, rays);
        size_t any_wrong = 0;
        for (size_t i = 0; i < rays.size(); ++i) any_wrong += bool(any[i]) != scalar[i].hit();
        EXPECT_EQ(any_wrong, 0u);
    });
}

/// Conservative against the double oracle: whenever the double slab test says a grazing ray
/// touches a box, the float test says so too (Ize 2013: the far distance times 1 + 2 gamma_3).
TEST(Slab, FloatTestNeverMissesABoxTheDoubleTestTouches) {
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), s01(0.0f, 1.0f);
    std::uniform_real_distribution<float> expo(-6.0f, 6.0f);
    const size_t n = ray_count(1000000);
    size_t double_hits = 0, float_misses = 0, nan_near = 0;
    for (size_t i = 0; i < n; ++i) {
        // a box of random scale and place; a ray aimed at a point of its surface (a face, an
        // edge or a corner), nudged by a few ulps either way
        const float scale = std::pow(10.0f, expo(rng));
        const vec3 c = scale * 10.0f * vec3(unit(rng), unit(rng), unit(rng));
        const vec3 lo = c - scale * vec3(s01(rng), s01(rng), s01(rng));
        const vec3 hi = c + scale * vec3(s01(rng), s01(rng), s01(rng));
        vec3 target;
        for (int k = 0; k < 3; ++k) target[k] = lo[k] + s01(rng) * (hi[k] - lo[k]);
        const int snapped = 1 + int(rng() % 3);
        for (int k = 0; k < snapped; ++k) {
            const int axis = int(rng() % 3);
            target[axis] = rng() % 2 ? lo[axis] : hi[axis];
        }
        const vec3 u = glm::normalize(vec3(unit(rng), unit(rng), unit(rng)));
        Ray r;
        r.org = target - (scale * 5.0f) * u;
        r.dir = target - r.org;
        for (int k = 0; k < 3; ++k) {
            const int steps = int(rng() % 7) - 3;
            for (int s = 0; s < std::abs(steps); ++s)
                r.dir[k] = std::nextafter(r.dir[k], steps > 0 ? infinity : -infinity);
        }
        const RayOf<double> rd = ray_of<double>(r);
        double dn = 0.0;
        const bool touch_d = intersect_slab(make_slab_ray(rd), glm::dvec3(lo), glm::dvec3(hi),
                                            rd.t_min, rd.t_max, dn);
        float fn = 0.0f;
        const bool touch_f = intersect_slab(make_slab_ray(r), lo, hi, r.t_min, r.t_max, fn);
        double_hits += touch_d;
        float_misses += touch_d && !touch_f;
        nan_near += touch_f && is_nan_bits(fn);
    }
    EXPECT_GT(double_hits, n / 4);
    EXPECT_EQ(float_misses, 0u) << "of " << double_hits << " rays the double test lets touch";
    EXPECT_EQ(nan_near, 0u);
}

}  // namespace
}  // namespace raylane
