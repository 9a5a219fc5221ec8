// shade: the report's local shading of one hit (diffuse + Phong, shadow rays to every light),
// the reference path. Mirrored by shade_packet.h.
#pragma once

#include <cstdint>

#include "accel/bvh.h"
#include "core/ray.h"
#include "scene/scene.h"

namespace raylane {

/// Rays traced while shading, by kind.
struct ShadeCounts {
    uint64_t shadow_rays = 0;
};

/// Radiance leaving the hit towards the ray origin:
///   k_a c_d + sum over lights with cos(theta) > 0 and no occluder of
///   k_d c_light F c_d cos(theta) + k_s c_light F c_s max(cos(alpha), 0)^e,
/// F = intensity / d^2 (point) or intensity (directional), theta between the shading normal and
/// the direction to the light, alpha between that direction and the mirrored view direction.
/// No 1/pi (the report's equations). Normals are turned to face the viewer.
vec3 shade_hit(const Scene& scene, const Accel& accel, const Ray& ray, const Hit& hit,
               ShadeCounts& counts);

}  // namespace raylane
