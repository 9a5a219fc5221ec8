// Tests of shade/brdf_scalar.h: lobe formulas, reciprocity, degenerate inputs, directional
// albedo against brdf-reference.md section 6, sampler distributions (Kolmogorov-Smirnov and
// chi-square), pdf normalisation; and of shade/optics_scalar.h: Fresnel and Beer's law. The packet
// twin: brdf_packet_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "shade/brdf_scalar.h"
#include "shade/optics_scalar.h"
#include "support/float_values.h"

namespace raylane {
namespace {

using namespace test;

#ifdef RAYLANE_SANITIZED
constexpr int sample_scale = 10;  // sanitizers: 10x fewer samples, same assertions
#else
constexpr int sample_scale = 1;
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
vec3 tangent_of(vec3 n) {
    const vec3 a = std::fabs(n.x) < 0.6f ? vec3(1, 0, 0) : vec3(0, 1, 0);
    return glm::normalize(a - n * glm::dot(a, n));
}

/// Unit vector at polar angle theta from n, towards tangent t.
vec3 at_angle(vec3 n, vec3 t, double theta) {
    return glm::normalize(n * static_cast<float>(std::cos(theta)) +
                          t * static_cast<float>(std::sin(theta)));
}

double radians(double deg) { return deg * pi_d / 180.0; }

bool finite(float v) { return std::isfinite(v); }
bool finite(vec3 v) { return finite(v.x) && finite(v.y) && finite(v.z); }

using dvec3 = glm::dvec3;
dvec3 to_d(vec3 v) { return dvec3(v.x, v.y, v.z); }

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

// ---- frames ---------------------------------------------------------------------------------

TEST(OrthonormalBasis, IsOrthonormalAndRightHanded) {
    Rng rng(1);
    std::vector<vec3> normals = {{0, 0, 1},
                                 {0, 0, -1},
                                 {1, 0, 0},
                                 {0, -1, 0},
                                 glm::normalize(vec3(1e-4f, 0, -1)),
                                 vec3(0, 0, -0.0f) + vec3(0, 1, 0)};
    for (int i = 0; i < 2000; ++i) normals.push_back(rng.direction());
    for (const vec3 n : normals) {
        vec3 t, b;
        orthonormal_basis(n, t, b);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(b), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::distance(glm::cross(t, b), n), 0.0f, 2e-6f);
    }
}

TEST(MirrorDirection, KeepsTheAngleToTheNormal) {
    Rng rng(2);
    for (int i = 0; i < 1000; ++i) {
        const vec3 n = rng.direction(), wo = rng.above(n);
        const vec3 r = mirror_direction(n, wo);
        EXPECT_NEAR(glm::dot(r, n), glm::dot(wo, n), 1e-6f);
        EXPECT_NEAR(glm::length(r), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(glm::cross(r + wo, n)), 0.0f, 1e-6f);  // r + wo along n
        EXPECT_EQ(reflect_direction(-wo, n), r * 1.0f) << "reflect(-wo) is the mirror of wo";
    }
}

// ---- lobes ----------------------------------------------------------------------------------

TEST(BrdfLobes, PeakValuesMatchTheNormalisation) {
    const vec3 n(0, 0, 1);
    for (float alpha : {1e-4f, 0.0141f, 0.162f, 1.0f}) {
        const double k = 4.0 * pi_d * double(alpha) * double(alpha);
        EXPECT_NEAR(ward_lobe(n, n, n, alpha) * k, 1.0, 1e-6);
        EXPECT_NEAR(ward_duer_lobe(n, n, n, alpha) * k, 1.0, 1e-6);
    }
    for (float e : {0.0f, 83.4f, 1040.0f, 1e6f})
        EXPECT_NEAR(blinn_phong_lobe(n, n, n, e) / ((e + 2.0) / (2.0 * pi_d)), 1.0, 1e-6);
    EXPECT_EQ(phong_lobe(n, n, 1e6f), 1.0f);
}

// Textbook evaluation in double (acos / tan), trustworthy at moderate angles.
double ward_textbook(dvec3 n, dvec3 wi, dvec3 wo, double alpha, bool duer) {
    const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
    const double th = std::acos(glm::dot(n, glm::normalize(wi + wo)));
    const double g = std::exp(-std::pow(std::tan(th) / alpha, 2)) / (4 * pi_d * alpha * alpha);
    return duer ? g / (ci * co) : g / std::sqrt(ci * co);
}
double blinn_phong_textbook(dvec3 n, dvec3 wi, dvec3 wo, double e) {
    return (e + 2) / (2 * pi_d) * std::pow(glm::dot(n, glm::normalize(wi + wo)), e);
}
double phong_textbook(dvec3 axis, dvec3 w, double e) {
    return std::pow(std::max(0.0, glm::dot(axis, w)), e);
}

TEST(BrdfLobes, AgreeWithTextbookFormulasAtModerateAngles) {
    Rng rng(3);
    int compared = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 n = rng.direction(), wo = rng.above(n), wi = rng.above(n);
        const dvec3 nd = to_d(n), id = to_d(wi), od = to_d(wo);
        const float alpha = 0.3f, e = 20.0f;
        const double w = ward_textbook(nd, id, od, alpha, false);
        const double wd = ward_textbook(nd, id, od, alpha, true);
        const double bp = blinn_phong_textbook(nd, id, od, e);
        const double ph = phong_textbook(to_d(mirror_direction(n, wo)), id, e);
        if (w < 1e-6 || bp < 1e-6 || ph < 1e-6) continue;
        ++compared;
        // float inputs, chord / tan^2 forms: relative error grows with the exponent's size
        EXPECT_NEAR(ward_lobe(n, wi, wo, alpha) / w, 1.0, 2e-4);
        EXPECT_NEAR(ward_duer_lobe(n, wi, wo, alpha) / wd, 1.0, 2e-4);
        EXPECT_NEAR(blinn_phong_lobe(n, wi, wo, e) / bp, 1.0, 2e-4);
        EXPECT_NEAR(phong_lobe(mirror_direction(n, wo), wi, e) / ph, 1.0, 2e-4);
    }
    EXPECT_GT(compared, 1000);
}

TEST(BrdfLobes, AreReciprocal) {
    Rng rng(4);
    for (int i = 0; i < 20000; ++i) {
        const vec3 n = rng.direction(), wo = rng.above(n), wi = rng.above(n);
        const float alpha = i % 2 ? 0.05f : 0.3f, e = i % 2 ? 1000.0f : 10.0f;
        // H, ci + co and min / max are symmetric, so these are exact
        EXPECT_EQ(ward_lobe(n, wi, wo, alpha), ward_lobe(n, wo, wi, alpha));
        EXPECT_EQ(ward_duer_lobe(n, wi, wo, alpha), ward_duer_lobe(n, wo, wi, alpha));
        EXPECT_EQ(blinn_phong_lobe(n, wi, wo, e), blinn_phong_lobe(n, wo, wi, e));
        // mirror-vector lobe: the angle between wi and r(wo) equals that between wo and r(wi).
        // The two mirror vectors differ by rounding (~4e-7 rad); d ln(cos^e) / d angle is
        // e tan(angle), which sets the tolerance.
        const float a = phong_lobe(mirror_direction(n, wo), wi, e);
        const float b = phong_lobe(mirror_direction(n, wi), wo, e);
        const dvec3 r = glm::normalize(to_d(mirror_direction(n, wo)));
        const double tan_angle = glm::length(glm::cross(r, to_d(wi))) / glm::dot(r, to_d(wi));
        if (tan_angle > 0) {
            EXPECT_NEAR(a, b, (1e-6 + 16e-7 * e * tan_angle) * a + 1e-30);
        }
    }
}

TEST(BrdfLobes, AreZeroBelowTheHorizon) {
    Rng rng(5);
    Material m;
    m.k_s = 1.0f;
    for (int i = 0; i < 5000; ++i) {
        const vec3 n = rng.direction(), up = rng.above(n), down = -rng.above(n);
        for (auto [wi, wo] : {std::pair{up, down}, std::pair{down, up}, std::pair{down, down}}) {
            EXPECT_EQ(ward_lobe(n, wi, wo, 0.1f), 0.0f);
            EXPECT_EQ(ward_duer_lobe(n, wi, wo, 0.1f), 0.0f);
            EXPECT_EQ(blinn_phong_lobe(n, wi, wo, 100.0f), 0.0f);
            for (SpecularModel model : {SpecularModel::phong, SpecularModel::blinn_phong,
                                        SpecularModel::ward, SpecularModel::ward_duer}) {
                m.model = model;
                for (BrdfScaling s : {BrdfScaling::physical, BrdfScaling::report}) {
                    if (glm::dot(n, wi) <= 0.0f || model != SpecularModel::phong) {
                        EXPECT_EQ(specular_factor(m, s, n, wi, wo), vec3(0.0f));
                    }
                    if (glm::dot(n, wi) <= 0.0f) {
                        EXPECT_EQ(diffuse_factor(m, s, vec3(1), n, wi), vec3(0.0f));
                        EXPECT_EQ(glossy_weight(m, s, n, wi), vec3(0.0f));
                    }
                }
            }
        }
        EXPECT_EQ(pdf_ward(n, up, down, 0.1f), 0.0f) << "pdf is 0 for a viewer below";
        EXPECT_EQ(pdf_blinn_phong(n, up, down, 100.0f), 0.0f);
        EXPECT_EQ(sample_ward(n, down, 0.1f, 0.3f, 0.6f).pdf, 0.0f);
        EXPECT_EQ(sample_blinn_phong(n, down, 100.0f, 0.3f, 0.6f).weight, 0.0f);
    }
}

TEST(BrdfLobes, StayFiniteAtDegenerateAngles) {
    Rng rng(6);
    const std::vector<float> alphas = {1e-4f, 1e-3f, 0.0141f, 0.3f, 1.0f};
    const std::vector<float> exponents = {0.0f, 1.0f, 83.4f, 1040.0f, 28400.0f, 1e6f};
    const std::vector<float> tiny = {0.5f, 1e-3f, 1e-6f, 1e-9f, 1e-12f};
    for (int i = 0; i < 50; ++i) {
        const vec3 n = i == 0 ? vec3(0, 0, 1) : rng.direction();
        const vec3 t = tangent_of(n);
        std::vector<std::pair<vec3, vec3>> cases = {{n, n}};  // wi == wo == n
        const vec3 wo = rng.above(n);
        cases.push_back({mirror_direction(n, wo), wo});  // exactly at the mirror direction
        cases.push_back({wo, wo});
        for (float ci : tiny)
            for (float co : tiny) {
                // cosines down to 1e-12: mirror pair, same side, and opposite sides
                const vec3 a = glm::normalize(n * ci + t * std::sqrt(1.0f - ci * ci));
                const vec3 b = glm::normalize(n * co - t * std::sqrt(1.0f - co * co));
                cases.push_back({a, b});
                cases.push_back({a, glm::normalize(n * co + t * std::sqrt(1.0f - co * co))});
                cases.push_back({n, b});
            }
        for (auto [wi, w_o] : cases) {
            for (float alpha : alphas) {
                for (float v : {ward_lobe(n, wi, w_o, alpha), ward_duer_lobe(n, wi, w_o, alpha),
                                pdf_ward(n, wi, w_o, alpha)}) {
                    EXPECT_TRUE(finite(v) && v >= 0.0f) << v << " alpha " << alpha;
                }
            }
            for (float e : exponents) {
                for (float v :
                     {blinn_phong_lobe(n, wi, w_o, e), pdf_blinn_phong(n, wi, w_o, e),
                      phong_lobe(mirror_direction(n, w_o), wi, e), pdf_phong_lobe(n, e, wi)}) {
                    EXPECT_TRUE(finite(v) && v >= 0.0f) << v << " e " << e;
                }
            }
            Material m;
            m.k_s = 1.0f;
            m.alpha = 1e-4f;
            m.exponent = 1e6f;
            for (SpecularModel model :
                 {SpecularModel::phong, SpecularModel::glossy_phong, SpecularModel::blinn_phong,
                  SpecularModel::ward, SpecularModel::ward_duer}) {
                m.model = model;
                for (BrdfScaling s : {BrdfScaling::physical, BrdfScaling::report}) {
                    EXPECT_TRUE(finite(specular_factor(m, s, n, wi, w_o)));
                    EXPECT_TRUE(finite(diffuse_factor(m, s, vec3(1), n, wi)));
                    EXPECT_TRUE(finite(glossy_weight(m, s, n, wi)));
                }
            }
        }
    }
}

// ---- shading factors ------------------------------------------------------------------------

TEST(SpecularFactor, PhongIsTheReportsUnnormalisedClampedLobe) {
    Rng rng(7);
    Material m;
    m.model = SpecularModel::phong;
    m.k_s = 0.8f;
    m.c_s = vec3(1.0f, 0.9f, 0.5f);
    m.exponent = 50.0f;
    int positive = 0, clamped = 0;
    for (int i = 0; i < 5000; ++i) {
        const vec3 n = rng.direction(), wo = rng.above(n), wi = rng.above(n);
        const double c =
            glm::dot(glm::normalize(to_d(wi)), glm::normalize(to_d(mirror_direction(n, wo))));
        const vec3 phys = specular_factor(m, BrdfScaling::physical, n, wi, wo);
        EXPECT_EQ(phys, specular_factor(m, BrdfScaling::report, n, wi, wo));
        if (c <= -1e-6) {
            ++clamped;  // the report's code would give |c|^50 here
            EXPECT_EQ(phys, vec3(0.0f));
        } else if (c > 0.5) {
            ++positive;
            const double expected = std::pow(c, 50.0);
            const double tol = 1e-5 * (1 + std::fabs(std::log(expected)));  // float vectors
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(phys[k], m.k_s * m.c_s[k] * expected, tol * expected + 1e-30);
        }
        EXPECT_EQ(specular_factor(m, BrdfScaling::physical, vec3(2, 3, 4), n, wi, wo) / 2.0f,
                  specular_factor(m, BrdfScaling::physical, vec3(1, 1.5f, 2), n, wi, wo))
            << "the explicit c_s replaces m.c_s";
    }
    EXPECT_GT(positive, 100);
    EXPECT_GT(clamped, 100);
}

TEST(SpecularFactor, GlossyPhongHasNoHighlight) {
    Material m;
    m.model = SpecularModel::glossy_phong;
    m.k_s = 0.8f;
    const vec3 n(0, 0, 1);
    EXPECT_EQ(specular_factor(m, BrdfScaling::report, n, n, n), vec3(0.0f));
    EXPECT_EQ(specular_factor(m, BrdfScaling::physical, n, n, n), vec3(0.0f));
}

TEST(SpecularFactor, FittedLobesScaleByRhoSAndCosineInThePhysicalScaling) {
    Rng rng(8);
    Material m;
    m.k_s = 0.5f;
    m.c_s = vec3(0.204f, 0.154f, 0.0946f);
    m.alpha = 0.2f;
    m.exponent = 30.0f;
    for (int i = 0; i < 3000; ++i) {
        const vec3 n = rng.direction(), wo = rng.above(n), wi = rng.above(n);
        const float ci = glm::dot(n, wi);
        for (SpecularModel model :
             {SpecularModel::blinn_phong, SpecularModel::ward, SpecularModel::ward_duer}) {
            m.model = model;
            const float s = model == SpecularModel::ward ? ward_lobe(n, wi, wo, m.alpha)
                            : model == SpecularModel::ward_duer
                                ? ward_duer_lobe(n, wi, wo, m.alpha)
                                : blinn_phong_lobe(n, wi, wo, m.exponent);
            const vec3 report = specular_factor(m, BrdfScaling::report, n, wi, wo);
            const vec3 phys = specular_factor(m, BrdfScaling::physical, n, wi, wo);
            for (int k = 0; k < 3; ++k) {
                EXPECT_FLOAT_EQ(report[k], m.k_s * m.c_s[k] * s);
                EXPECT_FLOAT_EQ(phys[k], m.k_s * m.c_s[k] * s * ci);
            }
        }
    }
}

TEST(DiffuseFactor, HasNoOneOverPiExceptForPhysicalFittedMaterials) {
    Material m;
    m.k_d = 0.2f;
    const vec3 n(0, 0, 1), wi = glm::normalize(vec3(1, 0, 1)), c_d(1, 0.8f, 0.6f);
    const float ci = glm::dot(n, wi);
    for (SpecularModel model : {SpecularModel::phong, SpecularModel::glossy_phong}) {
        m.model = model;
        for (BrdfScaling s : {BrdfScaling::physical, BrdfScaling::report})
            EXPECT_EQ(diffuse_factor(m, s, c_d, n, wi), c_d * (0.2f * ci));
    }
    for (SpecularModel model :
         {SpecularModel::blinn_phong, SpecularModel::ward, SpecularModel::ward_duer}) {
        m.model = model;
        EXPECT_EQ(diffuse_factor(m, BrdfScaling::report, c_d, n, wi), c_d * (0.2f * ci));
        const vec3 phys = diffuse_factor(m, BrdfScaling::physical, c_d, n, wi);
        for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(phys[k], c_d[k] * 0.2f * ci / float(pi_d));
    }
    EXPECT_EQ(diffuse_factor(m, BrdfScaling::report, c_d, n, -wi), vec3(0.0f));
}

TEST(GlossyWeight, IsKsCsInTheReportAndModifiedPhongWhenPhysical) {
    Material m;
    m.model = SpecularModel::glossy_phong;
    m.k_s = 0.8f;
    m.c_s = vec3(1, 0.9f, 0.9f);
    m.exponent = 1000.0f;
    const vec3 n(0, 0, 1), wi = glm::normalize(vec3(0.3f, 0, 1));
    const float ci = glm::dot(n, wi);
    EXPECT_EQ(glossy_weight(m, BrdfScaling::report, n, wi), m.k_s * m.c_s);
    const vec3 phys = glossy_weight(m, BrdfScaling::physical, n, wi);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(phys[k], m.k_s * m.c_s[k] * 1002.0f / 1001.0f * ci);
    EXPECT_EQ(glossy_weight(m, BrdfScaling::report, n, -wi), vec3(0.0f));
    EXPECT_EQ(glossy_weight(m, BrdfScaling::physical, n, -wi), vec3(0.0f));
}

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

int bin_of(vec3 w, vec3 n, int nz, int nphi) {
    vec3 t, b;
    orthonormal_basis(n, t, b);
    const double z = std::clamp(double(glm::dot(w, n)), -1.0, 1.0);
    double phi = std::atan2(double(glm::dot(w, b)), double(glm::dot(w, t)));
    if (phi < 0) phi += 2 * pi_d;
    const int iz = std::min(nz - 1, int((z + 1) / 2 * nz));
    const int ip = std::min(nphi - 1, int(phi / (2 * pi_d) * nphi));
    return iz * nphi + ip;
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

// ---- Fresnel and optics ---------------------------------------------------------------------

TEST(Fresnel, IsFourPercentAtNormalIncidenceOnGlass) {
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f, 1.0f), 0.04f, 1e-7f);
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-7f);
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-7f);
}

TEST(Fresnel, ReachesOneAtGrazingIncidence) {
    for (float eta : {1.0001f, 1.33f, 1.5f, 4.0f}) {
        EXPECT_EQ(fresnel_dielectric(0.0f, eta), 1.0f);
        EXPECT_GT(fresnel_dielectric(1e-7f, eta), 0.99f);  // eta 1.0001: 0.972 at 1e-4 already
        if (eta > 2.0f) continue;  // high indices dip below R(0) near Brewster's angle
        float previous = 1.0f;
        for (float c = 1e-7f; c <= 1.0f; c *= 1.5f) {  // decreasing towards normal incidence
            const float r = fresnel_dielectric(c, eta);
            EXPECT_LE(r, previous + 1e-6f) << eta << " " << c;
            previous = r;
        }
    }
}

TEST(Fresnel, IsZeroAndRefractsStraightThroughForIndexMatchedMedia) {
    Rng rng(700);
    for (int i = 0; i < 1000; ++i) {
        const vec3 n = rng.direction(), d = -rng.above(n);
        vec3 t;
        float cos_t = -1.0f;
        ASSERT_TRUE(refract_direction(d, n, 1.0f, t, cos_t));
        EXPECT_EQ(t, d);
        EXPECT_EQ(cos_t, std::clamp(-glm::dot(d, n), 0.0f, 1.0f));
        EXPECT_EQ(fresnel_dielectric(cos_t, 1.0f, cos_t), 0.0f);
        EXPECT_EQ(fresnel_dielectric(cos_t, 1.0f), 0.0f);
    }
}

TEST(Fresnel, DetectsTotalInternalReflectionAtTheCriticalAngle) {
    const vec3 n(0, 0, 1);
    for (double index : {1.0001, 1.33, 1.5, 4.0}) {
        const float eta = float(1.0 / index);  // leaving the dense medium
        const double critical = std::asin(double(eta));
        for (double delta : {-1e-4, -1e-5, 1e-5, 1e-4}) {
            const double theta = critical + delta;
            const vec3 d(float(std::sin(theta)), 0.0f, float(-std::cos(theta)));
            vec3 t;
            float cos_t;
            const bool refracts = refract_direction(d, n, eta, t, cos_t);
            EXPECT_EQ(refracts, delta < 0) << index << " " << delta;
            EXPECT_TRUE(finite(t));
            const float r = fresnel_dielectric(-d.z, eta);
            if (refracts) {
                EXPECT_GT(r, 0.5f) << "R rises towards 1 near the critical angle";
                EXPECT_LT(r, 1.0f);
                EXPECT_GT(cos_t, 0.0f);
            } else {
                EXPECT_EQ(r, 1.0f);
                EXPECT_EQ(cos_t, 0.0f);
                EXPECT_EQ(t, reflect_direction(d, n));
            }
        }
    }
}

TEST(Fresnel, ConservesEnergyAndIsSymmetricInTheTwoMedia) {
    // T from the transmission amplitudes (Stokes): t_s = 2 ci / (ci + eta ct),
    // t_p = 2 ci / (eta ci + ct), power T = eta ct / ci (t_s^2 + t_p^2) / 2; R + T must be 1.
    const float one_up = std::nextafter(1.0f, 2.0f);
    for (float eta : {1.0f, 1.0001f, 1.5f, 4.0f, 1.0f / 1.5f, 0.25f}) {
        for (float ci : {0.0f, 1e-7f, 0.01f, 0.1f, 0.5f, 0.9f, 0.999f, 1.0f, one_up}) {
            const float r2 = fresnel_dielectric(ci, eta);
            EXPECT_TRUE(r2 >= 0.0f && r2 <= 1.0f) << eta << " " << ci;
            const double c = std::min(double(ci), 1.0);
            const double sin2_t = (1 - c * c) / (double(eta) * eta);
            if (sin2_t >= 1 || c == 0) continue;
            const double ct = std::sqrt(1 - sin2_t);
            const float r = fresnel_dielectric(ci, eta, float(ct));
            EXPECT_NEAR(r, r2, 1e-6f);
            const double ts = 2 * c / (c + eta * ct), tp = 2 * c / (eta * c + ct);
            const double t = eta * ct / c * (ts * ts + tp * tp) / 2;
            EXPECT_NEAR(r + t, 1.0, 2e-6) << eta << " " << ci;
            // the same interface seen from the other side
            EXPECT_NEAR(fresnel_dielectric(float(ct), 1.0f / eta, ci), r, 2e-6f);
        }
    }
}

TEST(Fresnel, SchlickHitsItsEndpointsAndAcceptsLargeR0) {
    EXPECT_EQ(schlick(0.04f, 1.0f), 0.04f);
    EXPECT_EQ(schlick(0.04f, 0.0f), 1.0f);
    EXPECT_EQ(schlick(0.04f, -0.5f), 1.0f) << "cos clamped to 0";
    EXPECT_EQ(schlick(0.04f, 1.5f), 0.04f) << "cos clamped to 1";
    EXPECT_EQ(schlick(0.04f, std::numeric_limits<float>::quiet_NaN()), 1.0f);
    EXPECT_NEAR(schlick(0.04f, 0.5f), 0.04f + 0.96f / 32.0f, 1e-7f);
    EXPECT_EQ(schlick(1.5f, 1.0f), 1.5f) << "the fractal's r0 > 1";
    EXPECT_NEAR(schlick(1.5f, 0.5f), 1.5f - 0.5f / 32.0f, 1e-6f);
}

TEST(RefractDirection, ObeysSnellsLaw) {
    Rng rng(701);
    for (int i = 0; i < 5000; ++i) {
        const vec3 n = rng.direction(), d = -rng.above(n);
        const float eta = i % 2 ? 1.5f : 1.0f / 1.5f;
        vec3 t;
        float cos_t;
        if (!refract_direction(d, n, eta, t, cos_t)) continue;
        const double ci = -glm::dot(d, n);
        const double sin_i = std::sqrt(std::max(0.0, 1 - ci * ci));
        EXPECT_NEAR(glm::length(t), 1.0f, 2e-6f);
        EXPECT_NEAR(-glm::dot(t, n), cos_t, 2e-6f) << "t continues below the surface";
        EXPECT_NEAR(std::sqrt(std::max(0.0, 1.0 - double(cos_t) * cos_t)), sin_i / eta, 1e-5);
        EXPECT_NEAR(glm::dot(glm::cross(d, n), t), 0.0f, 2e-6f) << "coplanar with d and n";
    }
}

TEST(ReflectDirection, MirrorsAboutTheNormal) {
    const vec3 n(0, 0, 1);
    EXPECT_EQ(reflect_direction(vec3(0.6f, 0, -0.8f), n), vec3(0.6f, 0, 0.8f));
    EXPECT_EQ(reflect_direction(vec3(0, 0, -1), n), vec3(0, 0, 1));
}

TEST(BeerTransmittance, FollowsThePowerLawAndItsLimits) {
    EXPECT_EQ(beer_transmittance(vec3(0.0f), 1.0f), vec3(0.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.0f), 1e-9f), vec3(0.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.0f), 0.0f), vec3(1.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.5f), 0.0f), vec3(1.0f));
    EXPECT_EQ(beer_transmittance(vec3(1.0f), inf_f), vec3(1.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.999f), inf_f), vec3(0.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.5f, 1.0f, 0.0f), inf_f), vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(beer_transmittance(vec3(0.5f), nan_f), vec3(1.0f));
    const std::vector<float> filters = {0.0f, 1e-9f, 0.1f, 0.5f, 0.999f, 1.0f};
    const std::vector<float> distances = {0.0f, 1e-9f, 0.5f, 1.0f, 3.0f, 1e3f, inf_f};
    for (float f : filters) {
        float previous = 1.0f;
        for (float d : distances) {
            const float t = beer_transmittance(vec3(f), d).x;
            EXPECT_TRUE(t >= 0.0f && t <= 1.0f) << f << " " << d;
            EXPECT_LE(t, previous) << "monotone in distance";
            previous = t;
            if (f > 0 && std::isfinite(d)) {
                const double expected = std::pow(double(f), double(d));
                // exp(d log f): a log error of 1 ulp grows to |ln T| ulps
                const double tol = 2.4e-7 * (2 + std::fabs(std::log(std::max(expected, 1e-300))));
                EXPECT_NEAR(t, expected, tol * expected + 1e-37) << f << " " << d;
            }
        }
    }
}

}  // namespace
}  // namespace raylane
