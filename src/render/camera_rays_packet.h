// render: primary rays of the pinhole camera, W at a time. Mirrors camera_rays.h.
#pragma once

#include "core/ray_packet.h"
#include "render/camera_rays.h"
#include "shade/lights_packet.h"

namespace raylane::RAYLANE_ISA_NS {

/// The unit-direction rays through image positions (x, y), lane-wise camera_ray.
template <int W>
inline RayPacket<W> camera_ray(const CameraFrame& f, const vfloat<W>& x, const vfloat<W>& y) {
    const vfloat<W> sx = ((vfloat<W>(2.0f) * x) * vfloat<W>(f.inv_width) - vfloat<W>(1.0f)) *
                         vfloat<W>(f.half_width);
    const vfloat<W> sy = (vfloat<W>(1.0f) - (vfloat<W>(2.0f) * y) * vfloat<W>(f.inv_height)) *
                         vfloat<W>(f.half_height);
    const Vec3<W> u = make_vec3<W>(f.u.x, f.u.y, f.u.z), v = make_vec3<W>(f.v.x, f.v.y, f.v.z);
    const Vec3<W> d = (make_vec3<W>(f.w.x, f.w.y, f.w.z) + sx * u) + sy * v;
    RayPacket<W> rays;
    rays.org = make_vec3<W>(f.origin.x, f.origin.y, f.origin.z);
    rays.dir = d / sqrt(dot(d, d));
    return rays;
}

/// Thin-lens rays: the packet twin of camera_ray(f, x, y, lens_u, lens_v).
template <int W>
inline RayPacket<W> camera_ray(const CameraFrame& f, const vfloat<W>& x, const vfloat<W>& y,
                               const vfloat<W>& lens_u, const vfloat<W>& lens_v) {
    RayPacket<W> rays = camera_ray<W>(f, x, y);
    if (f.lens_radius == 0.0f) return rays;
    const vfloat<W> sx = ((vfloat<W>(2.0f) * x) * vfloat<W>(f.inv_width) - vfloat<W>(1.0f)) *
                         vfloat<W>(f.half_width);
    const vfloat<W> sy = (vfloat<W>(1.0f) - (vfloat<W>(2.0f) * y) * vfloat<W>(f.inv_height)) *
                         vfloat<W>(f.half_height);
    const Vec3<W> u = make_vec3<W>(f.u.x, f.u.y, f.u.z), v = make_vec3<W>(f.v.x, f.v.y, f.v.z);
    const Vec3<W> origin = make_vec3<W>(f.origin.x, f.origin.y, f.origin.z);
    const Vec3<W> focus = origin + vfloat<W>(f.focal_distance) *
                                       ((make_vec3<W>(f.w.x, f.w.y, f.w.z) + sx * u) + sy * v);
    vfloat<W> dx, dy;
    concentric_disk<W>(lens_u, lens_v, dx, dy);
    const vfloat<W> r(f.lens_radius);
    rays.org = (origin + (r * dx) * u) + (r * dy) * v;
    const Vec3<W> d = focus - rays.org;
    rays.dir = d / sqrt(dot(d, d));
    return rays;
}

}  // namespace raylane::RAYLANE_ISA_NS
