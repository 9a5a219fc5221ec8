// render: primary rays of the pinhole camera, one at a time. Mirrored by camera_rays_packet.h.
#pragma once

#include "core/ray.h"
#include "scene/scene.h"
#include "shade/lights_scalar.h"

namespace raylane {

/// The camera's orthonormal frame and image-plane half extents at distance 1.
/// Image right is +u, image up is +v, forward is +w; pixel (0, 0) is the top-left corner.
struct CameraFrame {
    vec3 origin{0.0f};
    vec3 u{1.0f, 0.0f, 0.0f}, v{0.0f, 1.0f, 0.0f}, w{0.0f, 0.0f, 1.0f};
    float half_width = 1.0f, half_height = 1.0f;
    float inv_width = 1.0f, inv_height = 1.0f;  ///< 1 / resolution
    float lens_radius = 0.0f;                   ///< 0: pinhole
    float focal_distance = 1.0f;                ///< distance of the plane of focus along w
};

CameraFrame make_camera_frame(const Camera& camera);

/// The unit-direction ray through image position (x, y) in pixels from the top-left corner
/// (the centre of pixel (i, j) is (i + 0.5, j + 0.5)).
inline Ray camera_ray(const CameraFrame& f, float x, float y) {
    const float sx = (2.0f * x * f.inv_width - 1.0f) * f.half_width;
    const float sy = (1.0f - 2.0f * y * f.inv_height) * f.half_height;
    const vec3 d = f.w + sx * f.u + sy * f.v;
    Ray ray;
    ray.org = f.origin;
    ray.dir = d / std::sqrt(glm::dot(d, d));
    return ray;
}

/// The thin-lens ray through image position (x, y) for the lens position (lens_u, lens_v) in
/// the unit square (concentric map to the lens disc): from the lens point to where the pinhole
/// ray meets the plane of focus. A zero lens radius gives camera_ray(f, x, y) exactly.
inline Ray camera_ray(const CameraFrame& f, float x, float y, float lens_u, float lens_v) {
    Ray ray = camera_ray(f, x, y);
    if (f.lens_radius == 0.0f) return ray;
    const float sx = (2.0f * x * f.inv_width - 1.0f) * f.half_width;
    const float sy = (1.0f - 2.0f * y * f.inv_height) * f.half_height;
    const vec3 focus = f.origin + f.focal_distance * ((f.w + sx * f.u) + sy * f.v);
    const vec2 disk = concentric_disk(vec2(lens_u, lens_v));
    ray.org = f.origin + (f.lens_radius * disk.x) * f.u + (f.lens_radius * disk.y) * f.v;
    const vec3 d = focus - ray.org;
    ray.dir = d / std::sqrt(glm::dot(d, d));
    return ray;
}

}  // namespace raylane
