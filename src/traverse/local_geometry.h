// traverse: what a shape reports about a hit point in its object space. Used by the reference
// shape files (*_scalar.h); the packet shape files (*_packet.h) keep the same fields in SoA form.
#pragma once

#include <cmath>
#include <numbers>

#include "core/ray.h"

namespace raylane {

/// Geometry at an object-space hit point.
struct LocalGeometry {
    vec3 normal{0.0f, 1.0f, 0.0f};  ///< unit geometric normal (outward, or the winding side)
    vec2 uv{0.0f};                  ///< surface parameters; in [0, 1] on bounded shapes
};

/// Azimuth of (x, z) around +y, measured from +x towards +z, as a fraction of a turn in [0, 1].
/// The u parameter of spheres and cylinders.
inline float azimuth_fraction(float x, float z) {
    float phi = std::atan2(z, x);  // (-pi, pi]
    if (phi < 0.0f) phi += 2.0f * std::numbers::pi_v<float>;
    return phi * (0.5f * std::numbers::inv_pi_v<float>);
}

}  // namespace raylane
