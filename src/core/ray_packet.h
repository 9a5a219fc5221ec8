// core: W rays and their closest hits in SoA form (the packet path); mirrors core/ray.h.
#pragma once

#include "core/ray.h"
#include "simd/lanes.h"
#include "simd/vec3.h"

namespace raylane::RAYLANE_ISA_NS {

/// W rays o + t d accepted for t in the open interval (t_min, t_max). Inactive lanes must hold
/// a benign ray (finite origin and direction, t_max <= t_min) so they never produce a hit.
template <int W>
struct RayPacket {
    Vec3<W> org;
    Vec3<W> dir = make_vec3<W>(0.0f, 0.0f, 1.0f);
    vfloat<W> t_min = vfloat<W>(0.0f);
    vfloat<W> t_max = vfloat<W>(infinity);
};

/// The closest hits of W rays; prim == invalid_id (as int32: -1) means no hit.
template <int W>
struct HitPacket {
    vfloat<W> t = vfloat<W>(infinity);
    vint<W> prim = vint<W>(-1);
    vint<W> object = vint<W>(-1);
    vfloat<W> u = vfloat<W>(0.0f), v = vfloat<W>(0.0f);
};

/// Lane i of W vectors as one vector.
template <int W>
vec3 get_vec3(const Vec3<W>& v, int i) {
    return vec3(get(v.x, i), get(v.y, i), get(v.z, i));
}

/// Lane i of a packet as a single ray / hit (tests and scalar fallbacks).
template <int W>
Ray get_ray(const RayPacket<W>& p, int i) {
    Ray r;
    r.org = get_vec3(p.org, i);
    r.dir = get_vec3(p.dir, i);
    r.t_min = get(p.t_min, i);
    r.t_max = get(p.t_max, i);
    return r;
}

template <int W>
void set_ray(RayPacket<W>& p, int i, const Ray& r) {
    set(p.org.x, i, r.org.x);
    set(p.org.y, i, r.org.y);
    set(p.org.z, i, r.org.z);
    set(p.dir.x, i, r.dir.x);
    set(p.dir.y, i, r.dir.y);
    set(p.dir.z, i, r.dir.z);
    set(p.t_min, i, r.t_min);
    set(p.t_max, i, r.t_max);
}

template <int W>
Hit get_hit(const HitPacket<W>& h, int i) {
    Hit hit;
    hit.t = get(h.t, i);
    hit.prim = static_cast<uint32_t>(get(h.prim, i));
    hit.object = static_cast<uint32_t>(get(h.object, i));
    hit.uv = vec2(get(h.u, i), get(h.v, i));
    return hit;
}

}  // namespace raylane::RAYLANE_ISA_NS
