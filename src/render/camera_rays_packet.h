// render: primary rays of the pinhole camera, W at a time. Mirrors camera_rays.h.
#pragma once

#include "core/ray_packet.h"
#include "render/camera_rays.h"

namespace raylane {

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

}  // namespace raylane
