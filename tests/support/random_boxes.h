// tests/support: random axis-aligned boxes for the BVH builders' tests.
#pragma once

#include <random>
#include <vector>

#include "core/aabb.h"

namespace raylane {

/// n boxes with corners uniform in [-10, 10]^3 and sides uniform in [0, 0.5], from `seed`.
inline std::vector<Aabb> random_boxes(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-10.0f, 10.0f), size(0.0f, 0.5f);
    std::vector<Aabb> boxes(n);
    for (Aabb& b : boxes) {
        b.lo = vec3(pos(rng), pos(rng), pos(rng));
        b.hi = b.lo + vec3(size(rng), size(rng), size(rng));
    }
    return boxes;
}

}  // namespace raylane
