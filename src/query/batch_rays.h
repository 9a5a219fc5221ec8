// query: the caller's ray arrays as the batch queries read them (intersect_batch.h): which
// rays are traced, and the cone test of the automatic coherence choice. Both paths, every
// instruction set.
#pragma once

#include <cmath>
#include <cstddef>

#include "core/ray.h"
#include "query/intersect_batch.h"

namespace raylane {

/// Ray i, and whether it is traced: finite origin and direction, a direction that is not zero,
/// and t_max > 0.
inline bool read_ray(const RayArrays& rays, size_t i, Ray& ray) {
    const float* o = rays.org + i * rays.org_stride;
    const float* d = rays.dir + i * rays.dir_stride;
    ray.org = vec3(o[0], o[1], o[2]);
    ray.dir = vec3(d[0], d[1], d[2]);
    ray.t_min = 0.0f;
    ray.t_max = rays.t_max ? rays.t_max[i] : rays.t_max_all;
    const bool finite = std::isfinite(o[0]) && std::isfinite(o[1]) && std::isfinite(o[2]) &&
                        std::isfinite(d[0]) && std::isfinite(d[1]) && std::isfinite(d[2]);
    return finite && ray.dir != vec3(0.0f) && ray.t_max > 0.0f;
}

/// The automatic choice's test: every direction within about 25 degrees of the first one's
/// (cosine >= 0.9, compared squared: no square root or division per ray).
struct ConeTest {
    vec3 first{0.0f};
    float first_len2 = 0.0f;
    bool inside = true;
    void add(vec3 d) {
        const float len2 = glm::dot(d, d);
        if (first_len2 == 0.0f) {
            first = d, first_len2 = len2;
            return;
        }
        const float c = glm::dot(d, first);
        inside = inside && c > 0.0f && c * c >= 0.81f * len2 * first_len2;
    }
};

}  // namespace raylane
