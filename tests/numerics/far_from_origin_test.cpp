// numerics.md §17 and §20: models far from the origin (io/load_scene.cpp,
// traverse/), barycentric hit points of far triangles, and a median-split BVH over
// exponentially spaced centroids (accel/build_median.cpp) traversed without overflowing the
// fixed traversal stacks of intersect_scalar.cpp / intersect_packet.cpp.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "accel/bvh.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "support/geometry_support.h"
#include "support/models.h"
#include "traverse/surface_packet.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// scenes/bunny.json's bunny and floor, everything moved by `shift` (camera, light and plane
/// included): the same picture in exact arithmetic.
std::string bunny_json(double shift) {
    auto v = [&](double x, double y, double z) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", x + shift, y + shift, z + shift);
        return std::string(buf);
    };
    return R"({"version": 1,
  "camera": {"position": )" +
           v(0, 0, 0) + R"(, "look_at": )" + v(0, -0.6, 6) + R"(, "up": [0, 1, 0],
             "fov_deg": 40, "fov_axis": "horizontal", "resolution": [320, 180]},
  "materials": {"floor": {}, "bunny": {}},
  "objects": [
    {"shape": "plane", "point": )" +
           v(0, -1.5, 0) + R"(, "normal": [0, 1, 0], "material": "floor"},
    {"shape": "mesh", "file": "bunny.ply", "material": "bunny",
     "fit": {"scale": 30, "offset": [-0.5, 0.1, 0]},
     "transform": {"translate": )" +
           v(0, -1.6, 6) + R"(, "rotate": [{"axis": "y", "deg": -175}]}}
  ],
  "lights": [{"type": "point", "position": )" +
           v(-4, 4, 1) + R"(, "intensity": 50}]})";
}

/// Per pixel: (object, primitive) of the primary hit.
std::vector<std::pair<uint32_t, uint32_t>> primary_ids(const SceneData& scene, const Accel& accel,
                                                       std::vector<Ray>* rays = nullptr) {
    const CameraFrame f = make_camera_frame(scene.camera);
    std::vector<std::pair<uint32_t, uint32_t>> ids;
    for (int y = 0; y < scene.camera.height; ++y) {
        for (int x = 0; x < scene.camera.width; ++x) {
            const Ray r = camera_ray(f, float(x) + 0.5f, float(y) + 0.5f);
            const Hit h = intersect_closest(scene, accel, r);
            ids.push_back({h.object, h.prim});
            if (rays) rays->push_back(r);
        }
    }
    return ids;
}

/// numerics.md §17: the bunny and its camera moved by (1e5, 1e5, 1e5) must give the picture of
/// the bunny at home (primitive ids within 1 % of the pixels): the loader's camera-relative
/// origin (everything translated by -camera in double, then rounded to float). The agreement is
/// printed.
TEST(FarFromOrigin, TranslatedBunnyRendersLikeTheBunnyAtHome) {
    const std::string where = std::string(RAYLANE_SOURCE_DIR) + "/scenes/far_bunny.json";
    SceneData home, far;
    try {
        home = load_scene_from_string(bunny_json(0.0), where);
        far = load_scene_from_string(bunny_json(1e5), where);
    } catch (const std::exception& e) {
        RAYLANE_MODEL_MISSING() << "bunny.ply is not available: " << e.what();
    }
    if (sanitized) {
        home.camera.width = far.camera.width = 80;
        home.camera.height = far.camera.height = 45;
    }
    const Accel home_accel = build_accel(home, BuildParams{});
    const Accel far_accel = build_accel(far, BuildParams{});
    std::vector<Ray> far_rays;
    const auto a = primary_ids(home, home_accel);
    const auto b = primary_ids(far, far_accel, &far_rays);
    size_t same_prim = 0, same_object = 0, bunny = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        same_prim += a[i] == b[i];
        same_object += a[i].first == b[i].first;
        bunny += a[i].first == 1;
    }
    ASSERT_GT(bunny, a.size() / 20) << "the bunny must be in view";
    const double prim_agree = double(same_prim) / double(a.size());
    std::printf(
        "[ measured ] bunny at 1e5: same primitive in %.1f %% of pixels, same object in "
        "%.1f %%\n",
        100.0 * prim_agree, 100.0 * double(same_object) / double(a.size()));
    EXPECT_GE(prim_agree, 0.99) << "the translated bunny is not the bunny at home";
    // row P: the packet path sees the translated scene as the scalar path does
    std::vector<Hit> scalar;
    for (const Ray& r : far_rays) scalar.push_back(intersect_closest(far, far_accel, r));
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(far, far_accel, far_rays)), 0u)
            << "W = " << W;
    });
}

/// A camera far from the origin that looks outwards at a point ten times farther away, with a
/// sphere 10 and a plane 40 ahead of it, in scene-file numbers (written with 17 digits).
struct FarCameraScene {
    glm::dvec3 eye{100000.3, 200000.7, -299999.9};
    glm::dvec3 look_at = 10.0 * eye;
    glm::dvec3 center, plane_point, plane_normal;
    double radius = 2.5;

    FarCameraScene() {
        const glm::dvec3 w = glm::normalize(look_at - eye);
        const glm::dvec3 u = glm::normalize(glm::cross(w, glm::dvec3(0, 1, 0)));
        center = eye + 10.0 * w + 0.5 * u;
        plane_point = eye + 40.0 * w;
        plane_normal = glm::normalize(-w + 0.2 * u);
    }

    std::string json() const {
        auto v = [](glm::dvec3 p) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", p.x, p.y, p.z);
            return std::string(buf);
        };
        return R"({"version": 1,
  "camera": {"position": )" +
               v(eye) + R"(, "look_at": )" + v(look_at) + R"(, "up": [0, 1, 0],
             "fov_deg": 40, "resolution": [24, 16]},
  "materials": {"grey": {}},
  "objects": [
    {"shape": "sphere", "center": )" +
               v(center) + R"(, "radius": )" + std::to_string(radius) +
               R"(, "material": "grey"},
    {"shape": "plane", "point": )" +
               v(plane_point) + R"(, "normal": )" + v(plane_normal) + R"(, "material": "grey"}]})";
    }

    /// The depth of the world ray (org, dir) on object 0 (the sphere) or 1 (the plane), in
    /// closed form in double on the scene file's numbers.
    double depth(uint32_t object, glm::dvec3 org, glm::dvec3 dir) const {
        if (object == 1)
            return glm::dot(plane_point - org, plane_normal) / glm::dot(dir, plane_normal);
        const glm::dvec3 f = org - center;
        const double a = glm::dot(dir, dir), b = glm::dot(f, dir);
        const double c = glm::dot(f, f) - radius * radius;
        return c / (-b + std::sqrt(b * b - a * c));
    }
};

/// numerics.md §17: the world origin follows the eye, however far away the look-at point is
/// set. Every pixel's primary depth on the sphere 10 ahead and the plane 40 ahead, within 1e-6
/// relative of the closed form in double (on the traced ray, moved back to world space), in both
/// paths. Left where it is, the scene would hold its shapes in floats spaced 1/128 to 1/32 apart.
TEST(FarFromOrigin, CameraLookingFarAwayKeepsTheDepthsNearIt) {
    const FarCameraScene fs;
    const SceneData scene = load_scene_from_string(fs.json(), "far_camera.json");
    const Accel accel = build_accel(scene, BuildParams{});
    const CameraFrame frame = make_camera_frame(scene.camera);
    std::vector<Ray> rays;
    std::vector<Hit> scalar;
    double worst = 0.0;
    size_t off = 0, on_sphere = 0;
    for (int y = 0; y < scene.camera.height; ++y) {
        for (int x = 0; x < scene.camera.width; ++x) {
            const Ray r = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const Hit h = intersect_closest(scene, accel, r);
            ASSERT_TRUE(h.hit()) << "pixel " << x << ", " << y;
            const double t_exact =
                fs.depth(h.object, scene.world_origin + glm::dvec3(r.org), glm::dvec3(r.dir));
            const double err = std::fabs(double(h.t) - t_exact) / t_exact;
            worst = std::max(worst, err);
            off += err > 1e-6;
            on_sphere += h.object == 0;
            rays.push_back(r);
            scalar.push_back(h);
        }
    }
    EXPECT_GT(on_sphere, rays.size() / 10);
    EXPECT_LT(on_sphere, rays.size() * 9 / 10);
    EXPECT_EQ(off, 0u) << "depths off by more than 1e-6 relative; worst " << worst;
    std::printf("[ measured ] camera at 3e5 looking 3e6 away: worst relative depth error %.3g\n",
                worst);
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(scene, accel, rays)), 0u)
            << "W = " << W;
    });
}

/// Hit points on triangles near (1e5, 1e5, 1e5) come from the barycentrics (surface_at, numerics.md
/// §3), so they lie on the triangle's plane within pbrt's bound gamma_7 sum |b_i p_i| (Pharr,
/// Jakob, Humphreys, "Physically Based Rendering" 4th ed., 6.8.5), not within the error of
/// o + t d. Both paths.
TEST(FarFromOrigin, BarycentricHitPointsStayOnFarTriangles) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    MeshData m;
    m.name = "far triangles";
    const vec3 base(1e5f);
    for (uint32_t k = 0; k < 64; ++k) {
        const vec3 c = base + vec3(unit(rng), unit(rng), unit(rng)) * 20.0f;
        for (int j = 0; j < 3; ++j)
            m.positions.push_back(c + vec3(unit(rng), unit(rng), unit(rng)));
        m.tris.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    }
    const SceneData scene = make_mesh_scene({m});
    const Accel accel = build_accel(scene, BuildParams{});
    std::vector<Ray> rays;
    std::uniform_real_distribution<float> s01(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        const uvec3 t = m.tris[size_t(i) % m.tris.size()];
        float u = s01(rng), v = s01(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const glm::dvec3 target = (1.0 - u - v) * glm::dvec3(m.positions[t.x]) +
                                  double(u) * glm::dvec3(m.positions[t.y]) +
                                  double(v) * glm::dvec3(m.positions[t.z]);
        const vec3 eye = base + vec3(0.0f, 0.0f, -60.0f) + vec3(unit(rng), unit(rng), 0.0f) * 5.0f;
        rays.push_back({eye, vec3(glm::normalize(target - glm::dvec3(eye))), 0.0f, infinity});
    }
    const double gamma7 = 7.0 * 0x1.0p-24 / (1.0 - 7.0 * 0x1.0p-24);
    size_t off_plane = 0, hits = 0;
    double worst = 0.0;
    std::vector<Hit> scalar;
    std::vector<vec3> positions;
    for (const Ray& r : rays) {
        const Hit h = intersect_closest(scene, accel, r);
        scalar.push_back(h);
        positions.push_back(vec3(0.0f));
        if (!h.hit()) continue;
        ++hits;
        const vec3 p = surface_at(scene, r, h).position;
        positions.back() = p;
        const uvec3 t = m.tris[h.prim];
        const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
        const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        const double dist = std::fabs(glm::dot(glm::dvec3(p) - a, n));
        const double w = 1.0 - double(h.uv.x) - double(h.uv.y);
        const double bound =
            gamma7 * (std::fabs(w) * glm::length(a) + std::fabs(double(h.uv.x)) * glm::length(b) +
                      std::fabs(double(h.uv.y)) * glm::length(c));
        worst = std::max(worst, dist / bound);
        off_plane += dist > bound;
    }
    EXPECT_GT(hits, rays.size() * 9 / 10);
    EXPECT_EQ(off_plane, 0u) << "worst " << worst << " of the bound";
    std::printf("[ measured ] far triangles: worst distance from the plane %.3g of gamma_7 bound\n",
                worst);
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        const std::vector<Hit> packet = packet_closest<W>(scene, accel, rays);
        EXPECT_EQ(hit_disagreements(scalar, packet), 0u) << "W = " << W;
        size_t differ = 0;
        for (size_t first = 0; first < rays.size(); first += W) {
            vmask<W> active;
            const RayPacket<W> p = make_packet<W>(rays, first, active);
            HitPacket<W> h;
            uint32_t hit_bits = 0;
            for (int i = 0; i < W && first + size_t(i) < rays.size(); ++i) {
                const Hit& s = scalar[first + size_t(i)];
                if (!s.hit()) continue;
                hit_bits |= 1u << i;
                set(h.t, i, s.t);
                set(h.prim, i, int32_t(s.prim));
                set(h.object, i, int32_t(s.object));
                set(h.u, i, s.uv.x);
                set(h.v, i, s.uv.y);
            }
            if (hit_bits == 0) continue;
            const SurfacePacket<W> sp = surface_at<W>(scene, p, h, mask_from_bits<W>(hit_bits));
            for (int i = 0; i < W; ++i) {
                if (!((hit_bits >> i) & 1u)) continue;
                const vec3 q(get(sp.position.x, i), get(sp.position.y, i), get(sp.position.z, i));
                const vec3 want = positions[first + size_t(i)];
                for (int k = 0; k < 3; ++k) differ += ulp_distance(q[k], want[k]) > 4;
            }
        }
        EXPECT_EQ(differ, 0u) << "packet hit points vs scalar, W = " << W;
    });
}

/// numerics.md §17 and §20: 10^6 tiny triangles whose centroids are spaced exponentially (1e-12
/// to 1e22 along x). The object-median build still halves the count at every split, so the tree
/// is ceil(log2(n / 2)) + 1 deep at most and fits the traversal stack; the BVH answers as brute
/// force does on a subset of rays aimed at random triangles, in both paths.
TEST(FarFromOrigin, ExponentiallySpacedCentroidsDoNotOverflowTheTraversalStack) {
    const uint32_t n = sanitized ? 50000 : 1000000;
    MeshData m;
    m.name = "exponential";
    m.positions.reserve(3 * size_t(n));
    for (uint32_t i = 0; i < n; ++i) {
        // 1e-12 .. 1e22: beyond, the triangles' edge functions (~ size^2) under- or overflow float
        const double x = std::pow(10.0, -12.0 + 34.0 * double(i) / double(n));
        const float s = float(x * 1e-5);  // the gap to the next centroid is ~8e-5 x
        const vec3 p(float(x), 0.0f, 0.0f);
        m.positions.push_back(p);
        m.positions.push_back(p + vec3(s, 0.0f, 0.0f));
        m.positions.push_back(p + vec3(0.0f, s, 0.0f));
        m.tris.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    }
    const SceneData scene = make_mesh_scene({m});
    const Accel accel = build_accel(scene, BuildParams{4});
    const BvhStats st = compute_stats(accel.meshes[0].bvh);
    const int bound = int(std::ceil(std::log2(double(n) / 2.0))) + 1;
    EXPECT_LE(st.max_leaf_depth, bound);
    EXPECT_LT(st.max_leaf_depth, traversal_stack_size);
    std::printf("[ measured ] exponential centroids, n = %u: depth %d (bound %d, stack %d)\n", n,
                st.max_leaf_depth, bound, traversal_stack_size);
    // rays down -z onto random triangles (a point inside each), and two along the x axis in
    // their plane (edge-on: no hit), through every level of the tree
    std::mt19937 rng(5);
    std::uniform_int_distribution<uint32_t> pick(0, n - 1);
    std::vector<Ray> rays;
    for (int i = 0; i < (sanitized ? 20 : 100); ++i) {
        const uint32_t k = pick(rng);
        const vec3 a = m.positions[3 * k];
        const float s = m.positions[3 * k + 1].x - a.x;
        rays.push_back({a + vec3(0.25f * s, 0.25f * s, 1.0f), vec3(0.0f, 0.0f, -1.0f)});
    }
    rays.push_back({vec3(-1.0f, 1e-25f, 0.0f), vec3(1.0f, 0.0f, 0.0f)});  // edge-on to all
    rays.push_back({vec3(1e23f, 1e-3f, 0.0f), vec3(-1.0f, 0.0f, 0.0f)});
    std::vector<Hit> scalar(rays.size()), brute(rays.size());
    tbb::parallel_for(size_t(0), rays.size(), [&](size_t i) {
        scalar[i] = intersect_closest(scene, accel, rays[i]);
        brute[i] = brute_force_closest(scene, rays[i]);
    });
    size_t mismatches = 0, hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        hits += brute[i].hit();
        mismatches += scalar[i].prim != brute[i].prim || scalar[i].t != brute[i].t;
    }
    EXPECT_GE(hits, rays.size() - 2);
    EXPECT_EQ(mismatches, 0u);
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(scene, accel, rays)), 0u)
            << "W = " << W;
    });
}

}  // namespace
}  // namespace raylane
