// numerics.md §3 : the acne / leak sweep. One scene (a sphere resting on a
// box, a glass sphere beside it, a point light) at scales 1e-4, 1 and 1e5, and at scale 1
// translated by (1e5, 1e5, 1e5), camera moved along. Secondary rays start at
// offset_ray_origin (core/offset.h, offset_packet.h) as shading spawns them, with no tmin.
#include <gtest/gtest.h>

#include <random>

#include "core/offset.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "shade/optics_scalar.h"
#include "support/geometry_support.h"
#include "traverse/box_scalar.h"
#include "traverse/sphere_scalar.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

struct Setup {
    const char* name;
    double scale;
    double shift;  ///< added to every coordinate
};

const Setup setups[] = {{"scale 1e-4", 1e-4, 0.0},
                        {"scale 1", 1.0, 0.0},
                        {"scale 1e5", 1e5, 0.0},
                        {"scale 1 at (1e5, 1e5, 1e5)", 1.0, 1e5}};

/// Object ids of the scene.
enum : uint32_t { box_id = 0, ball_id = 1, glass_id = 2 };

struct SweepScene {
    SceneData scene;
    Accel accel;
    glm::dvec3 light;  ///< the light's position as placed (float), in double
};

/// Box [-3, 3] x [-1, 0] x [-3, 3], a ball of radius 1 resting on it at the origin, a glass ball
/// of radius 0.7 resting on it at (2.2, 0, -1.2), a light up and behind, the camera in front:
/// all times `scale`, plus `shift`, written as a scene file (coordinates to 17 digits) and read
/// by load_scene, so that whatever the loader does about far coordinates applies.
SweepScene make_sweep_scene(const Setup& s, int width, int height) {
    auto at = [&](double x, double y, double z) {
        const glm::dvec3 p = glm::dvec3(x, y, z) * s.scale + glm::dvec3(s.shift);
        char buf[128];
        std::snprintf(buf, sizeof buf, "[%.17g, %.17g, %.17g]", p.x, p.y, p.z);
        return std::string(buf);
    };
    auto num = [](double v) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.17g", v);
        return std::string(buf);
    };
    const std::string json = R"({"version": 1,
  "camera": {"position": )" + at(0, 2.5, -7) +
                             R"(, "look_at": )" + at(0, 0.3, 0) +
                             R"(, "fov_deg": 40, "resolution": [)" + std::to_string(width) + ", " +
                             std::to_string(height) + R"(]},
  "materials": {"diffuse": {}, "glass": {"refraction": {"ior": 1.5}}},
  "objects": [
    {"shape": "box", "min": )" +
                             at(-3, -1, -3) + R"(, "max": )" + at(3, 0, 3) +
                             R"(, "material": "diffuse"},
    {"shape": "sphere", "center": )" +
                             at(0, 1, 0) + R"(, "radius": )" + num(s.scale) +
                             R"(, "material": "diffuse"},
    {"shape": "sphere", "center": )" +
                             at(2.2, 0.7, -1.2) + R"(, "radius": )" + num(0.7 * s.scale) +
                             R"(, "material": "glass"}
  ],
  "lights": [{"type": "point", "position": )" +
                             at(-1.5, 6, 3) + R"(, "intensity": 1}]})";
    SweepScene out;
    out.scene = load_scene_from_string(json, "sweep.json");
    out.light = glm::dvec3(out.scene.lights.at(0).position);
    out.accel = build_accel(out.scene, BuildParams{});
    return out;
}

/// Exact-arithmetic visibility of the light from a surface point (double, from the double
/// oracle's hit point): +1 lit, -1 in shadow, 0 too close to a shadow boundary to call.
int exact_visibility(const SceneData& sc, glm::dvec3 p, glm::dvec3 n, glm::dvec3 light) {
    const glm::dvec3 to = light - p;
    const double len = glm::length(to);
    const double facing = glm::dot(n, to) / len;
    if (facing < -1e-3) return -1;
    if (facing < 1e-3) return 0;
    int vis = 1;
    for (const Sphere& s : sc.spheres) {
        const glm::dvec3 c(s.center);
        const double r = s.radius;
        const double along = std::clamp(glm::dot(c - p, to) / (len * len), 0.0, 1.0);
        const double dist = glm::length(p + along * to - c);
        if (glm::length(p - c) < r * (1.0 + 1e-3)) continue;  // p is on this sphere
        if (dist < r * (1.0 - 1e-3)) return -1;
        if (dist < r * (1.0 + 1e-3)) vis = 0;
    }
    return vis;
}

/// What one scale's sweep measures.
struct Sweep {
    size_t lit = 0, acne = 0, shadowed = 0, leaks = 0, glass_entries = 0, glass_no_exit = 0;
    std::vector<uint32_t> object;  ///< per pixel: object hit (invalid_id: none)
    std::vector<int8_t> lit_px;    ///< per pixel: 1 lit, 0 shadowed, -1 no shadow ray
    std::vector<Ray> shadow_rays, glass_rays;
    std::vector<uint8_t> shadow_blocked;
    std::vector<Hit> glass_hits;
};

Sweep run_sweep(const SweepScene& ss) {
    const SceneData& sc = ss.scene;
    EXPECT_TRUE(sc.objects.size() == 3 && sc.objects[box_id].kind == ShapeKind::box &&
                sc.materials[sc.objects[glass_id].material].refractive);
    const CameraFrame frame = make_camera_frame(sc.camera);
    Sweep sw;
    const int w = sc.camera.width, h = sc.camera.height;
    sw.object.assign(size_t(w) * size_t(h), invalid_id);
    sw.lit_px.assign(size_t(w) * size_t(h), -1);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t px = size_t(y) * size_t(w) + size_t(x);
            const Ray ray = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const Hit hit = intersect_closest(sc, ss.accel, ray);
            if (!hit.hit()) continue;
            sw.object[px] = hit.object;
            const SurfacePoint sp = surface_at(sc, ray, hit);
            const bool front = !(glm::dot(sp.geometric_normal, ray.dir) > 0.0f);
            const vec3 ng = front ? sp.geometric_normal : -sp.geometric_normal;
            if (hit.object == glass_id) {
                // refraction into the glass: the child ray must find the exit
                vec3 t_dir;
                float cos_t;
                if (!refract_direction(ray.dir, ng, 1.5f, t_dir, cos_t)) continue;
                const Ray in{offset_ray_origin(sp.position, -ng, ray_reach(ray, hit.t)), t_dir,
                             0.0f, infinity};
                const Hit exit = intersect_closest(sc, ss.accel, in);
                ++sw.glass_entries;
                sw.glass_no_exit += !(exit.hit() && exit.object == glass_id && exit.t > 0.0f);
                sw.glass_rays.push_back(in);
                sw.glass_hits.push_back(exit);
                continue;
            }
            // the exact hit point: the double oracle on the same float ray, exact normal
            const RayOf<double> rd = ray_of<double>(ray);
            glm::dvec3 p, n;
            if (hit.object == ball_id) {
                const Sphere& s = sc.spheres[0];
                const double t = intersect_sphere(s, rd);
                if (!(t < infinity_of<double>)) continue;
                p = rd.org + t * rd.dir;
                n = glm::normalize(p - glm::dvec3(s.center));
            } else {
                const double t = intersect_box(sc.boxes[0], rd);
                if (!(t < infinity_of<double>)) continue;
                p = rd.org + t * rd.dir;
                n = glm::dvec3(geometry_box(sc.boxes[0], p).normal);
            }
            if (glm::dot(n, rd.dir) > 0.0) n = -n;
            const int vis = exact_visibility(sc, p, n, ss.light);
            const vec3 org = offset_ray_origin(sp.position, ng, ray_reach(ray, hit.t));
            const Ray shadow{org, vec3(ss.light - glm::dvec3(org)), 0.0f, 1.0f};
            const bool blocked = intersect_any(sc, ss.accel, shadow);
            sw.shadow_rays.push_back(shadow);
            sw.shadow_blocked.push_back(blocked);
            sw.lit_px[px] = blocked ? 0 : 1;
            if (vis > 0) {
                ++sw.lit;
                sw.acne += blocked;
            } else if (vis < 0 && glm::dot(n, ss.light - p) > 0.0) {
                // facing the light but behind an occluder: the contact and cast shadows
                ++sw.shadowed;
                sw.leaks += !blocked;
            }
        }
    }
    return sw;
}

int sweep_width() { return sanitized ? 96 : 480; }

const Sweep& sweep_of(size_t k) {
    static std::map<size_t, Sweep> cache;
    if (auto it = cache.find(k); it != cache.end()) return it->second;
    const int w = sweep_width(), h = w * 3 / 4;
    return cache[k] = run_sweep(make_sweep_scene(setups[k], w, h));
}

TEST(SelfIntersection, LitPointsDoNotShadowThemselvesAtAnyScale) {
    for (size_t k = 0; k < std::size(setups); ++k) {
        SCOPED_TRACE(setups[k].name);
        const Sweep& sw = sweep_of(k);
        ASSERT_GT(sw.lit, sw.object.size() / 8);
        const double acne = double(sw.acne) / double(sw.lit);
        std::printf("[ measured ] %s: acne %.3g (%zu of %zu lit points)\n", setups[k].name, acne,
                    sw.acne, sw.lit);
        EXPECT_LE(acne, 1e-5) << sw.acne << " of " << sw.lit << " lit points reported occluded";
    }
}

TEST(SelfIntersection, ContactShadowsDoNotLeakAtAnyScale) {
    for (size_t k = 0; k < std::size(setups); ++k) {
        SCOPED_TRACE(setups[k].name);
        const Sweep& sw = sweep_of(k);
        ASSERT_GT(sw.shadowed, sw.object.size() / 40);
        std::printf("[ measured ] %s: leaks %zu of %zu shadowed points\n", setups[k].name, sw.leaks,
                    sw.shadowed);
        EXPECT_EQ(sw.leaks, 0u) << "of " << sw.shadowed << " points in shadow reported lit";
    }
}

TEST(SelfIntersection, RefractedRaysFindTheirExitAtAnyScale) {
    for (size_t k = 0; k < std::size(setups); ++k) {
        SCOPED_TRACE(setups[k].name);
        const Sweep& sw = sweep_of(k);
        ASSERT_GT(sw.glass_entries, sw.object.size() / 40);
        EXPECT_EQ(sw.glass_no_exit, 0u) << "of " << sw.glass_entries << " refracted rays";
    }
}

/// The images agree after undoing the scale: a pixel may differ from the scale-1 image (object
/// hit, or lit / shadowed) only where the scale-1 image itself changes within one pixel
/// (silhouettes and shadow boundaries).
TEST(SelfIntersection, ImagesAgreeAcrossScalesAwayFromEdges) {
    const Sweep& ref = sweep_of(1);
    const int w = sweep_width(), h = w * 3 / 4;
    auto boundary = [&](int x, int y) {
        const size_t px = size_t(y) * size_t(w) + size_t(x);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int xx = x + dx, yy = y + dy;
                if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                const size_t q = size_t(yy) * size_t(w) + size_t(xx);
                if (ref.object[q] != ref.object[px] || ref.lit_px[q] != ref.lit_px[px]) return true;
            }
        }
        return false;
    };
    for (size_t k : {size_t(0), size_t(2), size_t(3)}) {
        SCOPED_TRACE(setups[k].name);
        const Sweep& sw = sweep_of(k);
        size_t differ = 0, interior = 0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const size_t px = size_t(y) * size_t(w) + size_t(x);
                if (sw.object[px] == ref.object[px] && sw.lit_px[px] == ref.lit_px[px]) continue;
                ++differ;
                interior += !boundary(x, y);
            }
        }
        std::printf("[ measured ] %s: %zu pixels differ from scale 1, %zu away from edges\n",
                    setups[k].name, differ, interior);
        EXPECT_EQ(interior, 0u) << "pixels differing from the scale-1 image away from edges";
    }
}

/// Row P: the packet path gives the same shadow and refraction answers at every width.
TEST(SelfIntersection, PacketPathDecidesAsTheScalarPath) {
    for (size_t k = 0; k < std::size(setups); ++k) {
        SCOPED_TRACE(setups[k].name);
        const Sweep& sw = sweep_of(k);
        const SweepScene ss = make_sweep_scene(setups[k], 4, 3);
        for_each_width([&](auto wd) {
            constexpr int W = decltype(wd)::value;
            SCOPED_TRACE("W = " + std::to_string(W));
            EXPECT_TRUE(packet_any<W>(ss.scene, ss.accel, sw.shadow_rays) == sw.shadow_blocked);
            EXPECT_EQ(hit_disagreements(sw.glass_hits,
                                        packet_closest<W>(ss.scene, ss.accel, sw.glass_rays)),
                      0u);
        });
    }
}

}  // namespace
}  // namespace raylane
