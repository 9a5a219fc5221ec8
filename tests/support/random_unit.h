// Test support: random unit vectors, uniform on the sphere.
#pragma once

#include <glm/glm.hpp>
#include <random>

namespace raylane::test {

/// A normalised Gaussian vector (drawn again when its length^2 is below 1e-6).
inline glm::vec3 random_unit(std::mt19937& rng) {
    std::normal_distribution<float> gauss;
    for (;;) {
        const glm::vec3 v(gauss(rng), gauss(rng), gauss(rng));
        if (glm::dot(v, v) > 1e-6f) return glm::normalize(v);
    }
}

}  // namespace raylane::test
