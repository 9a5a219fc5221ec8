// numerics.md §8 : degenerate triangles (three identical vertices, collinear
// vertices, a sliver of area 1e-20 edge^2) and NaN vertices: the loaders (io/load_obj.h,
// io/load_ply.h) reject NaN and drop zero-area triangles, the watertight test
// (traverse/triangle_scalar.h, triangle_packet.h) never reports a degenerate triangle as hit, the
// median build terminates on identical centroids, and rendering produces no NaN.
#include <gtest/gtest.h>

#include <random>

#include "core/error.h"
#include "io/load_obj.h"
#include "io/load_ply.h"
#include "render/camera_rays.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "support/geometry_support.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// Face 1: a sliver (area 1e-20 of its edge length squared); 2: three identical vertices;
/// 3: three collinear vertices; 4: a proper triangle; 5: two identical vertices.
const char* const degenerate_obj = R"(v -1 0 0
v 1 0 0
v 0 0 4e-20
v 0.2 0 0.2
v -1 -0.5 0
v 0 -0.5 0
v 1 -0.5 0
v -2 -1 -2
v 2 -1 -2
v 0 -1 2
f 1 2 3
f 4 4 4
f 5 6 7
f 8 9 10
f 1 1 2
)";

const char* const degenerate_ply = R"(ply
format ascii 1.0
element vertex 10
property float x
property float y
property float z
element face 5
property list uchar int vertex_indices
end_header
-1 0 0
1 0 0
0 0 4e-20
0.2 0 0.2
-1 -0.5 0
0 -0.5 0
1 -0.5 0
-2 -1 -2
2 -1 -2
0 -1 2
3 0 1 2
3 3 3 3
3 4 5 6
3 7 8 9
3 0 0 1
)";

/// The same five faces built directly (every face kept, whatever the loaders drop), for the
/// intersection and rendering tests.
MeshData degenerate_mesh() {
    MeshData m;
    m.name = "degenerate";
    m.positions = {{-1, 0, 0},    {1, 0, 0},     {0, 0, 4e-20f}, {0.2f, 0, 0.2f}, {-1, -0.5f, 0},
                   {0, -0.5f, 0}, {1, -0.5f, 0}, {-4, -1, -4},   {4, -1, -4},     {0, -1, 4}};
    m.tris = {{0, 1, 2}, {3, 3, 3}, {4, 5, 6}, {7, 8, 9}, {0, 0, 1}};
    return m;
}

bool has_zero_area(const MeshData& m) {
    for (uvec3 t : m.tris)
        if (is_zero_area_triangle(m.positions[t.x], m.positions[t.y], m.positions[t.z]))
            return true;
    return false;
}

/// numerics.md §8: "Reject NaN/Inf vertex coordinates in the loader" - one line, file:line.
TEST(DegenerateTriangle, LoadersRejectNaNAndInfiniteVertices) {
    for (const char* bad : {"nan", "-nan", "inf", "-inf", "1e39"}) {
        SCOPED_TRACE(bad);
        const std::string obj = std::string("v 0 0 0\nv 1 0 0\nv 0 ") + bad + " 0\nf 1 2 3\n";
        try {
            load_obj_from_memory(obj, "nan.obj");
            ADD_FAILURE() << "load_obj accepted a non-finite vertex";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind("nan.obj:3:", 0), 0u) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
        const std::string ply = std::string(
                                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\n1 0 0\n0 ") +
                                bad + " 0\n3 0 1 2\n";
        try {
            load_ply_from_memory(ply, "nan.ply");
            ADD_FAILURE() << "load_ply accepted a non-finite vertex";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind("nan.ply:", 0), 0u) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

/// numerics.md §8: zero-area triangles (cross product exactly zero, in double) are dropped at
/// load time; the sliver is not zero-area and stays. Expected: faces 1 and 4 only.
TEST(DegenerateTriangle, LoadersDropZeroAreaTriangles) {
    const MeshData obj = load_obj_from_memory(degenerate_obj, "degenerate.obj");
    EXPECT_FALSE(has_zero_area(obj)) << "load_obj keeps zero-area triangles";
    EXPECT_EQ(obj.tris.size(), 2u);
    const MeshData ply = load_ply_from_memory(degenerate_ply, "degenerate.ply");
    EXPECT_FALSE(has_zero_area(ply)) << "load_ply keeps zero-area triangles";
    EXPECT_EQ(ply.tris.size(), 2u);
}

/// Rays through the identical-vertex and collinear triangles (through their vertices, along
/// their line, across it), far from and near the origin: never a hit, in float, in double, and
/// through the BVH in both paths.
TEST(DegenerateTriangle, ZeroAreaTrianglesAreNeverHit) {
    for (float shift : {0.0f, 1e5f}) {
        SCOPED_TRACE("shifted by " + std::to_string(shift));
        MeshData m = degenerate_mesh();
        for (vec3& p : m.positions) p += vec3(shift);
        const std::vector<uint32_t> zero_area = {1, 2, 4};
        for (uint32_t k : zero_area) {
            const uvec3 t = m.tris[k];
            ASSERT_TRUE(
                is_zero_area_triangle(m.positions[t.x], m.positions[t.y], m.positions[t.z]));
        }
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> unit(-1.0f, 1.0f), s01(0.0f, 1.0f);
        std::vector<Ray> rays;
        for (uint32_t k : zero_area) {
            const uvec3 t = m.tris[k];
            const vec3 a = m.positions[t.x], c = m.positions[t.z];
            for (int i = 0; i < (sanitized ? 200 : 5000); ++i) {
                const vec3 target = i % 3 == 0 ? a : a + s01(rng) * (c - a);
                vec3 dir = glm::normalize(vec3(unit(rng), unit(rng), unit(rng)));
                if (i % 5 == 0) dir = glm::normalize(c - a);  // along the line
                if (i % 7 == 0) dir = vec3(0.0f, -1.0f, 0.0f);
                rays.push_back({target - 3.0f * dir, dir, 0.0f, infinity});
            }
        }
        size_t hits = 0;
        for (const Ray& r : rays) {
            const RayOf<double> rd = ray_of<double>(r);
            for (uint32_t k : zero_area) {
                const uvec3 t = m.tris[k];
                float tf, uf, vf;
                hits +=
                    intersect_triangle(make_watertight_ray(r), m.positions[t.x], m.positions[t.y],
                                       m.positions[t.z], r.t_min, r.t_max, tf, uf, vf);
                double td, ud, vd;
                hits +=
                    intersect_triangle(make_watertight_ray(rd), glm::dvec3(m.positions[t.x]),
                                       glm::dvec3(m.positions[t.y]), glm::dvec3(m.positions[t.z]),
                                       rd.t_min, rd.t_max, td, ud, vd);
            }
        }
        EXPECT_EQ(hits, 0u) << "degenerate triangles reported as hit";
        const SceneData scene = make_mesh_scene({m});
        const Accel accel = build_accel(scene, BuildParams{1});
        std::vector<Hit> scalar;
        size_t degenerate_hits = 0;
        for (const Ray& r : rays) {
            scalar.push_back(intersect_closest(scene, accel, r));
            const uint32_t p = scalar.back().prim;
            degenerate_hits += p == 1 || p == 2 || p == 4;
        }
        EXPECT_EQ(degenerate_hits, 0u);
        for_each_width([&](auto w) {
            constexpr int W = decltype(w)::value;
            const std::vector<Hit> packet = packet_closest<W>(scene, accel, rays);
            EXPECT_EQ(hit_disagreements(scalar, packet), 0u) << "W = " << W;
        });
    }
}

/// The sliver is a real triangle: rays inside it and along its long edge hit with t within 2 ulps
/// and barycentrics in [0, 1], and its geometric normal (geometry_triangle, as surface_at uses it)
/// is a finite unit vector although |cross| ^ 2 = 6.4e-39 is below the smallest normal float.
TEST(DegenerateTriangle, SliversGiveFiniteHitsAndNormals) {
    const MeshData m = degenerate_mesh();
    const uvec3 t = m.tris[0];
    const vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    ASSERT_FALSE(is_zero_area_triangle(a, b, c));
    std::vector<Ray> rays;
    for (float x = -0.95f; x < 0.95f; x += 0.01f) {
        rays.push_back({vec3(x, 3.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f)});  // along the long edge
        rays.push_back(
            {vec3(x, 3.0f, 1e-20f * (1.0f - std::fabs(x))), vec3(0.0f, -1.0f, 0.0f)});  // inside
    }
    size_t hits = 0, bad_values = 0, bad_normals = 0;
    const SceneData scene = make_mesh_scene({m});
    const Accel accel = build_accel(scene, BuildParams{});
    for (const Ray& r : rays) {
        float th, u, v;
        if (!intersect_triangle(make_watertight_ray(r), a, b, c, r.t_min, r.t_max, th, u, v))
            continue;
        ++hits;
        bad_values +=
            !(ulp_distance(th, 3.0f) <= 2 && u >= 0.0f && v >= 0.0f && u + v <= 1.0f + 1e-6f);
        const vec3 n = geometry_triangle(a, b, c, u, v).normal;
        bad_normals += !(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) &&
                         std::fabs(glm::length(n) - 1.0f) < 1e-6f);
        const Hit h = intersect_closest(scene, accel, r);
        EXPECT_EQ(h.prim, 0u);
        const SurfacePoint sp = surface_at(scene, r, h);
        bad_normals += !std::isfinite(sp.geometric_normal.y);
    }
    EXPECT_EQ(hits, rays.size());
    EXPECT_EQ(bad_values, 0u);
    EXPECT_EQ(bad_normals, 0u) << "non-finite normals of the sliver";
}

/// numerics.md §8: the median build does not recurse forever on identical centroids (it splits
/// by count), and the tree it makes is valid and shallow.
TEST(DegenerateTriangle, MedianBuildTerminatesOnIdenticalCentroids) {
    const size_t n = 10000;
    std::vector<Aabb> boxes(n, Aabb{vec3(0.5f), vec3(0.5f)});
    for (size_t i = 0; i < n; i += 3) boxes[i] = Aabb{vec3(-1.0f), vec3(2.0f)};  // same centre
    const Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    EXPECT_EQ(check_bvh(bvh, boxes, 4), "");
    const BvhStats st = compute_stats(bvh);
    EXPECT_LE(st.max_leaf_depth, int(std::ceil(std::log2(double(n) / 4.0))) + 1);
}

/// A scene showing the sliver edge-on along a pixel row, the other degenerate triangles behind it
/// and the proper triangle around them, lit from above: both renderers produce no NaN or
/// infinite sample, a finite image, and the pixels that see the sliver are lit like the rest
/// (a NaN normal would make them silently black: every comparison with NaN is false).
TEST(DegenerateTriangle, RenderingProducesNoNaN) {
    SceneData scene = make_mesh_scene({degenerate_mesh()});
    scene.camera.position = vec3(0.0f, 5.0f, 0.0f);
    scene.camera.look_at = vec3(0.0f, 0.0f, 0.0f);
    scene.camera.up = vec3(0.0f, 0.0f, 1.0f);
    scene.camera.width = 201;
    scene.camera.height = 1;  // one row: its rays have a direction z of exactly 0
    scene.camera.fov_deg = 40.0f;
    scene.camera.fov_axis = FovAxis::horizontal;
    Light light;
    light.position = vec3(0.5f, 4.0f, 0.0f);
    scene.lights.push_back(light);
    const Accel accel = build_accel(scene, BuildParams{});
    // the pixels whose primary ray hits the sliver (primitive 0) and the proper triangle (3)
    const CameraFrame frame = make_camera_frame(scene.camera);
    std::vector<uint32_t> prim;
    for (int x = 0; x < scene.camera.width; ++x)
        prim.push_back(
            intersect_closest(scene, accel, camera_ray(frame, float(x) + 0.5f, 0.5f)).prim);
    ASSERT_GT(std::count(prim.begin(), prim.end(), 0u), 50);
    ASSERT_GT(std::count(prim.begin(), prim.end(), 3u), 10);
    RenderParams params;
    params.threads = 1;
    for (bool packet : {false, true}) {
        SCOPED_TRACE(packet ? "packet" : "scalar");
        const RenderResult res =
            packet ? render_packet(scene, accel, params) : render_scalar(scene, accel, params);
        EXPECT_EQ(res.stats.nan_samples, 0u);
        EXPECT_EQ(res.stats.inf_samples, 0u);
        size_t bad = 0, dark_sliver = 0, lit_triangle = 0;
        for (int x = 0; x < scene.camera.width; ++x) {
            const vec3 px = res.film.at(x, 0);
            bad += !(std::isfinite(px.x) && std::isfinite(px.y) && std::isfinite(px.z));
            dark_sliver += prim[size_t(x)] == 0u && !(px.x > 0.0f);
            lit_triangle += prim[size_t(x)] == 3u && px.x > 0.0f;
        }
        EXPECT_EQ(bad, 0u);
        EXPECT_GT(lit_triangle, 0u) << "the proper triangle is lit";
        EXPECT_EQ(dark_sliver, 0u) << "pixels on the sliver (facing the light) came out black";
    }
}

}  // namespace
}  // namespace raylane
