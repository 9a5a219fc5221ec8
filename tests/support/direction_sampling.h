// Test support for the BRDF and optics tests (tests/shade/brdf_*_test.cpp, optics_test.cpp):
// reproducible random numbers and directions, directions at an angle, and direction pdfs
// integrated over bins of (cosine, azimuth).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "shade/brdf_scalar.h"
#include "support/float_values.h"

namespace raylane::test {

#ifdef RAYLANE_SANITIZED
inline constexpr int sample_scale = 10;  // sanitizers: 10x fewer samples, same assertions
#else
inline constexpr int sample_scale = 1;
#endif

/// Uniform floats in [0, 1) (24 bits), reproducible.
struct Rng {
    std::mt19937_64 engine;
    explicit Rng(uint64_t seed) : engine(seed) {}
    float uniform() { return static_cast<float>(engine() >> 40) * 0x1.0p-24f; }
    /// Uniform on the unit sphere, normalised in float.
    vec3 direction() {
        const float z = 2.0f * uniform() - 1.0f;
        const float phi = 2.0f * static_cast<float>(pi_d) * uniform();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::normalize(vec3(r * std::cos(phi), r * std::sin(phi), z));
    }
    /// Uniform on the hemisphere around unit n (strictly above: n.w > 1e-3).
    vec3 above(vec3 n) {
        for (;;) {
            const vec3 w = direction();
            const float c = glm::dot(w, n);
            if (c > 1e-3f) return w;
            if (c < -1e-3f) return -w;
        }
    }
};

/// A tangent of unit n by Gram-Schmidt (independent of orthonormal_basis).
inline vec3 tangent_of(vec3 n) {
    const vec3 a = std::fabs(n.x) < 0.6f ? vec3(1, 0, 0) : vec3(0, 1, 0);
    return glm::normalize(a - n * glm::dot(a, n));
}

/// Unit vector at polar angle theta from n, towards tangent t.
inline vec3 at_angle(vec3 n, vec3 t, double theta) {
    return glm::normalize(n * static_cast<float>(std::cos(theta)) +
                          t * static_cast<float>(std::sin(theta)));
}

inline double radians(double deg) { return deg * pi_d / 180.0; }

inline bool finite(float v) { return std::isfinite(v); }
inline bool finite(vec3 v) { return finite(v.x) && finite(v.y) && finite(v.z); }

using dvec3 = glm::dvec3;
inline dvec3 to_d(vec3 v) { return dvec3(v.x, v.y, v.z); }

/// Integral of pdf(wi) over each of nz x nphi bins of (n.wi, azimuth) in the frame (t, b, n),
/// by the midpoint rule with sub x sub points per bin (solid angle = dz dphi).
template <class Pdf>
std::vector<double> bin_probabilities(Pdf pdf, vec3 n, int nz, int nphi, int sub) {
    vec3 t, b;
    orthonormal_basis(n, t, b);
    std::vector<double> p(size_t(nz * nphi), 0.0);
    const double dz = 2.0 / (nz * sub), dphi = 2 * pi_d / (nphi * sub);
    for (int iz = 0; iz < nz * sub; ++iz) {
        const double z = -1 + (iz + 0.5) * dz, r = std::sqrt(1 - z * z);
        for (int ip = 0; ip < nphi * sub; ++ip) {
            const double phi = (ip + 0.5) * dphi;
            const vec3 w = glm::normalize(t * float(r * std::cos(phi)) +
                                          b * float(r * std::sin(phi)) + n * float(z));
            p[size_t((iz / sub) * nphi + ip / sub)] += pdf(w) * dz * dphi;
        }
    }
    return p;
}

/// The bin of bin_probabilities that holds direction w.
inline int bin_of(vec3 w, vec3 n, int nz, int nphi) {
    vec3 t, b;
    orthonormal_basis(n, t, b);
    const double z = std::clamp(double(glm::dot(w, n)), -1.0, 1.0);
    double phi = std::atan2(double(glm::dot(w, b)), double(glm::dot(w, t)));
    if (phi < 0) phi += 2 * pi_d;
    const int iz = std::min(nz - 1, int((z + 1) / 2 * nz));
    const int ip = std::min(nphi - 1, int(phi / (2 * pi_d) * nphi));
    return iz * nphi + ip;
}

}  // namespace raylane::test
