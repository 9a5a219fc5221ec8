// core: axis-aligned bounding boxes, shared by the BVH build and both traversal paths.
#pragma once

#include <glm/glm.hpp>

#include "core/ray.h"

namespace raylane {

/// An axis-aligned box. The default box is empty (lo > hi) and absorbs nothing when grown.
struct Aabb {
    vec3 lo{infinity};
    vec3 hi{-infinity};

    void grow(vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    vec3 extent() const { return hi - lo; }
    vec3 center() const { return 0.5f * (lo + hi); }
    float surface_area() const {
        if (empty()) return 0.0f;
        vec3 e = extent();
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
    bool contains(const Aabb& b) const {
        return lo.x <= b.lo.x && lo.y <= b.lo.y && lo.z <= b.lo.z && hi.x >= b.hi.x &&
               hi.y >= b.hi.y && hi.z >= b.hi.z;
    }
    int longest_axis() const {
        vec3 e = extent();
        return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    }
};

}  // namespace raylane
