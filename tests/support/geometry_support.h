// Test support for the geometry half of the numerical stability suite (numerics.md §1-8, 16,
// 17): synthetic closed meshes, brute-force oracles, ulp distances, and running ray sets
// through the packet path at every width this machine runs.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "accel/bvh.h"
#include "core/ray_packet.h"
#include "scene/scene.h"
#include "simd/simd.h"
#include "support/ray_packets.h"
#include "support/widths.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_scalar.h"
#include "traverse/triangle_scalar.h"

namespace raylane::geometry_test {

#ifdef RAYLANE_SANITIZED
inline constexpr bool sanitized = true;
#else
inline constexpr bool sanitized = false;
#endif

/// n in Release, n / shrink (at least 1) under the sanitizers.
inline size_t ray_count(size_t n, size_t shrink = 50) {
    return sanitized ? std::max<size_t>(1, n / shrink) : n;
}

// ---- widths ------------------------------------------------------------------------------------

template <class... Ws>
struct WidthList {
    /// Calls f(Width<W>{}) for every width in the list, in order.
    template <class F>
    static void run(F&& f) {
        (f(Ws{}), ...);
    }
};

/// f(Width<W>{}) for every packet width the program tests (support/widths.h).
template <class F>
void for_each_width(F&& f) {
    tested_widths<WidthList>::run(std::forward<F>(f));
}

// ---- floats ------------------------------------------------------------------------------------

/// Distance in ulps between two finite floats of any signs (0 when equal, +0 and -0 included).
inline int64_t ulp_distance(float a, float b) {
    auto key = [](float f) {
        const int32_t i = std::bit_cast<int32_t>(f);
        return i < 0 ? int64_t(INT32_MIN) - int64_t(i) : int64_t(i);
    };
    const int64_t d = key(a) - key(b);
    return d < 0 ? -d : d;
}

/// One ulp of float at magnitude |x| (the spacing of floats just above |x|), in double.
inline double float_ulp(double x) {
    const float f = static_cast<float>(std::fabs(x));
    return double(std::nextafter(f, infinity)) - double(f);
}

inline bool is_nan_bits(float f) { return f != f; }

// ---- meshes ------------------------------------------------------------------------------------

/// A closed icosphere: the icosahedron subdivided `level` times, vertices pushed to the sphere
/// in double and rounded once, shared by index (so shared edges have identical endpoints).
/// Outward winding. level 3: 642 vertices, 1,280 triangles.
inline MeshData make_icosphere(int level, vec3 center, float radius) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                 {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                 {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (glm::dvec3& p : v) p = glm::normalize(p);
    std::vector<uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            return mid[key] = static_cast<uint32_t>(v.size() - 1);
        };
        std::vector<uvec3> next;
        for (uvec3 t : f) {
            const uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z),
                           ca = midpoint(t.z, t.x);
            next.push_back({t.x, ab, ca});
            next.push_back({t.y, bc, ab});
            next.push_back({t.z, ca, bc});
            next.push_back({ab, bc, ca});
        }
        f = std::move(next);
    }
    MeshData m;
    m.name = "icosphere";
    for (const glm::dvec3& p : v)
        m.positions.push_back(vec3(glm::dvec3(center) + double(radius) * p));
    m.tris = std::move(f);
    return m;
}

/// The 12-triangle cube [lo, hi], outward winding, 8 shared vertices.
inline MeshData make_cube_mesh(vec3 lo, vec3 hi) {
    MeshData m;
    m.name = "cube";
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
    m.tris = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
              {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    return m;
}

/// A square floor of two triangles at height y, [-half, half]^2 in x and z, normal +y.
inline MeshData make_floor_mesh(float y, float half) {
    MeshData m;
    m.name = "floor";
    m.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
    m.tris = {{0, 2, 1}, {0, 3, 2}};
    return m;
}

/// A scene holding the meshes as objects 0, 1, ... (one diffuse material).
inline SceneData make_mesh_scene(std::vector<MeshData> meshes) {
    SceneData s;
    s.materials.push_back(Material{});
    for (MeshData& m : meshes) {
        Object o;
        o.kind = ShapeKind::mesh;
        o.shape = static_cast<uint32_t>(s.meshes.size());
        s.objects.push_back(o);
        s.meshes.push_back(std::move(m));
    }
    return s;
}

// ---- oracles -----------------------------------------------------------------------------------

/// The closest hit of the ray over every triangle of every mesh object, no BVH: the float
/// watertight test, ties to the smaller t, then object, then primitive (intersect_closest's rule).
inline Hit brute_force_closest(const SceneData& scene, const Ray& ray) {
    Hit best;
    const WatertightRay wr = make_watertight_ray(ray);
    for (uint32_t o = 0; o < scene.objects.size(); ++o) {
        if (scene.objects[o].kind != ShapeKind::mesh) continue;
        const MeshData& m = scene.meshes[scene.objects[o].shape];
        for (uint32_t k = 0; k < m.tris.size(); ++k) {
            const uvec3 t3 = m.tris[k];
            float t, u, v;
            if (!intersect_triangle(wr, m.positions[t3.x], m.positions[t3.y], m.positions[t3.z],
                                    ray.t_min, ray.t_max, t, u, v))
                continue;
            const bool better =
                !best.hit() || t < best.t ||
                (t == best.t && (o < best.object || (o == best.object && k < best.prim)));
            if (better) best = {t, k, o, vec2(u, v)};
        }
    }
    return best;
}

// ---- the packet path ---------------------------------------------------------------------------

/// intersect_closest of the packet path, W rays at a time, returned ray by ray.
template <int W>
std::vector<Hit> packet_closest(const SceneData& scene, const Accel& accel,
                                const std::vector<Ray>& rays) {
    std::vector<Hit> out(rays.size());
    for (size_t first = 0; first < rays.size(); first += W) {
        vmask<W> active;
        const RayPacket<W> p = make_packet<W>(rays, first, active);
        const HitPacket<W> h = intersect_closest<W>(scene, accel, p, active);
        for (int i = 0; i < W && first + size_t(i) < rays.size(); ++i)
            out[first + size_t(i)] = get_hit(h, i);
    }
    return out;
}

/// intersect_any of the packet path, W rays at a time.
template <int W>
std::vector<uint8_t> packet_any(const SceneData& scene, const Accel& accel,
                                const std::vector<Ray>& rays) {
    std::vector<uint8_t> out(rays.size());
    for (size_t first = 0; first < rays.size(); first += W) {
        vmask<W> active;
        const RayPacket<W> p = make_packet<W>(rays, first, active);
        const uint32_t b = bits(intersect_any<W>(scene, accel, p, active));
        for (int i = 0; i < W && first + size_t(i) < rays.size(); ++i)
            out[first + size_t(i)] = static_cast<uint8_t>((b >> i) & 1u);
    }
    return out;
}

/// A packet shape test (intersect_sphere<W> and its siblings) over the ray list: t per ray.
template <int W, class Shape, class F>
std::vector<float> packet_shape(const Shape& shape, const std::vector<Ray>& rays, F&& test) {
    std::vector<float> out(rays.size());
    for (size_t first = 0; first < rays.size(); first += W) {
        vmask<W> active;
        const RayPacket<W> p = make_packet<W>(rays, first, active);
        const vfloat<W> t = test(shape, p, active);
        for (int i = 0; i < W && first + size_t(i) < rays.size(); ++i)
            out[first + size_t(i)] = get(t, i);
    }
    return out;
}

/// Row P for shape tests: the same decision (hit or miss) ray by ray, t within `max_ulps`, never
/// NaN. Returns the number of rays that break it.
inline size_t shape_disagreements(const std::vector<float>& scalar,
                                  const std::vector<float>& packet, int64_t max_ulps = 4) {
    size_t bad = 0;
    for (size_t i = 0; i < scalar.size(); ++i) {
        const bool hs = scalar[i] < infinity, hp = packet[i] < infinity;
        if (is_nan_bits(packet[i]) || hs != hp ||
            (hs && ulp_distance(scalar[i], packet[i]) > max_ulps))
            ++bad;
    }
    return bad;
}

/// Row P for scene queries: the same object and primitive ray by ray, t within `max_ulps`.
inline size_t hit_disagreements(const std::vector<Hit>& scalar, const std::vector<Hit>& packet,
                                int64_t max_ulps = 4) {
    size_t bad = 0;
    for (size_t i = 0; i < scalar.size(); ++i) {
        const Hit& a = scalar[i];
        const Hit& b = packet[i];
        if (a.object != b.object || a.prim != b.prim ||
            (a.hit() && ulp_distance(a.t, b.t) > max_ulps))
            ++bad;
    }
    return bad;
}

}  // namespace raylane::geometry_test
