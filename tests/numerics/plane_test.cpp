// numerics.md §6 and §20 : rays parallel to a plane, lying in it, and with
// tiny and denormal slopes (traverse/plane_scalar.h, plane_packet.h): a miss or a finite t,
// never NaN; shadow rays leaving a plane do not hit it; planes stay out of the BVH.
#include <gtest/gtest.h>

#include <random>

#include "core/offset.h"
#include "support/geometry_support.h"
#include "traverse/plane_packet.h"
#include "traverse/plane_scalar.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

std::vector<float> packet_plane_t(const Plane& pl, const std::vector<Ray>& rays, auto w) {
    constexpr int W = decltype(w)::value;
    return packet_shape<W>(pl, rays, [](const Plane& p, const RayPacket<W>& r, vmask<W> a) {
        return intersect_plane<W>(p, r, a);
    });
}

TEST(Plane, ParallelInPlaneAndDenormalSlopeRaysNeverGiveNaN) {
    const Plane pl{vec3(0.0f, -1.5f, 0.0f), vec3(0.0f, 1.0f, 0.0f)};
    struct Case {
        const char* name;
        Ray ray;
        bool may_hit;  ///< false: must miss; true: a miss or a finite t > 0
    };
    const Case cases[] = {
        {"parallel above", {vec3(0.0f, 2.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)}, false},
        {"parallel below", {vec3(3.0f, -4.0f, 1.0f), vec3(0.0f, -0.0f, 1.0f)}, false},
        {"in the plane", {vec3(1.0f, -1.5f, 2.0f), vec3(0.6f, 0.0f, 0.8f)}, false},
        {"in the plane, -0 slope", {vec3(1.0f, -1.5f, 2.0f), vec3(0.6f, -0.0f, -0.8f)}, false},
        {"slope -1e-30", {vec3(0.0f, 2.0f, 0.0f), vec3(1.0f, -1e-30f, 0.0f)}, true},
        {"slope -1e-45 (denormal)", {vec3(0.0f, 2.0f, 0.0f), vec3(1.0f, -1e-45f, 0.0f)}, true},
        {"slope -1e-38", {vec3(0.0f, 2.0f, 0.0f), vec3(1.0f, -1e-38f, 0.0f)}, true},
        {"in the plane, slope -1e-45", {vec3(0.0f, -1.5f, 0.0f), vec3(1.0f, -1e-45f, 0.0f)}, true},
        {"towards it", {vec3(0.0f, 2.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f)}, true},
    };
    std::vector<Ray> rays;
    std::vector<float> scalar;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const float t = intersect_plane(pl, c.ray);
        EXPECT_FALSE(is_nan_bits(t));
        if (c.may_hit)
            EXPECT_TRUE(t == infinity || (t > 0.0f && std::isfinite(t))) << t;
        else
            EXPECT_EQ(t, infinity);
        const double td = intersect_plane(pl, ray_of<double>(c.ray));
        EXPECT_FALSE(td != td);
        rays.push_back(c.ray);
        scalar.push_back(t);
    }
    EXPECT_EQ(scalar.back(), 3.5f);
    for_each_width([&](auto w) {
        EXPECT_EQ(shape_disagreements(scalar, packet_plane_t(pl, rays, w)), 0u)
            << "W = " << decltype(w)::value;
    });
}

/// Points on a tilted plane seen by a camera at scales 1e-4, 1 and 1e5: the shadow ray to a
/// light above the plane, from offset_ray_origin as shading spawns it, is never occluded by the
/// plane it leaves (no tmin epsilon anywhere).
TEST(Plane, ShadowRaysLeavingThePlaneAreNotOccludedByIt) {
    const size_t n = ray_count(200000);
    for (float scale : {1e-4f, 1.0f, 1e5f}) {
        SCOPED_TRACE("scale " + std::to_string(scale));
        SceneData scene;
        scene.materials.push_back(Material{});
        scene.planes.push_back(
            {scale * vec3(0.3f, -1.0f, 0.2f), vec3(glm::normalize(glm::dvec3(0.1, 1.0, -0.25)))});
        Object o;
        o.kind = ShapeKind::plane;
        scene.objects.push_back(o);
        const Accel accel = build_accel(scene, BuildParams{});
        const vec3 eye = scale * vec3(0.0f, 1.0f, -4.0f);
        const vec3 light = scale * vec3(2.0f, 5.0f, 3.0f);
        std::mt19937 rng(4);
        std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
        std::vector<Ray> shadow;
        for (size_t i = 0; i < n; ++i) {
            const vec3 d = glm::normalize(vec3(unit(rng), -0.2f + 0.19f * unit(rng), 1.0f));
            const Ray r{eye, d, 0.0f, infinity};
            const Hit h = intersect_closest(scene, accel, r);
            if (!h.hit()) continue;
            const SurfacePoint sp = surface_at(scene, r, h);
            const vec3 ng = glm::dot(sp.geometric_normal, d) > 0.0f ? -sp.geometric_normal
                                                                    : sp.geometric_normal;
            const vec3 org = offset_ray_origin(sp.position, ng, ray_reach(r, h.t));
            shadow.push_back({org, light - org, 0.0f, 1.0f});
        }
        ASSERT_GT(shadow.size(), n / 2);
        std::vector<uint8_t> scalar;
        for (const Ray& r : shadow) scalar.push_back(intersect_any(scene, accel, r));
        EXPECT_EQ(std::count(scalar.begin(), scalar.end(), uint8_t{1}), 0)
            << "of " << shadow.size() << " shadow rays";
        for_each_width([&](auto w) {
            constexpr int W = decltype(w)::value;
            EXPECT_TRUE(packet_any<W>(scene, accel, shadow) == scalar) << "W = " << W;
        });
    }
}

/// §6 and §20: infinite planes are tested from Accel::unbounded, never put in the top-level BVH
/// (an infinite box would spoil every median split above it).
TEST(Plane, PlanesStayOutOfTheBvh) {
    SceneData scene = make_mesh_scene({make_cube_mesh(vec3(0.0f), vec3(1.0f))});
    scene.spheres.push_back({vec3(3.0f), 1.0f});
    scene.planes.push_back({vec3(0.0f), vec3(0.0f, 1.0f, 0.0f)});
    scene.planes.push_back({vec3(0.0f, 9.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f)});
    Object sphere;
    scene.objects.push_back(sphere);
    for (uint32_t k = 0; k < 2; ++k) {
        Object o;
        o.kind = ShapeKind::plane;
        o.shape = k;
        scene.objects.push_back(o);
    }
    const Accel accel = build_accel(scene, BuildParams{});
    EXPECT_EQ(accel.unbounded, (std::vector<uint32_t>{2, 3}));
    ASSERT_FALSE(accel.top.nodes.empty());
    for (uint32_t id : accel.top.prim_ids) EXPECT_NE(scene.objects[id].kind, ShapeKind::plane);
    const Aabb root = accel.top.nodes[0].bounds();
    EXPECT_TRUE(std::isfinite(root.lo.x) && std::isfinite(root.hi.y) && std::isfinite(root.hi.z));
    // and the planes are still found
    const Hit h = intersect_closest(scene, accel, {vec3(-5.0f, 4.0f, -5.0f), vec3(0, 1, 0)});
    EXPECT_EQ(h.object, 3u);
    EXPECT_EQ(h.t, 5.0f);
}

}  // namespace
}  // namespace raylane
