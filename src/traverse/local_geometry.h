// traverse: what a shape reports about a hit point in its object space, and the real type T the
// reference shape files (*_scalar.h) are templated on: float is the renderer, double the oracle
// of tests/numerics. The packet shape files (*_packet.h) keep the same fields in SoA form.
#pragma once

#include <cmath>
#include <limits>
#include <numbers>

#include "core/ray.h"

namespace raylane {

/// A 3-vector of the real type T (vec3 for float, glm::dvec3 for double).
template <typename T>
using Vec3Of = glm::vec<3, T>;

/// +infinity in the real type T.
template <typename T>
inline constexpr T infinity_of = std::numeric_limits<T>::infinity();

/// Ray's fields in the real type T. The shape tests take it; their float overloads taking Ray
/// convert with ray_of<float>, which copies the fields exactly.
template <typename T>
struct RayOf {
    Vec3Of<T> org{T(0)};
    Vec3Of<T> dir{T(0), T(0), T(1)};
    T t_min = T(0);
    T t_max = infinity_of<T>;
};

/// The ray with its fields converted to T (exact for float and double).
template <typename T>
inline RayOf<T> ray_of(const Ray& r) {
    return {Vec3Of<T>(r.org), Vec3Of<T>(r.dir), static_cast<T>(r.t_min), static_cast<T>(r.t_max)};
}

/// Geometry at an object-space hit point.
template <typename T>
struct LocalGeometryOf {
    Vec3Of<T> normal{T(0), T(1), T(0)};  ///< unit geometric normal (outward, or the winding side)
    glm::vec<2, T> uv{T(0)};             ///< surface parameters; in [0, 1] on bounded shapes
};
using LocalGeometry = LocalGeometryOf<float>;

/// Azimuth of (x, z) around +y, measured from +x towards +z, as a fraction of a turn in [0, 1].
/// The u parameter of spheres and cylinders.
template <typename T>
inline T azimuth_fraction(T x, T z) {
    T phi = std::atan2(z, x);  // (-pi, pi]
    if (phi < T(0)) phi += T(2) * std::numbers::pi_v<T>;
    return phi * (T(0.5) * std::numbers::inv_pi_v<T>);
}

}  // namespace raylane
