// core: the zero-area test for triangles, shared by the loaders (which drop such triangles) and
// the watertight intersection tests of both paths (which never report a hit on one).
#pragma once

#include <glm/glm.hpp>

namespace raylane {

/// True when the three vertices span no area: their cross product is exactly zero, computed in
/// double from double differences (exact for any mesh whose edge vectors fit in 26 bits).
template <typename T>
inline bool is_zero_area_triangle(glm::vec<3, T> a, glm::vec<3, T> b, glm::vec<3, T> c) {
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

}  // namespace raylane
