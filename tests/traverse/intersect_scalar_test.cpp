// Tests of traverse/intersect_scalar.cpp: two-level BVH traversal against brute force.
#include "traverse/intersect_scalar.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "io/load_mesh.h"
#include "support/models.h"
#include "traverse/surface_scalar.h"
#include "traverse/triangle_scalar.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int bunny_rays = 2000;
#else
constexpr int bunny_rays = 100000;
#endif

/// The mesh's vertices per triangle as structure of arrays, for the brute-force oracle.
struct TriangleSoa {
    std::vector<float> p[3][3];  ///< p[vertex][axis][triangle]
};

TriangleSoa make_soa(const MeshData& mesh) {
    TriangleSoa soa;
    for (auto& vertex : soa.p)
        for (auto& axis : vertex) axis.resize(mesh.tris.size());
    for (size_t i = 0; i < mesh.tris.size(); ++i)
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) soa.p[v][k][i] = mesh.positions[mesh.tris[i][v]][k];
    return soa;
}

/// Closest hit over every triangle of one mesh object, with the traversal's tie-break. A
/// vectorisable pass over all triangles keeps those whose sheared edge functions (the same
/// float expressions as intersect_triangle's) do not exclude the ray, zeros included; each of
/// those few candidates then goes through intersect_triangle itself.
Hit brute_force_mesh(const TriangleSoa& soa, uint32_t object, const Ray& ray,
                     std::vector<uint8_t>& maybe) {
    const WatertightRay wr = make_watertight_ray(ray);
    const size_t n = soa.p[0][0].size();
    maybe.resize(n);
    const float* P[3][3];
    for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 3; ++k) P[v][k] = soa.p[v][k].data();
    const float ox = wr.org[wr.kx], oy = wr.org[wr.ky], oz = wr.org[wr.kz];
    const float* axp = P[0][wr.kx];
    const float* ayp = P[0][wr.ky];
    const float* azp = P[0][wr.kz];
    const float* bxp = P[1][wr.kx];
    const float* byp = P[1][wr.ky];
    const float* bzp = P[1][wr.kz];
    const float* cxp = P[2][wr.kx];
    const float* cyp = P[2][wr.ky];
    const float* czp = P[2][wr.kz];
    uint8_t* out = maybe.data();
    for (size_t i = 0; i < n; ++i) {
        const float Az = azp[i] - oz, Bz = bzp[i] - oz, Cz = czp[i] - oz;
        const float ax = (axp[i] - ox) - wr.sx * Az, ay = (ayp[i] - oy) - wr.sy * Az;
        const float bx = (bxp[i] - ox) - wr.sx * Bz, by = (byp[i] - oy) - wr.sy * Bz;
        const float cx = (cxp[i] - ox) - wr.sx * Cz, cy = (cyp[i] - oy) - wr.sy * Cz;
        const float e_a = cx * by - cy * bx, e_b = ax * cy - ay * cx, e_c = bx * ay - by * ax;
        // bitwise, not short-circuit, so the loop vectorises
        const int neg = (e_a < 0.0f) | (e_b < 0.0f) | (e_c < 0.0f);
        const int pos = (e_a > 0.0f) | (e_b > 0.0f) | (e_c > 0.0f);
        const int zero = (e_a == 0.0f) | (e_b == 0.0f) | (e_c == 0.0f);
        out[i] = static_cast<uint8_t>(zero | (1 - (neg & pos)));
    }
    Hit best;
    for (uint32_t i = 0; i < n; ++i) {
        if (!out[i]) continue;
        const vec3 a(soa.p[0][0][i], soa.p[0][1][i], soa.p[0][2][i]);
        const vec3 b(soa.p[1][0][i], soa.p[1][1][i], soa.p[1][2][i]);
        const vec3 c(soa.p[2][0][i], soa.p[2][1][i], soa.p[2][2][i]);
        float th, u, v;
        if (intersect_triangle(wr, a, b, c, ray.t_min, ray.t_max, th, u, v) &&
            (th < best.t || (th == best.t && i < best.prim)))
            best = {th, i, object, vec2(u, v)};
    }
    return best;
}

/// Rays from a sphere around `box` towards random points inside it, plus random directions.
std::vector<Ray> random_rays(const Aabb& box, int n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    const vec3 c = box.center();
    const float r = glm::length(box.extent());
    std::vector<Ray> rays(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        const float z = 2.0f * uni(rng) - 1.0f, phi = 6.2831853f * uni(rng);
        const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        Ray& ray = rays[static_cast<size_t>(i)];
        ray.org = c + r * vec3(s * std::cos(phi), s * std::sin(phi), z);
        if (i % 4 == 3) {  // a random direction: many of these miss
            ray.dir = glm::normalize(vec3(uni(rng), uni(rng), uni(rng)) - 0.5f);
        } else {
            const vec3 target = box.lo + box.extent() * vec3(uni(rng), uni(rng), uni(rng));
            ray.dir = target - ray.org;
        }
        if (i % 16 == 5) ray.org = box.lo + box.extent() * vec3(uni(rng), uni(rng), uni(rng));
    }
    return rays;
}

TEST(IntersectScalar, ClosestHitEqualsBruteForceOnTheBunny) {
    const std::string path = std::string(RAYLANE_SHARED_DIR) + "/models/bunny.ply";
    if (!std::filesystem::exists(path)) {
        RAYLANE_MODEL_MISSING() << path << " not found";
    }
    SceneData scene;
    scene.meshes.push_back(load_mesh(path));
    scene.materials.push_back({});
    scene.objects.push_back({ShapeKind::mesh, 0, 0});
    const Accel accel = build_accel(scene, BuildParams{});
    const std::vector<Ray> rays = random_rays(accel.object_bounds[0], bunny_rays, 42);
    const TriangleSoa soa = make_soa(scene.meshes[0]);
    std::vector<Hit> got(rays.size()), want(rays.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size()),
                      [&](const tbb::blocked_range<size_t>& range) {
                          std::vector<uint8_t> maybe;
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                              got[i] = intersect_closest(scene, accel, rays[i]);
                              want[i] = brute_force_mesh(soa, 0, rays[i], maybe);
                          }
                      });
    int hits = 0, mismatches = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        hits += want[i].hit();
        if (got[i].prim != want[i].prim || got[i].t != want[i].t) {
            if (++mismatches <= 5)
                ADD_FAILURE() << "ray " << i << ": bvh prim " << got[i].prim << " t " << got[i].t
                              << ", brute force prim " << want[i].prim << " t " << want[i].t;
        }
        // any-hit agrees with closest-hit
        if (i % 8 == 0) {
            EXPECT_EQ(intersect_any(scene, accel, rays[i]), want[i].hit());
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(hits, bunny_rays / 3);  // many test rays hit: the comparison means something
}

TEST(IntersectScalar, EveryShapeKindThroughTheTopLevelEqualsBruteForce) {
    SceneData scene = make_builtin_scene();
    const Accel accel = build_accel(scene, BuildParams{1});
    Aabb bounds;
    for (const Aabb& b : accel.object_bounds)
        if (!b.empty()) bounds.grow(b);
    const std::vector<Ray> rays = random_rays(bounds, 20000, 7);
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const Hit got = intersect_closest(scene, accel, rays[i]);
        // brute force: every object alone in its own scene
        Hit want;
        for (uint32_t o = 0; o < scene.objects.size(); ++o) {
            SceneData one = scene;
            one.objects = {scene.objects[o]};
            const Accel a1 = build_accel(one, BuildParams{});
            Hit h = intersect_closest(one, a1, rays[i]);
            if (h.hit() && (h.t < want.t || (h.t == want.t && o < want.object))) {
                want = h;
                want.object = o;
            }
        }
        hits += want.hit();
        ASSERT_EQ(got.object, want.object) << "ray " << i;
        ASSERT_EQ(got.t, want.t) << "ray " << i;
        ASSERT_EQ(intersect_any(scene, accel, rays[i]), want.hit()) << "ray " << i;
        if (i > 2000) break;
    }
    EXPECT_GT(hits, 500);
}

TEST(IntersectScalar, EmptySceneHitsNothing) {
    SceneData scene;
    const Accel accel = build_accel(scene, BuildParams{});
    Ray ray;
    EXPECT_FALSE(intersect_closest(scene, accel, ray).hit());
    EXPECT_FALSE(intersect_any(scene, accel, ray));
}

TEST(IntersectScalar, RespectsTheRayInterval) {
    SceneData scene;
    scene.materials.push_back({});
    scene.spheres.push_back({vec3(0.0f, 0.0f, 5.0f), 1.0f});
    scene.objects.push_back({ShapeKind::sphere, 0, 0});
    const Accel accel = build_accel(scene, BuildParams{});
    Ray ray;  // from the origin along +z: hits at t = 4
    EXPECT_FLOAT_EQ(intersect_closest(scene, accel, ray).t, 4.0f);
    ray.t_max = 4.0f;  // open interval: t = 4 is excluded
    EXPECT_FALSE(intersect_any(scene, accel, ray));
    ray.t_max = 0.0f;
    EXPECT_FALSE(intersect_closest(scene, accel, ray).hit());
    ray.t_max = infinity;
    ray.t_min = 4.5f;  // inside: the far side at t = 6
    EXPECT_FLOAT_EQ(intersect_closest(scene, accel, ray).t, 6.0f);
}

TEST(IntersectScalar, TransformedSphereMovesWithItsTransform) {
    SceneData scene;
    scene.materials.push_back({});
    scene.spheres.push_back({vec3(0.0f), 1.0f});
    Object o{ShapeKind::sphere, 0, 0};
    o.has_transform = true;
    o.world_from_object =
        glm::translate(mat4(1.0f), vec3(0.0f, 0.0f, 10.0f)) * glm::scale(mat4(1.0f), vec3(2.0f));
    o.object_from_world = glm::inverse(o.world_from_object);
    scene.objects.push_back(o);
    const Accel accel = build_accel(scene, BuildParams{});
    Ray ray;
    const Hit hit = intersect_closest(scene, accel, ray);
    ASSERT_TRUE(hit.hit());
    EXPECT_FLOAT_EQ(hit.t, 8.0f);
    const SurfacePoint sp = surface_at(scene, ray, hit);
    EXPECT_NEAR(sp.geometric_normal.z, -1.0f, 1e-6f);
    EXPECT_NEAR(sp.position.z, 8.0f, 1e-5f);
}

/// surface_at gives uv on spheres and cylinders only to a material that reads it (a texture or
/// a normal map): the same normal and position either way, uv 0 otherwise (no acos / atan2).
TEST(IntersectScalar, SurfaceUvOnlyForMaterialsThatReadIt) {
    for (ShapeKind kind : {ShapeKind::sphere, ShapeKind::cylinder}) {
        SceneData scene;
        scene.materials.resize(3);
        scene.materials[1].texture = 0;
        scene.materials[2].normal_map = 0;
        scene.spheres.push_back({vec3(0.0f), 1.0f});
        scene.cylinders.push_back({1.0f, 2.0f});
        scene.objects.push_back(Object{kind, 0, 0});
        const Accel accel = build_accel(scene, BuildParams{});
        Ray ray;
        ray.org = vec3(0.3f, 0.5f, -5.0f);
        ray.dir = vec3(0.0f, 0.0f, 1.0f);
        const Hit hit = intersect_closest(scene, accel, ray);
        ASSERT_TRUE(hit.hit());
        const SurfacePoint plain = surface_at(scene, ray, hit);
        EXPECT_EQ(plain.uv, vec2(0.0f));
        for (uint32_t material : {1u, 2u}) {
            scene.objects[0].material = material;
            const SurfacePoint sp = surface_at(scene, ray, hit);
            EXPECT_GT(sp.uv.x, 0.5f) << int(kind);  // the -z side: azimuth past a half turn
            EXPECT_GT(sp.uv.y, 0.0f) << int(kind);
            EXPECT_EQ(sp.position, plain.position);
            EXPECT_EQ(sp.geometric_normal, plain.geometric_normal);
        }
    }
}

}  // namespace
}  // namespace raylane
