// Tests of shade/brdf_scalar.h: frames, the lobe formulas (against textbook formulas, reciprocity,
// below the horizon, degenerate angles) and the shading factors. Albedo: brdf_albedo_test.cpp;
// sampling: brdf_sampling_test.cpp; the packet twin: brdf_packet_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "shade/brdf_scalar.h"
#include "shade/optics_scalar.h"
#include "support/direction_sampling.h"
#include "support/float_values.h"

namespace raylane {
namespace {

using namespace test;

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

}  // namespace
}  // namespace raylane
