// shade: light samples for W shading points, the packet path. Mirrors lights_scalar.h step by
// step (sample index and light are uniform across the lanes; positions and uniforms vary).
#pragma once

#include <cmath>
#include <limits>
#include <numbers>

#include "shade/lights_scalar.h"
#include "simd/math.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

template <int W>
struct LightSamplePacket {
    Vec3<W> dir;
    vfloat<W> distance = vfloat<W>(infinity);
    vfloat<W> factor = vfloat<W>(0.0f);
    vmask<W> valid;
};

/// stratified_square of lights_scalar.h for every lane (one stratum, W jitters).
template <int W>
inline void stratified_square(int i, int n, const vfloat<W>& u1, const vfloat<W>& u2, vfloat<W>& sx,
                              vfloat<W>& sy) {
    const Stratum s = stratum_of(i, n);
    sx = (vfloat<W>(s.x0) + u1 * vfloat<W>(s.cells)) / vfloat<W>(s.n);
    sy = (vfloat<W>(s.row) + u2) / vfloat<W>(s.cells);
}

/// concentric_disk of lights_scalar.h for every lane, bit-identical.
template <int W>
inline void concentric_disk(const vfloat<W>& sx, const vfloat<W>& sy, vfloat<W>& dx,
                            vfloat<W>& dy) {
    const vfloat<W> one(1.0f), two(2.0f), zero(0.0f);
    const vfloat<W> a = two * sx - one, b = two * sy - one;
    constexpr float quarter_pi = 0.25f * std::numbers::pi_v<float>;
    const vmask<W> wide = abs(a) > abs(b);
    // the divisions of the branch not taken may be 0/0: their lanes are discarded by select
    const vfloat<W> r = select(wide, a, b);
    const vfloat<W> phi = select(wide, vfloat<W>(quarter_pi) * (b / a),
                                 vfloat<W>(2.0f * quarter_pi) - vfloat<W>(quarter_pi) * (a / b));
    const vmask<W> centre = mask_and(a == zero, b == zero);
    // std::cos and std::sin lane by lane: the scalar's bits, so lens rays and disc samples agree
    const vfloat<W> c = map_lanes(phi, [](float x) { return std::cos(x); });
    const vfloat<W> s = map_lanes(phi, [](float x) { return std::sin(x); });
    dx = select(centre, zero, r * c);
    dy = select(centre, zero, r * s);
}

template <int W>
inline Vec3<W> area_light_point(const Light& light, const vfloat<W>& sx, const vfloat<W>& sy,
                                const vfloat<W>& u3) {
    switch (light.kind) {
        case LightKind::rect:
            return (broadcast_vec3<W>(light.position) + sx * broadcast_vec3<W>(light.edge_u)) +
                   sy * broadcast_vec3<W>(light.edge_v);
        case LightKind::disk: {
            const vec3 n = light.direction;
            const vec3 a = std::fabs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f);
            const vec3 t = glm::normalize(glm::cross(n, a));
            const vec3 b = glm::cross(n, t);
            vfloat<W> dx, dy;
            concentric_disk<W>(sx, sy, dx, dy);
            const vfloat<W> r(light.radius);
            return broadcast_vec3<W>(light.position) +
                   r * (dx * broadcast_vec3<W>(t) + dy * broadcast_vec3<W>(b));
        }
        case LightKind::box:
            return broadcast_vec3<W>(light.position) +
                   Vec3<W>{sx, sy, u3} * broadcast_vec3<W>(light.edge_u);
        default:
            return broadcast_vec3<W>(light.position);
    }
}

template <int W>
inline LightSamplePacket<W> sample_light(const Light& light, const Vec3<W>& origin, int i, int n,
                                         const vfloat<W>& u1, const vfloat<W>& u2,
                                         const vfloat<W>& u3) {
    LightSamplePacket<W> ls;
    if (light.kind == LightKind::directional) {
        ls.dir = make_vec3<W>(light.direction.x, light.direction.y, light.direction.z);
        ls.factor = vfloat<W>(light.intensity);
        ls.valid = vfloat<W>(0.0f) == vfloat<W>(0.0f);
        return ls;
    }
    Vec3<W> p;
    if (light.kind == LightKind::point) {
        p = make_vec3<W>(light.position.x, light.position.y, light.position.z);
    } else {
        vfloat<W> sx, sy;
        stratified_square<W>(i, n, u1, u2, sx, sy);
        p = area_light_point<W>(light, sx, sy, u3);
    }
    const Vec3<W> to = p - origin;
    const vfloat<W> d2 = dot(to, to);
    const vfloat<W> factor = vfloat<W>(light.intensity) / d2;
    // on the light (d = 0), or so close that intensity / d^2 overflows: no usable sample
    ls.valid =
        mask_and(d2 > vfloat<W>(0.0f), factor < vfloat<W>(std::numeric_limits<float>::infinity()));
    const vfloat<W> d = sqrt(d2);
    ls.dir = to / d;
    ls.distance = d;
    ls.factor = factor;
    return ls;
}

}  // namespace raylane::RAYLANE_ISA_NS
