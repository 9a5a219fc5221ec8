// traverse: watertight ray/triangle intersection, the reference path (one ray).
// Mirrored by triangle_packet.h.
// Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013.
#pragma once

#include <cmath>
#include <utility>

#include "core/ray.h"
#include "traverse/local_geometry.h"

namespace raylane {

/// A ray prepared for the watertight test: after translating by org, permuting the axes to
/// (kx, ky, kz) and shearing with (sx, sy, sz), the ray is the +z axis.
struct WatertightRay {
    vec3 org{0.0f};
    int kx = 0, ky = 1, kz = 2;
    float sx = 0.0f, sy = 0.0f, sz = 1.0f;
};

/// kz is the axis of the largest |dir| component (ties to the lower axis), kx and ky follow it
/// cyclically and are swapped when dir[kz] < 0 so the winding is kept. sx = d[kx] / d[kz],
/// sy = d[ky] / d[kz], sz = 1 / d[kz], by division.
inline WatertightRay make_watertight_ray(const Ray& ray) {
    WatertightRay wr;
    wr.org = ray.org;
    const vec3 ad = glm::abs(ray.dir);
    wr.kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
    wr.kx = (wr.kz + 1) % 3;
    wr.ky = (wr.kx + 1) % 3;
    if (ray.dir[wr.kz] < 0.0f) std::swap(wr.kx, wr.ky);
    wr.sx = ray.dir[wr.kx] / ray.dir[wr.kz];
    wr.sy = ray.dir[wr.ky] / ray.dir[wr.kz];
    wr.sz = 1.0f / ray.dir[wr.kz];
    return wr;
}

/// True when the three vertices span no area: their cross product is exactly zero, computed in
/// double from double differences (exact for any mesh whose edge vectors fit in 26 bits).
inline bool is_zero_area_triangle(vec3 a, vec3 b, vec3 c) {
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

/// True when the ray hits triangle (a, b, c) from either side at t in the open interval
/// (t_min, t_max); then t, and u, v = the barycentric weights of b and c, are written (outputs
/// are left alone on a miss). A ray through a shared edge or vertex hits at least one of the
/// triangles sharing it (an edge function of zero counts as inside). Zero-area triangles and
/// NaN inputs never hit. Requires -ffp-contract=off: see numerics.md §1.
inline bool intersect_triangle(const WatertightRay& wr, vec3 a, vec3 b, vec3 c, float t_min,
                               float t_max, float& t, float& u, float& v) {
    // translate: vertices relative to the ray origin
    const vec3 A = a - wr.org;
    const vec3 B = b - wr.org;
    const vec3 C = c - wr.org;

    // shear: the ray becomes the +z axis (z is scaled later, for candidates only)
    const float ax = A[wr.kx] - wr.sx * A[wr.kz];
    const float ay = A[wr.ky] - wr.sy * A[wr.kz];
    const float bx = B[wr.kx] - wr.sx * B[wr.kz];
    const float by = B[wr.ky] - wr.sy * B[wr.kz];
    const float cx = C[wr.kx] - wr.sx * C[wr.kz];
    const float cy = C[wr.ky] - wr.sy * C[wr.kz];

    // edge functions: e_a, e_b, e_c are det times the weights of a, b, c; the function of an
    // edge shared by two triangles is the same expression of the same two sheared vertices
    float e_a = cx * by - cy * bx;
    float e_b = ax * cy - ay * cx;
    float e_c = bx * ay - by * ax;

    // fallback: an exactly zero edge function is recomputed in double, where the products of
    // two floats are exact, so its sign is right
    if (e_a == 0.0f || e_b == 0.0f || e_c == 0.0f) {
        e_a = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
        e_b = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
        e_c = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
    }

    // inside: no edge function negative, or none positive (positive form: NaN is outside)
    const bool inside =
        (e_a >= 0.0f && e_b >= 0.0f && e_c >= 0.0f) || (e_a <= 0.0f && e_b <= 0.0f && e_c <= 0.0f);
    if (!inside) return false;
    const float det = e_a + e_b + e_c;
    if (det == 0.0f) return false;

    // degenerate: zero-area triangles (the shear may round collinear vertices apart)
    if (is_zero_area_triangle(a, b, c)) return false;

    // distance: T = t * det, tested against the interval scaled by |det| (no division yet)
    const float az = wr.sz * A[wr.kz];
    const float bz = wr.sz * B[wr.kz];
    const float cz = wr.sz * C[wr.kz];
    const float t_scaled = e_a * az + e_b * bz + e_c * cz;
    const float det_sign = std::copysign(1.0f, det);
    const float abs_det = det_sign * det;
    const float t_signed = det_sign * t_scaled;
    if (!(t_signed > t_min * abs_det && t_signed < t_max * abs_det)) return false;

    // divide: only now, and re-check so rounding cannot leave the open interval
    const float t_hit = t_scaled / det;
    if (!(t_hit > t_min && t_hit < t_max)) return false;
    t = t_hit;
    u = e_b / det;
    v = e_c / det;
    return true;
}

/// Normal and uv at a hit: normal = normalize(cross(b - a, c - a)), the side the winding
/// (a, b, c) gives, and uv = (u, v) the barycentric weights of b and c.
inline LocalGeometry geometry_triangle(vec3 a, vec3 b, vec3 c, float u, float v) {
    LocalGeometry g;
    g.normal = glm::normalize(glm::cross(b - a, c - a));
    g.uv = vec2(u, v);
    return g;
}

}  // namespace raylane
