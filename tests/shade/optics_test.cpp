// Tests of shade/optics_scalar.h: Fresnel (dielectric and Schlick), refraction and reflection
// directions, Beer's law. The packet twin: brdf_packet_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "shade/optics_scalar.h"
#include "support/direction_sampling.h"
#include "support/float_values.h"

namespace raylane {
namespace {

using namespace test;

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
