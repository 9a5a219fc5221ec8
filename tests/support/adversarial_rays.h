// Test support: adversarial rays for the unit cube and a floor in its bottom plane (the meshes
// of geometry_support.h), for the oracle tests of the slab and triangle tests and of every
// traversal.
#pragma once

#include <random>
#include <vector>

#include "core/ray.h"

namespace raylane {

/// Adversarial rays for the cube [0, 1]^3 and the floor: origins snapped to face planes, zero,
/// -0, denormal and tiny direction components, rays through corners and along edges.
inline std::vector<Ray> adversarial_rays(size_t n) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> pos(-3.0f, 3.0f), unit(-1.0f, 1.0f), s01(0.0f, 1.0f);
    std::uniform_int_distribution<int> pick(0, 9);
    const float planes[] = {0.0f, 1.0f, 0.5f, -2.0f, 2.0f};
    const float specials[] = {0.0f, -0.0f, 1e-40f, -1e-40f, 1e-30f, -1e-30f, 1.0f, -1.0f};
    std::vector<Ray> rays;
    rays.reserve(n);
    while (rays.size() < n) {
        Ray r;
        r.org = vec3(pos(rng), pos(rng), pos(rng));
        for (int k = 0; k < 3; ++k)
            if (pick(rng) < 3) r.org[k] = planes[rng() % 5];
        const int kind = pick(rng);
        if (kind < 2) {
            // through a corner of the cube
            const vec3 corner(float(rng() % 2), float(rng() % 2), float(rng() % 2));
            r.dir = corner - r.org;
        } else if (kind < 4) {
            // along an edge line of the cube (origin on the line, direction along it)
            const int axis = int(rng() % 3);
            r.org[(axis + 1) % 3] = float(rng() % 2);
            r.org[(axis + 2) % 3] = float(rng() % 2);
            r.dir = vec3(0.0f);
            r.dir[axis] = rng() % 2 ? 1.0f : -1.0f;
            if (rng() % 2) r.dir[(axis + 1) % 3] = specials[rng() % 8];
        } else {
            // toward a random point of the cube, some components replaced by specials
            const vec3 target(s01(rng), s01(rng), s01(rng));
            r.dir = target - r.org;
            for (int k = 0; k < 3; ++k)
                if (pick(rng) < 3) r.dir[k] = specials[rng() % 8];
        }
        if (r.dir == vec3(0.0f)) continue;
        if (rng() % 8 == 0) r.t_max = s01(rng) * 4.0f;
        rays.push_back(r);
    }
    return rays;
}

}  // namespace raylane
