// numerics.md §7 : a box primitive of zero thickness (traverse/box_scalar.h,
// box_packet.h) and flat BVH nodes around a planar mesh, crossed head-on, at 45 degrees and at
// 89.9 degrees: every ray over the footprint hits, and the BVH answers as brute force does.
#include <gtest/gtest.h>

#include <random>

#include "support/geometry_support.h"
#include "traverse/box_packet.h"
#include "traverse/box_scalar.h"
#include "traverse/slab_packet.h"
#include "traverse/slab_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// A quad: the box of zero thickness in y, at awkward (non-dyadic) coordinates.
const Box flat_box{vec3(-1.3f, 0.7f, -0.9f), vec3(2.1f, 0.7f, 1.6f)};

/// Rays crossing the plane y = 0.7 at `tilt_deg` from its normal, downwards, through an n x n
/// grid of points of the footprint: cell centres, or with `edges` (head-on only, where x and z
/// do not change along the ray, so the rays pass exactly through them) the footprint's edges.
std::vector<Ray> footprint_rays(float tilt_deg, int n, float azimuth_deg, bool with_edges) {
    const double tilt = glm::radians(double(tilt_deg)), az = glm::radians(double(azimuth_deg));
    const glm::dvec3 d(std::sin(tilt) * std::cos(az), -std::cos(tilt),
                       std::sin(tilt) * std::sin(az));
    std::vector<Ray> rays;
    const vec3 lo = flat_box.lo, hi = flat_box.hi;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const bool edges = with_edges && tilt_deg == 0.0f;
            const double s = edges ? double(i) / (n - 1) : (i + 0.5) / n;
            const double r = edges ? double(j) / (n - 1) : (j + 0.5) / n;
            vec3 p(float(lo.x + s * (double(hi.x) - lo.x)), lo.y,
                   float(lo.z + r * (double(hi.z) - lo.z)));
            if (edges) {
                if (i == 0) p.x = lo.x;
                if (i == n - 1) p.x = hi.x;
                if (j == 0) p.z = lo.z;
                if (j == n - 1) p.z = hi.z;
            }
            Ray ray;
            ray.dir = vec3(d);
            ray.org = vec3(glm::dvec3(p) - 3.0 * d);
            if (edges) ray.org = vec3(p.x, p.y + 3.0f, p.z);
            rays.push_back(ray);
        }
    }
    return rays;
}

TEST(ZeroThicknessBox, IsHitOverItsWholeFootprintAtEveryAngle) {
    const int n = sanitized ? 40 : 300;
    for (float tilt : {0.0f, 45.0f, 89.9f}) {
        for (float az : {0.0f, 30.0f, 90.0f, 200.0f}) {
            SCOPED_TRACE("tilt " + std::to_string(tilt) + ", azimuth " + std::to_string(az));
            const std::vector<Ray> rays = footprint_rays(tilt, n, az, true);
            std::vector<float> scalar;
            size_t box_misses = 0, node_misses = 0, far_off = 0;
            int64_t worst = 0;
            for (const Ray& r : rays) {
                const float t = intersect_box(flat_box, r);
                box_misses += !(t < infinity);
                scalar.push_back(t);
                float t_near;
                node_misses += !intersect_slab(make_slab_ray(r), flat_box.lo, flat_box.hi, r.t_min,
                                               r.t_max, t_near);
                // the double oracle's t of the same ray
                const double td = intersect_box(flat_box, ray_of<double>(r));
                if (t < infinity && td < infinity_of<double>) {
                    const int64_t u = ulp_distance(t, float(td));
                    worst = std::max(worst, u);
                    far_off += u > 4;
                }
            }
            EXPECT_EQ(box_misses, 0u) << "of " << rays.size();
            EXPECT_EQ(node_misses, 0u);
            EXPECT_EQ(far_off, 0u) << "worst " << worst << " ulps from the double t";
            for_each_width([&](auto w) {
                constexpr int W = decltype(w)::value;
                SCOPED_TRACE("W = " + std::to_string(W));
                const std::vector<float> packet = packet_shape<W>(
                    flat_box, rays, [](const Box& b, const RayPacket<W>& p, vmask<W> a) {
                        return intersect_box<W>(b, p, a);
                    });
                EXPECT_EQ(shape_disagreements(scalar, packet), 0u);
            });
        }
    }
}

/// A ray lying in the plane of the zero-thickness slab (d.y = 0, o.y = 0.7) gives 0 * inf = NaN
/// for both planes: the primitive misses (nothing to hit edge-on), the node test keeps the box
/// (conservative), and neither produces NaN.
TEST(ZeroThicknessBox, RaysInItsPlaneMissWithoutNaN) {
    std::vector<Ray> rays;
    for (float z : {-0.9f, 0.0f, 1.6f})
        for (vec3 d : {vec3(1, 0, 0), vec3(1, -0.0f, 0.5f), vec3(-1, 0, -1)})
            rays.push_back({vec3(-5.0f, 0.7f, z) + (d.x < 0 ? vec3(10, 0, 0) : vec3(0)), d});
    std::vector<float> scalar;
    for (const Ray& r : rays) {
        const float t = intersect_box(flat_box, r);
        EXPECT_EQ(t, infinity);
        scalar.push_back(t);
        float t_near = 0.0f;
        if (intersect_slab(make_slab_ray(r), flat_box.lo, flat_box.hi, r.t_min, r.t_max, t_near)) {
            EXPECT_FALSE(is_nan_bits(t_near));
        }
    }
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        const std::vector<float> packet =
            packet_shape<W>(flat_box, rays, [](const Box& b, const RayPacket<W>& p, vmask<W> a) {
                return intersect_box<W>(b, p, a);
            });
        EXPECT_EQ(shape_disagreements(scalar, packet), 0u) << "W = " << W;
    });
}

/// A floor of 2 n^2 triangles at y = 0.7 in a BVH of flat nodes (every node has zero thickness
/// in y), seen at grazing angles: every ray over the floor hits, and the BVH gives brute force's
/// answer (primitive and t), in both paths.
TEST(ZeroThicknessBox, FlatBvhNodesHaveNoHolesAtGrazingAngles) {
    const int cells = 16;
    MeshData floor;
    floor.name = "tiled floor";
    for (int i = 0; i <= cells; ++i)
        for (int j = 0; j <= cells; ++j)
            floor.positions.push_back(
                vec3(-1.3f + 3.4f * float(i) / cells, 0.7f, -0.9f + 2.5f * float(j) / cells));
    for (int i = 0; i < cells; ++i) {
        for (int j = 0; j < cells; ++j) {
            const uint32_t a = uint32_t(i * (cells + 1) + j), b = a + 1,
                           c = a + uint32_t(cells + 1), d = c + 1;
            floor.tris.push_back({a, b, d});
            floor.tris.push_back({a, d, c});
        }
    }
    const SceneData scene = make_mesh_scene({floor});
    const Accel accel = build_accel(scene, BuildParams{2});
    const Aabb root = accel.meshes[0].bvh.nodes[0].bounds();
    ASSERT_EQ(root.lo.y, root.hi.y) << "the floor's nodes must be flat";
    std::vector<Ray> rays;
    const int n = 40;  // the same rays in every build: 25 views of 1,600 rays
    for (float tilt : {0.0f, 45.0f, 80.0f, 89.0f, 89.9f})
        for (float az : {0.0f, 45.0f, 90.0f, 135.0f, 250.0f})
            for (const Ray& r : footprint_rays(tilt, n, az, false)) rays.push_back(r);
    std::vector<Hit> scalar(rays.size());
    size_t misses = 0, mismatches = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        scalar[i] = intersect_closest(scene, accel, rays[i]);
        const Hit b = brute_force_closest(scene, rays[i]);
        misses += !b.hit();
        mismatches += scalar[i].prim != b.prim || scalar[i].t != b.t;
    }
    EXPECT_EQ(misses, 0u) << "of " << rays.size() << " rays over the floor";
    EXPECT_EQ(mismatches, 0u);
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        SCOPED_TRACE("W = " + std::to_string(W));
        EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(scene, accel, rays)), 0u);
    });
}

}  // namespace
}  // namespace raylane
