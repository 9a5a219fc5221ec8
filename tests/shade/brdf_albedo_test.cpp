// Tests of shade/brdf_scalar.h: directional albedo of the lobes against brdf-reference.md
// section 6 (the table, closed forms at normal incidence, cosine sampling) and the samplers' mass
// above the horizon. Lobes: brdf_lobes_test.cpp; sampling: brdf_sampling_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "shade/brdf_scalar.h"
#include "support/direction_sampling.h"
#include "support/float_values.h"

namespace raylane {
namespace {

using namespace test;

// ---- directional albedo (brdf-reference.md section 6) -----------------------------------------

enum class Lobe { ward, ward_duer, blinn_phong, modified_phong };

struct Estimate {
    double mean = 0, se = 0;
};
struct AlbedoEstimates {
    Estimate weight;   ///< mean of the samplers' closed-form weights
    Estimate eval;     ///< mean of (evaluated f ci) / (evaluated pdf)
    double above = 0;  ///< fraction of samples above the surface
};

/// Directional albedo of a unit-rho_s lobe at viewing angle theta_o, in a random world frame.
AlbedoEstimates albedo(Lobe lobe, float param, double theta_o_deg, int count, uint64_t seed) {
    Rng rng(seed);
    const vec3 n = rng.direction();
    const vec3 wo = at_angle(n, tangent_of(n), radians(theta_o_deg));
    Material m;
    m.k_s = 1.0f;
    m.c_s = vec3(1.0f);
    m.alpha = param;
    m.exponent = param;
    m.model = lobe == Lobe::ward        ? SpecularModel::ward
              : lobe == Lobe::ward_duer ? SpecularModel::ward_duer
                                        : SpecularModel::blinn_phong;
    double sw = 0, sw2 = 0, se = 0, se2 = 0, above = 0;
    for (int i = 0; i < count; ++i) {
        const float u1 = rng.uniform(), u2 = rng.uniform();
        double w = 0, e = 0;
        vec3 wi;
        if (lobe == Lobe::modified_phong) {
            m.model = SpecularModel::glossy_phong;
            const vec3 r = mirror_direction(n, wo);
            wi = sample_phong_lobe(r, param, u1, u2);
            w = glossy_weight(m, BrdfScaling::physical, n, wi).x;
            const double pdf = pdf_phong_lobe(r, param, wi);
            const double f = (param + 2.0) / (2.0 * pi_d) * phong_lobe(r, wi, param);
            if (pdf > 0 && glm::dot(n, wi) > 0) e = f * glm::dot(n, wi) / pdf;
        } else {
            const LobeSample s = lobe == Lobe::ward ? sample_ward(n, wo, param, u1, u2)
                                 : lobe == Lobe::ward_duer
                                     ? sample_ward_duer(n, wo, param, u1, u2)
                                     : sample_blinn_phong(n, wo, param, u1, u2);
            wi = s.wi;
            w = s.weight;
            const double pdf = lobe == Lobe::blinn_phong ? pdf_blinn_phong(n, wi, wo, param)
                                                         : pdf_ward(n, wi, wo, param);
            if (pdf > 0) e = specular_factor(m, BrdfScaling::physical, n, wi, wo).x / pdf;
        }
        if (glm::dot(n, wi) > 0) above += 1;
        sw += w, sw2 += w * w, se += e, se2 += e * e;
    }
    const double c = count;
    auto finish = [c](double s, double s2) {
        const double mean = s / c;
        return Estimate{mean, std::sqrt(std::max(0.0, s2 / c - mean * mean) / c)};
    };
    return {finish(sw, sw2), finish(se, se2), above / c};
}

struct AlbedoRow {
    const char* name;
    Lobe lobe;
    float param;
    std::array<double, 5> ref;  // theta_o = 0, 30, 60, 75, 85 degrees
};

const std::array<AlbedoRow, 10> albedo_table = {{
    {"Ward 0.0432", Lobe::ward, 0.0432f, {0.994, 0.861, 0.498, 0.259, 0.092}},
    {"Ward 0.0141", Lobe::ward, 0.0141f, {0.999, 0.866, 0.500, 0.259, 0.088}},
    {"Ward 0.162", Lobe::ward, 0.162f, {0.928, 0.805, 0.472, 0.265, 0.159}},
    {"Ward-Duer 0.0424", Lobe::ward_duer, 0.0424f, {0.996, 0.996, 0.996, 0.997, 0.970}},
    {"Ward-Duer 0.0137", Lobe::ward_duer, 0.0137f, {1.000, 1.000, 1.000, 1.000, 1.000}},
    {"Ward-Duer 0.146", Lobe::ward_duer, 0.146f, {0.960, 0.960, 0.958, 0.929, 1.042}},
    {"Blinn-Phong 1040", Lobe::blinn_phong, 1040.0f, {3.985, 2.991, 1.002, 0.274, 0.038}},
    {"Blinn-Phong 28400", Lobe::blinn_phong, 28400.0f, {3.999, 3.000, 1.000, 0.268, 0.031}},
    {"Blinn-Phong 83.4", Lobe::blinn_phong, 83.4f, {3.817, 2.886, 1.023, 0.343, 0.105}},
    {"modified Phong 1000", Lobe::modified_phong, 1000.0f, {1.000, 0.866, 0.500, 0.259, 0.087}},
}};

TEST(DirectionalAlbedo, MatchesTheReferenceTable) {
    const std::array<double, 5> angles = {0, 30, 60, 75, 85};
    const int count = 200000 / sample_scale;
    uint64_t seed = 100;
    for (const AlbedoRow& row : albedo_table) {
        for (size_t a = 0; a < angles.size(); ++a) {
            const AlbedoEstimates est = albedo(row.lobe, row.param, angles[a], count, ++seed);
            const double ref = row.ref[a];
            const std::string where =
                std::string(row.name) + " at " + std::to_string(int(angles[a])) + " degrees";
            EXPECT_NEAR(est.weight.mean, ref, std::max(0.01, 4 * est.weight.se)) << where;
            EXPECT_NEAR(est.eval.mean, ref, std::max(0.01, 4 * est.eval.se)) << where;
        }
    }
}

/// Simpson's rule on [a, b] with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
    const double h = (b - a) / n;
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
    return s * h / 3;
}

TEST(DirectionalAlbedo, NormalIncidenceMatchesTheClosedForms) {
    // brdf-reference.md section 6, x = tan(theta_h)
    auto ward_duer_a0 = [](double a) {
        return 2 / (a * a) *
               simpson(
                   [a](double x) {
                       return std::exp(-x * x / (a * a)) * x / ((1 + x * x) * (1 + x * x));
                   },
                   0, 1, 200000);
    };
    auto ward_a0 = [](double a) {
        return 2 / (a * a) *
               simpson(
                   [a](double x) {
                       return std::exp(-x * x / (a * a)) * x / ((1 + x * x) * (1 + x * x)) *
                              std::sqrt((1 - x * x) / (1 + x * x));
                   },
                   0, 1, 200000);
    };
    auto blinn_phong_a0 = [](double n) {
        return 4 * (n + 2) *
               (2 * (1 - std::pow(2, -(n + 4) / 2)) / (n + 4) -
                (1 - std::pow(2, -(n + 2) / 2)) / (n + 2));
    };
    struct Case {
        Lobe lobe;
        float param;
        double closed, published;
    };
    const Case cases[] = {
        {Lobe::ward_duer, 0.0432f, ward_duer_a0(0.0432), 0.99629},
        {Lobe::ward_duer, 0.162f, ward_duer_a0(0.162), 0.95126},
        {Lobe::ward_duer, 0.146f, ward_duer_a0(0.146), 0.95988},
        {Lobe::ward, 0.0432f, ward_a0(0.0432), 0.99444},
        {Lobe::ward, 0.162f, ward_a0(0.162), 0.92804},
        {Lobe::blinn_phong, 1040.0f, blinn_phong_a0(1040), 3.98467},
        {Lobe::blinn_phong, 28400.0f, blinn_phong_a0(28400), 3.99944},
        {Lobe::blinn_phong, 83.4f, blinn_phong_a0(83.4), 3.81693},
        {Lobe::modified_phong, 1000.0f, 1.0, 1.0},
    };
    uint64_t seed = 200;
    for (const Case& c : cases) {
        EXPECT_NEAR(c.closed, c.published, 2e-5 * c.published);
        // the float param differs from the double one in the 8th digit: negligible here
        const AlbedoEstimates est = albedo(c.lobe, c.param, 0.0, 400000 / sample_scale, ++seed);
        EXPECT_NEAR(est.weight.mean, c.closed, 4 * est.weight.se + 1e-4) << c.param;
        EXPECT_NEAR(est.eval.mean, c.closed, 4 * est.eval.se + 1e-4) << c.param;
    }
}

TEST(DirectionalAlbedo, BroadLobesAgreeWithCosineSampling) {
    // estimator (a): the lobe's own sampler; (b): cosine-weighted hemisphere, pi S
    const int count = 400000 / sample_scale;
    uint64_t seed = 300;
    for (Lobe lobe : {Lobe::ward, Lobe::ward_duer, Lobe::blinn_phong}) {
        const float param = lobe == Lobe::blinn_phong ? 83.4f : 0.162f;
        for (double theta : {0.0, 30.0, 60.0}) {
            const AlbedoEstimates est = albedo(lobe, param, theta, count, ++seed);
            Rng rng(++seed);
            const vec3 n = rng.direction(), t = tangent_of(n), b = glm::cross(n, t);
            const vec3 wo = at_angle(n, t, radians(theta));
            double s = 0, s2 = 0;
            for (int i = 0; i < count; ++i) {
                const float r = std::sqrt(rng.uniform()), phi = 6.2831853f * rng.uniform();
                const vec3 wi = glm::normalize(t * (r * std::cos(phi)) + b * (r * std::sin(phi)) +
                                               n * std::sqrt(std::max(0.0f, 1.0f - r * r)));
                const double v = lobe == Lobe::ward        ? ward_lobe(n, wi, wo, param)
                                 : lobe == Lobe::ward_duer ? ward_duer_lobe(n, wi, wo, param)
                                                           : blinn_phong_lobe(n, wi, wo, param);
                s += pi_d * v, s2 += pi_d * pi_d * v * v;
            }
            const double mean = s / count, se = std::sqrt((s2 / count - mean * mean) / count);
            EXPECT_NEAR(est.weight.mean, mean, 4 * std::hypot(se, est.weight.se))
                << int(lobe) << " at " << theta;
        }
    }
}

TEST(LobeSamplers, LandAboveTheHorizonAsOftenAsTheReferenceSays) {
    // brdf-reference.md section 6: fraction of the sampling pdf above the horizon
    struct Case {
        Lobe lobe;
        float param;
        double theta, above, tol;
    };
    const Case cases[] = {
        {Lobe::ward, 0.0432f, 75, 1.000, 0.002},
        {Lobe::ward, 0.0432f, 85, 0.924, 0.005},
        {Lobe::ward, 0.162f, 30, 1.000, 0.002},
        {Lobe::ward, 0.162f, 60, 0.989, 0.003},
        {Lobe::ward, 0.162f, 75, 0.872, 0.005},
        {Lobe::ward, 0.162f, 85, 0.647, 0.006},
        {Lobe::modified_phong, 1000, 75, 1.0, 0.001},
        {Lobe::modified_phong, 1000, 85, 0.997, 0.002},
        {Lobe::modified_phong, 1000, 89, 0.71, 0.007},
    };
    uint64_t seed = 600;
    for (const Case& c : cases) {
        const AlbedoEstimates est = albedo(c.lobe, c.param, c.theta, 100000 / sample_scale, ++seed);
        EXPECT_NEAR(est.above, c.above, c.tol * (sample_scale == 1 ? 1 : 3))
            << c.param << " at " << c.theta;
    }
    // and the same masses by quadrature of pdf_ward over the upper hemisphere (alpha 0.162;
    // the lower one holds the pdf's singularity at wi = -wo, see the chi-square test)
    for (auto [theta, above] :
         {std::pair{60.0, 0.989}, std::pair{75.0, 0.872}, std::pair{85.0, 0.647}}) {
        const vec3 n(0, 0, 1), wo = at_angle(n, vec3(1, 0, 0), radians(theta));
        const std::vector<double> p = bin_probabilities(
            [&](vec3 w) -> double { return pdf_ward(n, w, wo, 0.162f); }, n, 2, 1, 600);
        EXPECT_NEAR(p[1], above, 1.5e-3) << theta;
    }
}

}  // namespace
}  // namespace raylane
