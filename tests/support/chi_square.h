// The chi-square test of the numerics suite's sampler tests (phong_exponent_test.cpp,
// ward_tiny_alpha_test.cpp): Pearson's statistic with small bins pooled, its p-value, and the
// frame in which the samples are binned.
#pragma once

#include <cmath>
#include <glm/glm.hpp>
#include <vector>

namespace raylane::chi_square {

/// Regularised upper incomplete gamma Q(a, x) (series below a + 1, Lentz's continued fraction
/// above; Press et al., "Numerical Recipes", 6.2).
inline double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double front = std::exp(-x + a * std::log(x) - std::lgamma(a));
    if (x < a + 1) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000 && term > sum * 1e-16; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * front;
    }
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        d = std::fabs(d) < tiny ? tiny : d;
        c = b + an / c;
        c = std::fabs(c) < tiny ? tiny : c;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::fabs(del - 1) < 1e-16) break;
    }
    return front * h;
}

/// Pearson chi-square p-value of counts against expected counts, pooling bins expected < 5.
inline double chi2_p_value(const std::vector<double>& expected, const std::vector<int>& counts,
                           int* bins_used) {
    double chi2 = 0, pooled_e = 0, pooled_o = 0;
    int bins = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        if (expected[i] < 5) {
            pooled_e += expected[i], pooled_o += counts[i];
            continue;
        }
        chi2 += (counts[i] - expected[i]) * (counts[i] - expected[i]) / expected[i], ++bins;
    }
    if (pooled_e > 0) chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, ++bins;
    *bins_used = bins;
    return gamma_q(0.5 * (bins - 1), 0.5 * chi2);
}

/// An orthonormal frame around unit a by Gram-Schmidt in double (independent of Raylane's).
struct Frame {
    glm::dvec3 t, b, n;
};
inline Frame frame_of(glm::vec3 a) {
    Frame f;
    f.n = glm::normalize(glm::dvec3(a));
    const glm::dvec3 g = std::fabs(f.n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    f.t = glm::normalize(g - f.n * glm::dot(g, f.n));
    f.b = glm::cross(f.n, f.t);
    return f;
}

}  // namespace raylane::chi_square
