// Tests of shade/brdf_scalar.h: the samplers' distributions (Kolmogorov-Smirnov and chi-square),
// the pdfs and weights they return, and pdf normalisation. Lobes: brdf_lobes_test.cpp; albedo:
// brdf_albedo_test.cpp; the packet twin: brdf_packet_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "shade/brdf_scalar.h"
#include "support/direction_sampling.h"
#include "support/float_values.h"

namespace raylane {
namespace {

using namespace test;

/// Kolmogorov-Smirnov distance of samples from Uniform(0, 1).
double ks_uniform(std::vector<double> u) {
    std::sort(u.begin(), u.end());
    const double n = static_cast<double>(u.size());
    double d = 0.0;
    for (size_t i = 0; i < u.size(); ++i) {
        d = std::max(d, static_cast<double>(i + 1) / n - u[i]);
        d = std::max(d, u[i] - static_cast<double>(i) / n);
    }
    return d;
}
/// KS critical distance at significance 0.001.
double ks_critical(size_t n) { return 1.949 / std::sqrt(static_cast<double>(n)); }

/// Chi-square critical value at significance 0.001 (Wilson-Hilferty).
double chi2_critical(int dof) {
    const double k = dof, z = 3.0902;
    const double c = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
    return k * c * c * c;
}

// ---- sampling: distributions ----------------------------------------------------------------

TEST(SamplePhongLobe, CosinePowerIsUniform) {
    const size_t count = 100000 / sample_scale;
    Rng rng(400);
    for (float e : {0.0f, 10.0f, 1000.0f, 1e6f}) {
        std::vector<double> u, phi;
        const vec3 axis = e == 1000.0f ? vec3(0, 0, -1) : rng.direction();
        vec3 t, b;
        orthonormal_basis(axis, t, b);
        for (size_t i = 0; i < count; ++i) {
            const vec3 w = sample_phong_lobe(axis, e, rng.uniform(), rng.uniform());
            const dvec3 wd = glm::normalize(to_d(w));
            const double c = glm::dot(wd, glm::normalize(to_d(axis)));
            ASSERT_GT(c, 0.0);
            u.push_back(std::exp((double(e) + 1.0) * std::log(c)));  // P(cos^(e+1) <= x) = x
            const double p = std::atan2(glm::dot(wd, to_d(b)), glm::dot(wd, to_d(t)));
            phi.push_back(p < 0 ? p / (2 * pi_d) + 1 : p / (2 * pi_d));
        }
        EXPECT_LT(ks_uniform(u), ks_critical(count)) << "e = " << e;
        EXPECT_LT(ks_uniform(phi), ks_critical(count)) << "e = " << e;
    }
}

TEST(SamplePhongLobe, StaysNearTheAxisAtExtremeRandomNumbers) {
    Rng rng(401);
    const float last = 1.0f - 0x1.0p-24f;
    for (int i = 0; i < 200; ++i) {
        const vec3 axis = i == 0 ? vec3(0, 0, -1) : rng.direction();
        for (float u2 : {0.0f, 1e-12f, 0.5f, 1.0f - 1e-7f, last}) {
            for (float u1 : {0.0f, 0.25f, last}) {
                const vec3 w = sample_phong_lobe(axis, 1e6f, u1, u2);
                ASSERT_TRUE(finite(w));
                EXPECT_NEAR(glm::length(w), 1.0f, 1e-6f);
                const double angle = std::atan2(glm::length(glm::cross(to_d(w), to_d(axis))),
                                                glm::dot(to_d(w), to_d(axis)));
                EXPECT_LT(angle, 0.01) << u2;
                // the sine is exact in log space: angle = acos((1 - u2)^(1 / (e + 1)))
                const double expected = std::acos(std::pow(1.0 - double(u2), 1.0 / (1e6 + 1)));
                EXPECT_NEAR(angle, expected, 1e-6 + 1e-4 * expected) << u2;
            }
        }
        EXPECT_NEAR(glm::length(sample_phong_lobe(axis, 0.0f, 0.3f, last)), 1.0f, 1e-6f);
    }
}

TEST(SampleWard, TangentSquaredIsExponential) {
    const size_t count = 100000 / sample_scale;
    Rng rng(402);
    for (float alpha : {0.01f, 0.05f, 0.3f}) {
        for (double theta : {0.0, 50.0}) {
            const vec3 n = rng.direction(), wo = at_angle(n, tangent_of(n), radians(theta));
            vec3 t, b;
            orthonormal_basis(n, t, b);
            std::vector<double> u, phi;
            for (size_t i = 0; i < count; ++i) {
                const LobeSample s = sample_ward(n, wo, alpha, rng.uniform(), rng.uniform());
                const dvec3 h = to_d(s.wi) + to_d(wo), nd = to_d(n);
                const double hz = glm::dot(nd, h);
                const dvec3 c = glm::cross(nd, h);
                const double t2 = glm::dot(c, c) / (hz * hz);
                u.push_back(std::exp(-t2 / (double(alpha) * double(alpha))));  // Exp(1) -> U
                if (theta == 0.0) {  // wo = n: h = H / |H| exactly, so phi_h is recoverable
                    const double p = std::atan2(glm::dot(h, to_d(b)), glm::dot(h, to_d(t)));
                    phi.push_back(p < 0 ? p / (2 * pi_d) + 1 : p / (2 * pi_d));
                }
            }
            EXPECT_LT(ks_uniform(u), ks_critical(count)) << alpha << " " << theta;
            if (!phi.empty()) {
                EXPECT_LT(ks_uniform(phi), ks_critical(phi.size())) << alpha;
            }
        }
    }
}

TEST(SampleBlinnPhong, CosinePowerOfTheHalfVectorIsUniform) {
    const size_t count = 100000 / sample_scale;
    Rng rng(403);
    for (float e : {10.0f, 83.4f, 28400.0f, 1e6f}) {
        const vec3 n = rng.direction(), wo = at_angle(n, tangent_of(n), radians(40.0));
        std::vector<double> u;
        for (size_t i = 0; i < count; ++i) {
            const LobeSample s = sample_blinn_phong(n, wo, e, rng.uniform(), rng.uniform());
            const dvec3 h = to_d(s.wi) + to_d(wo), nd = to_d(n);
            const double hz = glm::dot(nd, h);
            const dvec3 c = glm::cross(nd, h);
            const double log_cos = -0.5 * std::log1p(glm::dot(c, c) / (hz * hz));
            u.push_back(std::exp((double(e) + 1.0) * log_cos));
        }
        EXPECT_LT(ks_uniform(u), ks_critical(count)) << "n = " << e;
    }
}

// ---- sampling: pdfs -------------------------------------------------------------------------

/// Relative tolerance for a pdf re-evaluated from a sampled float direction wi: wi carries an
/// absolute error ~2e-7, so H = wi + wo (|H| = 2 wo.h) and its tangential part sqrt(t2) |H| / ...
/// are known to 2e-7 absolute; the lobe exponent x (t2 / alpha^2 or e/2 log1p(t2)) then has
/// relative error 2e-7 / (|H| tan), and the Jacobian 1 / (wo.h) relative error 2e-7 / (wo.h).
double resample_tolerance(vec3 n, vec3 wi, vec3 wo, double x_per_t2, bool log_form) {
    const dvec3 h = to_d(wi) + to_d(wo), nd = to_d(n);
    const double len = glm::length(h), hz = glm::dot(nd, h);
    const dvec3 c = glm::cross(nd, h);
    const double t2 = glm::dot(c, c) / (hz * hz);
    const double x = log_form ? x_per_t2 * std::log1p(t2) : x_per_t2 * t2;
    const double delta = 4e-7;
    return 2e-4 + 2 * delta / len + 2 * x * delta / (len * std::sqrt(std::max(t2, 1e-30)));
}

TEST(LobeSamplers, ReturnThePdfAndWeightTheyEvaluateTo) {
    Rng rng(500);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 n = rng.direction(), wo = rng.above(n);
        const float u1 = rng.uniform(), u2 = rng.uniform();
        const float alpha = std::array{0.01f, 0.05f, 0.162f, 0.3f}[i % 4];
        const float e = std::array{10.0f, 83.4f, 1040.0f, 28400.0f}[i % 4];
        const float co = glm::dot(n, wo);
        for (bool duer : {false, true}) {
            const LobeSample s =
                duer ? sample_ward_duer(n, wo, alpha, u1, u2) : sample_ward(n, wo, alpha, u1, u2);
            const float pdf = pdf_ward(n, s.wi, wo, alpha);
            const double tol =
                resample_tolerance(n, s.wi, wo, 1.0 / (double(alpha) * alpha), false);
            EXPECT_NEAR(s.pdf / pdf, 1.0, tol) << alpha;
            const float ci = glm::dot(n, s.wi);
            if (ci > 1e-3f && co > 1e-3f) {
                ++checked;
                const float f =
                    duer ? ward_duer_lobe(n, s.wi, wo, alpha) : ward_lobe(n, s.wi, wo, alpha);
                EXPECT_NEAR(s.weight / (f * ci / pdf), 1.0, tol + 1e-6 / ci) << alpha;
            }
        }
        const LobeSample s = sample_blinn_phong(n, wo, e, u1, u2);
        const float pdf = pdf_blinn_phong(n, s.wi, wo, e);
        const double tol = resample_tolerance(n, s.wi, wo, 0.5 * e, true);
        EXPECT_NEAR(s.pdf / pdf, 1.0, tol) << e;
        const float ci = glm::dot(n, s.wi);
        if (ci > 1e-3f && co > 1e-3f) {
            EXPECT_NEAR(s.weight / (blinn_phong_lobe(n, s.wi, wo, e) * ci / pdf), 1.0,
                        tol + 1e-6 / ci);
        }
        // modified Phong: glossy_weight(physical) = f ci / pdf with f = (e+2)/(2 pi) cos^e
        const vec3 r = mirror_direction(n, wo);
        const vec3 w = sample_phong_lobe(r, e, u1, u2);
        const double f = (e + 2.0) / (2.0 * pi_d) * phong_lobe(r, w, e);
        Material m;
        m.k_s = 1.0f;
        m.c_s = vec3(1.0f);
        m.exponent = e;
        const float cw = glm::dot(n, w);
        if (cw > 1e-3f) {
            EXPECT_NEAR(glossy_weight(m, BrdfScaling::physical, n, w).x /
                            (f * cw / pdf_phong_lobe(r, e, w)),
                        1.0, 1e-3);
        }
    }
    EXPECT_GT(checked, 10000);
}

/// Pearson chi-square of sample counts against bin probabilities, pooling bins expected < 5.
void expect_chi2_fit(const std::vector<double>& p, const std::vector<int>& counts, int total,
                     const std::string& what) {
    double chi2 = 0, pooled_e = 0, pooled_o = 0;
    int bins = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        const double e = p[i] * total;
        if (e < 5) {
            pooled_e += e, pooled_o += counts[i];
            continue;
        }
        chi2 += (counts[i] - e) * (counts[i] - e) / e, ++bins;
    }
    if (pooled_e >= 5) chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, ++bins;
    ASSERT_GT(bins, 10) << what;
    EXPECT_LT(chi2, chi2_critical(bins - 1)) << what << ": " << bins << " bins";
}

TEST(LobeSamplers, PassAChiSquareTestAgainstTheirPdfs) {
    // The half-vector pdfs have an integrable 1 / |wi + wo| singularity at wi = -wo, which the
    // midpoint rule cannot integrate; the cases keep it where the density is negligible
    // (half vectors perpendicular to wo are far out in the lobe's tail).
    const int nz = 40, nphi = 40, total = 400000 / sample_scale;
    Rng rng(501);
    struct Case {
        const char* name;
        int kind;  // 0 Ward, 1 Blinn-Phong, 2 Phong lobe around the mirror direction
        float param;
        double theta;
    };
    for (const Case& c :
         {Case{"Ward 0.162", 0, 0.162f, 60.0}, Case{"Ward 0.3", 0, 0.3f, 20.0},
          Case{"Blinn-Phong 83.4", 1, 83.4f, 30.0}, Case{"Blinn-Phong 30", 1, 30.0f, 50.0},
          Case{"Phong 20", 2, 20.0f, 45.0}}) {
        const vec3 n = rng.direction(), wo = at_angle(n, tangent_of(n), radians(c.theta));
        const vec3 r = mirror_direction(n, wo);
        const std::vector<double> p = bin_probabilities(
            [&](vec3 w) -> double {
                return c.kind == 0   ? pdf_ward(n, w, wo, c.param)
                       : c.kind == 1 ? pdf_blinn_phong(n, w, wo, c.param)
                                     : pdf_phong_lobe(r, c.param, w);
            },
            n, nz, nphi, 12);
        double sum = 0;
        for (double v : p) sum += v;
        EXPECT_NEAR(sum, 1.0, 3e-3) << c.name << ": the pdf integrates to 1 over the sphere";
        std::vector<int> counts(p.size(), 0);
        for (int i = 0; i < total; ++i) {
            const float u1 = rng.uniform(), u2 = rng.uniform();
            const vec3 w = c.kind == 0   ? sample_ward(n, wo, c.param, u1, u2).wi
                           : c.kind == 1 ? sample_blinn_phong(n, wo, c.param, u1, u2).wi
                                         : sample_phong_lobe(r, c.param, u1, u2);
            ++counts[size_t(bin_of(w, n, nz, nphi))];
        }
        expect_chi2_fit(p, counts, total, c.name);
    }
}

}  // namespace
}  // namespace raylane
