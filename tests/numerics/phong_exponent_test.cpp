// Numerical stability suite, shading (numerics.md §11): the Phong lobe around
// the mirror direction and the Blinn-Phong half-vector lobe of shade/brdf_scalar.h and
// brdf_packet.h at exponents 1e3 .. 1e6, the cases tests/shade/brdf_*_test.cpp leave out:
// chi-square in lobe coordinates scaled by sqrt(e), the pdf's integral, finite weights at
// extreme random numbers, the lobe near its peak, directional albedo, and a rendered glossy
// sphere at e = 1e6 against the mirror. Every check also runs through the packet path.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "render/camera_rays.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "shade/brdf_packet.h"
#include "shade/brdf_scalar.h"
#include "simd/lanes.h"
#include "support/chi_square.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

#ifdef RAYLANE_SANITIZED
constexpr int sample_scale = 10;  // sanitizers: 10x fewer samples, the same assertions
#else
constexpr int sample_scale = 1;
#endif

using chi_square::chi2_p_value;
using chi_square::Frame;
using chi_square::frame_of;
using chi_square::gamma_q;
using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;

const float exponents[] = {1e3f, 1e4f, 1e5f, 1e6f};

// ---- statistics -----------------------------------------------------------------------------

TEST(PhongExtremeExponent, ChiSquarePValuesOfTheHarnessAreRight) {
    // the p-value routine against known quantiles: chi2(10 dof) = 23.209 at p = 0.01, and
    // chi2(255) = 310.457 at p = 0.01
    EXPECT_NEAR(gamma_q(5.0, 23.209 / 2), 0.01, 1e-4);
    EXPECT_NEAR(gamma_q(127.5, 310.457 / 2), 0.01, 2e-4);
    EXPECT_NEAR(gamma_q(1.0, 2.0), std::exp(-2.0), 1e-12);
}

// ---- lobes in local coordinates -------------------------------------------------------------

enum class Lobe { phong, blinn_phong };

/// One lobe: Phong around `axis`, or Blinn-Phong around normal `axis` seen from wo.
struct LobeCase {
    Lobe lobe = Lobe::phong;
    float e = 1e3f;
    vec3 axis{0.0f, 0.0f, 1.0f};
    vec3 wo{0.0f, 0.0f, 1.0f};
};

std::string name(const LobeCase& c) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%s e = %g", c.lobe == Lobe::phong ? "Phong" : "Blinn-Phong",
                  double(c.e));
    return buf;
}

/// Lobe coordinates of a sampled direction, scaled by sqrt(e) so the lobe is a unit Gaussian at
/// every exponent: the sine components of w around the axis (Phong), the tangent components of
/// the half vector around n (Blinn-Phong).
dvec2 local_of(const LobeCase& c, const Frame& f, vec3 w) {
    const double s = std::sqrt(double(c.e));
    if (c.lobe == Lobe::phong) {
        const dvec3 wd = glm::normalize(dvec3(w));
        return dvec2(glm::dot(wd, f.t), glm::dot(wd, f.b)) * s;
    }
    const dvec3 h = glm::normalize(dvec3(w) + dvec3(c.wo));
    return dvec2(glm::dot(h, f.t), glm::dot(h, f.b)) / glm::dot(h, f.n) * s;
}

/// The direction at lobe coordinates (x, y) (rounded to float) and the Jacobian
/// d(solid angle of the sampled direction) / dx dy.
struct LocalPoint {
    vec3 w;
    double jacobian = 0;
};
LocalPoint point_at(const LobeCase& c, const Frame& f, dvec2 xy) {
    const double e = c.e, r2 = glm::dot(xy, xy);
    if (c.lobe == Lobe::phong) {
        const double cos_a = std::sqrt(std::max(0.0, 1 - r2 / e));
        const dvec3 w = (f.t * xy.x + f.b * xy.y) / std::sqrt(e) + f.n * cos_a;
        return {vec3(w), 1.0 / (e * cos_a)};
    }
    const dvec3 h = glm::normalize((f.t * xy.x + f.b * xy.y) / std::sqrt(e) + f.n);
    const dvec3 wo(c.wo);
    const dvec3 wi = h * (2 * glm::dot(wo, h)) - wo;
    return {vec3(wi), 4 * glm::dot(wo, h) / (e * std::pow(1 + r2 / e, 1.5))};
}

/// The production pdf of the lobe at `ws`: the scalar functions when W == 0, else the packet ones.
template <int W>
std::vector<double> pdfs(const LobeCase& c, const std::vector<vec3>& ws) {
    std::vector<double> out(ws.size());
    if constexpr (W == 0) {
        for (size_t i = 0; i < ws.size(); ++i)
            out[i] = c.lobe == Lobe::phong ? pdf_phong_lobe(c.axis, c.e, ws[i])
                                           : pdf_blinn_phong(c.axis, ws[i], c.wo, c.e);
    } else {
        const Vec3<W> axis = make_vec3<W>(c.axis.x, c.axis.y, c.axis.z);
        const Vec3<W> wo = make_vec3<W>(c.wo.x, c.wo.y, c.wo.z);
        for (size_t i = 0; i < ws.size(); i += W) {
            float x[W], y[W], z[W];
            for (int k = 0; k < W; ++k) {
                const vec3 v = ws[std::min(i + size_t(k), ws.size() - 1)];
                x[k] = v.x, y[k] = v.y, z[k] = v.z;
            }
            const Vec3<W> w = load_vec3<W>(x, y, z);
            const vfloat<W> p = c.lobe == Lobe::phong ? pdf_phong_lobe(axis, c.e, w)
                                                      : pdf_blinn_phong(axis, w, wo, c.e);
            for (int k = 0; k < W && i + size_t(k) < ws.size(); ++k) out[i + size_t(k)] = get(p, k);
        }
    }
    return out;
}

/// Samples of the lobe for the random numbers (u1, u2): scalar when W == 0, else packets.
template <int W>
std::vector<vec3> samples(const LobeCase& c, const std::vector<float>& u1,
                          const std::vector<float>& u2) {
    std::vector<vec3> out(u1.size());
    if constexpr (W == 0) {
        for (size_t i = 0; i < u1.size(); ++i)
            out[i] = c.lobe == Lobe::phong ? sample_phong_lobe(c.axis, c.e, u1[i], u2[i])
                                           : sample_blinn_phong(c.axis, c.wo, c.e, u1[i], u2[i]).wi;
    } else {
        const Vec3<W> axis = make_vec3<W>(c.axis.x, c.axis.y, c.axis.z);
        const Vec3<W> wo = make_vec3<W>(c.wo.x, c.wo.y, c.wo.z);
        for (size_t i = 0; i + W <= u1.size(); i += W) {
            const vfloat<W> a = load<W>(u1.data() + i), b = load<W>(u2.data() + i);
            const Vec3<W> w = c.lobe == Lobe::phong ? sample_phong_lobe<W>(axis, c.e, a, b)
                                                    : sample_blinn_phong<W>(axis, wo, c.e, a, b).wi;
            for (int k = 0; k < W; ++k)
                out[i + size_t(k)] = vec3(get(w.x, k), get(w.y, k), get(w.z, k));
        }
    }
    return out;
}

/// The lobes under test: random axes, one exactly -z and one 1e-8 off it (the frame's weak
/// spot), Blinn-Phong seen at 40 degrees.
std::vector<LobeCase> lobe_cases() {
    std::vector<LobeCase> cases;
    std::mt19937_64 rng(11);
    std::normal_distribution<float> g;
    int i = 0;
    for (float e : exponents) {
        for (Lobe lobe : {Lobe::phong, Lobe::blinn_phong}) {
            LobeCase c;
            c.lobe = lobe;
            c.e = e;
            c.axis = i % 4 == 1   ? vec3(0, 0, -1)
                     : i % 4 == 3 ? glm::normalize(vec3(1e-8f, 0, -1))
                                  : glm::normalize(vec3(g(rng), g(rng), g(rng)));
            const Frame f = frame_of(c.axis);
            c.wo = vec3(f.n * std::cos(40 * pi_d / 180) + f.t * std::sin(40 * pi_d / 180));
            cases.push_back(c);
            ++i;
        }
    }
    return cases;
}

/// Lobe-coordinate grid over [-8, 8]^2 with cells of 1/16: the pdf's integral over it (the mass
/// beyond is below e^-30), and the mass of each of 16 x 16 chi-square bins over [-4, 4]^2 plus
/// one bin for everything outside.
struct Integrated {
    double total = 0;
    std::vector<double> bins;  // 256 inner bins, then the outer one
};

template <int W>
Integrated integrate(const LobeCase& c) {
    const Frame f = frame_of(c.axis);
    const int n = 256;
    const double h = 16.0 / n;
    std::vector<vec3> ws;
    std::vector<double> jac;
    std::vector<int> bin;
    for (int iy = 0; iy < n; ++iy) {
        for (int ix = 0; ix < n; ++ix) {
            const dvec2 xy(-8 + (ix + 0.5) * h, -8 + (iy + 0.5) * h);
            const LocalPoint p = point_at(c, f, xy);
            ws.push_back(p.w);
            jac.push_back(p.jacobian * h * h);
            const bool inner = std::fabs(xy.x) < 4 && std::fabs(xy.y) < 4;
            bin.push_back(inner ? int((xy.y + 4) * 2) * 16 + int((xy.x + 4) * 2) : 256);
        }
    }
    const std::vector<double> p = pdfs<W>(c, ws);
    Integrated out;
    out.bins.assign(257, 0.0);
    for (size_t i = 0; i < p.size(); ++i) {
        out.total += p[i] * jac[i];
        out.bins[size_t(bin[i])] += p[i] * jac[i];
    }
    return out;
}

int phong_bin_of(dvec2 xy) {
    if (!(std::fabs(xy.x) < 4 && std::fabs(xy.y) < 4)) return 256;
    return int((xy.y + 4) * 2) * 16 + int((xy.x + 4) * 2);
}

/// Chi-square of the sampler against the integrated production pdf, and the pdf's integral.
template <int W>
void check_sampler_against_pdf(const std::string& path) {
    // the same samples in every build: a chi-square test on a tenth of them would be a different
    // test, with fewer usable bins (the sanitizer build shrinks only the albedo estimates)
    const int count = 200000;
    for (const LobeCase& c : lobe_cases()) {
        const std::string what = path + " " + name(c);
        const Integrated in = integrate<W>(c);
        EXPECT_NEAR(in.total, 1.0, 1e-3) << what << ": the pdf integrates to 1";
        std::mt19937_64 rng(uint64_t(c.e) + (c.lobe == Lobe::phong ? 1 : 2));
        std::vector<float> u1(static_cast<size_t>(count)), u2(static_cast<size_t>(count));
        for (int i = 0; i < count; ++i) {
            u1[size_t(i)] = float(rng() >> 40) * 0x1.0p-24f;
            u2[size_t(i)] = float(rng() >> 40) * 0x1.0p-24f;
        }
        const std::vector<vec3> ws = samples<W>(c, u1, u2);
        const Frame f = frame_of(c.axis);
        std::vector<int> counts(257, 0);
        for (const vec3& w : ws) {
            ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z)) << what;
            ++counts[size_t(phong_bin_of(local_of(c, f, w)))];
        }
        std::vector<double> expected(257);
        for (size_t i = 0; i < 257; ++i) expected[i] = in.bins[i] * count;
        int bins = 0;
        const double p = chi2_p_value(expected, counts, &bins);
        EXPECT_GT(p, 0.01) << what << ": chi-square over " << bins << " bins";
        EXPECT_GT(bins, 150) << what;
        std::printf("%s: integral of pdf - 1 = %.2e, chi-square p = %.3f (%d bins)\n", what.c_str(),
                    in.total - 1.0, p, bins);
    }
}

TEST(PhongExtremeExponent, SamplersFitTheirPdfsInLobeCoordinates) {
    check_sampler_against_pdf<0>("scalar");
}

// ---- extreme random numbers -----------------------------------------------------------------

/// A shading configuration for one lane: normal n, viewer wo at 30 degrees.
struct Extreme {
    float e, u1, u2;
};
std::vector<Extreme> extreme_cases() {
    std::vector<Extreme> out;
    for (float e : {1e3f, 1e4f, 1e5f, 1e6f, 1e7f})
        for (float u1 : extreme_u)
            for (float u2 : extreme_u) out.push_back({e, u1, u2});
    return out;
}

TEST(PhongExtremeExponent, WeightsStayFiniteAtExtremeRandomNumbers) {
    const vec3 n = glm::normalize(vec3(0.3f, -0.2f, -0.9f));
    const Frame f = frame_of(n);
    const vec3 wo(f.n * std::cos(0.5236) + f.t * std::sin(0.5236));
    const vec3 r = mirror_direction(n, wo);
    Material m;
    m.model = SpecularModel::glossy_phong;
    m.k_s = 1.0f;
    m.c_s = vec3(1.0f);
    for (const Extreme& x : extreme_cases()) {
        const std::string at = "e " + std::to_string(x.e) + " u1 " + std::to_string(x.u1) + " u2 " +
                               std::to_string(x.u2);
        // Phong around the mirror direction
        const vec3 w = sample_phong_lobe(r, x.e, x.u1, x.u2);
        ASSERT_TRUE(finite3(w)) << at;
        EXPECT_NEAR(glm::length(w), 1.0f, 1e-6f) << at;
        const double angle =
            std::atan2(glm::length(glm::cross(dvec3(w), dvec3(r))), glm::dot(dvec3(w), dvec3(r)));
        const double expected = std::acos(std::pow(1.0 - double(x.u2), 1.0 / (double(x.e) + 1)));
        EXPECT_NEAR(angle, expected, 2e-7 + 1e-4 * expected) << at;
        const float pdf = pdf_phong_lobe(r, x.e, w);
        ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f) << at;
        if (x.u2 < 1.0f) {
            // a drawn direction has the density the sampler meant: (e + 1)/(2 pi) (1 -
            // u2)^(e/(e+1))
            const double want =
                (x.e + 1.0) / (2 * pi_d) * std::pow(1.0 - double(x.u2), x.e / (x.e + 1.0));
            EXPECT_NEAR(pdf, want, 2e-3 * want) << at;
            EXPECT_GT(pdf, 0.0f) << at << ": f / pdf would be 0 / 0";
        }
        m.exponent = x.e;
        for (BrdfScaling s : {BrdfScaling::physical, BrdfScaling::report}) {
            const vec3 gw = glossy_weight(m, s, n, w);
            EXPECT_TRUE(finite3(gw) && gw.x >= 0.0f) << at;
            EXPECT_LE(gw.x, (x.e + 2.0f) / (x.e + 1.0f)) << at;
        }
        // Blinn-Phong half-vector sampling
        const LobeSample bs = sample_blinn_phong(n, wo, x.e, x.u1, x.u2);
        ASSERT_TRUE(finite3(bs.wi)) << at;
        EXPECT_TRUE(std::isfinite(bs.pdf) && bs.pdf >= 0.0f) << at;
        EXPECT_TRUE(std::isfinite(bs.weight) && bs.weight >= 0.0f) << at;
        EXPECT_LE(bs.weight, 4.0f * (x.e + 2.0f) / (x.e + 1.0f)) << at;
        const float ci = glm::dot(n, bs.wi);
        if (x.u2 < 1.0f && ci > 0.0f) {
            EXPECT_GT(bs.pdf, 0.0f) << at;
            const double f_ci_over_pdf = double(blinn_phong_lobe(n, bs.wi, wo, x.e)) * ci /
                                         pdf_blinn_phong(n, bs.wi, wo, x.e);
            EXPECT_NEAR(bs.weight, f_ci_over_pdf, 1e-3 * f_ci_over_pdf) << at;
        }
    }
}

/// Near the peak: the chord form keeps the lobe's top round where 1 - dot() rounds to 0 (below
/// about 2.4e-4 rad); compared with exp(e ln cos) of the angle between the float vectors.
TEST(PhongExtremeExponent, LobesAreResolvedAtTheirPeak) {
    const vec3 axis = glm::normalize(vec3(0.2f, 0.9f, -0.4f));
    const Frame f = frame_of(axis);
    double worst_chord = 0, worst_naive = 0;
    for (float e : {1e4f, 1e5f, 1e6f}) {
        for (double theta : {1e-6, 1e-5, 3e-5, 1e-4, 2.5e-4, 1e-3, 2e-3}) {
            const vec3 w = glm::normalize(vec3(f.n * std::cos(theta) + f.t * std::sin(theta)));
            const double a = std::atan2(glm::length(glm::cross(dvec3(w), dvec3(axis))),
                                        glm::dot(dvec3(w), dvec3(axis)));
            const double want = std::exp(double(e) * std::log(std::cos(a)));
            const float got = phong_lobe(axis, w, e);
            EXPECT_NEAR(got, want, 1e-4 * want + 1e-30) << "e " << e << " theta " << theta;
            worst_chord = std::max(worst_chord, std::fabs(got - want) / want);
            worst_naive =
                std::max(worst_naive, std::fabs(std::pow(glm::dot(axis, w), e) - want) / want);
            // Blinn-Phong: the half vector at theta from n
            const vec3 wo(f.n * std::cos(0.3) + f.t * std::sin(0.3));
            const dvec3 h = glm::normalize(f.n * std::cos(theta) + f.b * std::sin(theta));
            const vec3 wi(h * (2 * glm::dot(dvec3(wo), h)) - dvec3(wo));
            const dvec3 hh = glm::normalize(dvec3(wi) + dvec3(wo));
            const double th =
                std::atan2(glm::length(glm::cross(hh, dvec3(axis))), glm::dot(hh, dvec3(axis)));
            const double bp = (e + 2.0) / (2 * pi_d) * std::exp(double(e) * std::log(std::cos(th)));
            EXPECT_NEAR(blinn_phong_lobe(axis, wi, wo, e), bp, 1e-3 * bp + 1e-30)
                << "e " << e << " theta " << theta;
        }
    }
    std::printf("peak of the Phong lobe: max relative error %.2e (pow(dot, e) would give %.2e)\n",
                worst_chord, worst_naive);
}

// ---- directional albedo ---------------------------------------------------------------------

struct Albedo {
    double mean = 0, se = 0;
};

/// Mean closed-form sample weight per unit k_s c_s (modified Phong, physical) or rho_s (Ngan
/// Blinn-Phong) at viewing angle theta_o; below-surface samples count with weight 0.
template <int W>
Albedo albedo(Lobe lobe, float e, double theta_deg, int count, uint64_t seed) {
    const vec3 n = glm::normalize(vec3(-0.3f, 0.5f, 0.8f));
    const Frame f = frame_of(n);
    const double th = theta_deg * pi_d / 180;
    const vec3 wo(f.n * std::cos(th) + f.t * std::sin(th));
    std::mt19937_64 rng(seed);
    std::vector<float> u1(static_cast<size_t>(count)), u2(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        u1[size_t(i)] = float(rng() >> 40) * 0x1.0p-24f;
        u2[size_t(i)] = float(rng() >> 40) * 0x1.0p-24f;
    }
    Material m;
    m.model = SpecularModel::glossy_phong;
    m.k_s = 1.0f;
    m.c_s = vec3(1.0f);
    m.exponent = e;
    std::vector<double> w(static_cast<size_t>(count));
    if constexpr (W == 0) {
        for (size_t i = 0; i < w.size(); ++i) {
            if (lobe == Lobe::phong) {
                const vec3 wi = sample_phong_lobe(mirror_direction(n, wo), e, u1[i], u2[i]);
                w[i] = glossy_weight(m, BrdfScaling::physical, n, wi).x;
            } else {
                w[i] = sample_blinn_phong(n, wo, e, u1[i], u2[i]).weight;
            }
        }
    } else {
        const Vec3<W> nn = make_vec3<W>(n.x, n.y, n.z), wwo = make_vec3<W>(wo.x, wo.y, wo.z);
        for (size_t i = 0; i + W <= w.size(); i += W) {
            const vfloat<W> a = load<W>(u1.data() + i), b = load<W>(u2.data() + i);
            vfloat<W> v;
            if (lobe == Lobe::phong) {
                const Vec3<W> wi = sample_phong_lobe<W>(mirror_direction(nn, wwo), e, a, b);
                v = glossy_weight<W>(m, BrdfScaling::physical, nn, wi).x;
            } else {
                v = sample_blinn_phong<W>(nn, wwo, e, a, b).weight;
            }
            for (int k = 0; k < W; ++k) w[i + size_t(k)] = get(v, k);
        }
    }
    double s = 0, s2 = 0;
    for (double v : w) {
        EXPECT_TRUE(std::isfinite(v) && v >= 0);
        s += v, s2 += v * v;
    }
    const double mean = s / count;
    return {mean, std::sqrt(std::max(0.0, s2 / count - mean * mean) / count)};
}

/// Modified Phong: albedo <= 1, exactly 1 at normal incidence (brdf-reference.md §6), and
/// cos(theta_o) in the narrow-lobe limit. Ngan's Blinn-Phong lobe (per unit rho_s, no
/// 1 / (4 ci co)): 4e / (e + 4) at normal incidence and 4 cos^2(theta_o) in the limit, so a
/// material stays at or below albedo 1 when rho_s <= 1/4.
template <int W>
void check_albedo(const std::string& path) {
    const int count = 60000 / sample_scale;
    uint64_t seed = 900;
    for (float e : {1e3f, 1e5f, 1e6f}) {
        for (double theta : {0.0, 30.0, 60.0, 80.0}) {
            const double c = std::cos(theta * pi_d / 180);
            const std::string at =
                path + " e " + std::to_string(e) + " at " + std::to_string(int(theta)) + " degrees";
            const Albedo ph = albedo<W>(Lobe::phong, e, theta, count, ++seed);
            EXPECT_LE(ph.mean, 1.0 + 4 * ph.se) << at;
            EXPECT_NEAR(ph.mean, theta == 0.0 ? 1.0 : c, 4 * ph.se + 2e-3) << at << " Phong";
            const Albedo bp = albedo<W>(Lobe::blinn_phong, e, theta, count, ++seed);
            // 4 cos^2 is the e -> infinity limit (O(10 / e) below it), checked from e = 1e5
            if (theta == 0.0 || e >= 1e5f) {
                const double bp_ref = theta == 0.0 ? 4.0 * e / (e + 4.0) : 4 * c * c;
                EXPECT_NEAR(bp.mean, bp_ref, 4 * bp.se + 2e-3) << at << " Blinn-Phong";
            }
            EXPECT_LE(bp.mean, 4.0 + 4 * bp.se) << at;
        }
    }
}

TEST(PhongExtremeExponent, DirectionalAlbedoStaysBounded) { check_albedo<0>("scalar"); }

// ---- rendered: glossy at e = 1e6 is the mirror ------------------------------------------------

/// A sphere in a smooth environment (bilinear 16 x 8, varying with latitude only, so that it is
/// smooth at the poles too): glossy Phong at e = 1e6 with k_s c_s = 1, or a perfect
/// angle-independent mirror.
SceneData glossy_sphere(bool mirror, BrdfScaling scaling) {
    SceneData s;
    s.camera.position = vec3(0.0f, 0.0f, -4.0f);
    s.camera.look_at = vec3(0.0f);
    s.camera.fov_deg = 34.0f;
    s.camera.width = 25;
    s.camera.height = 25;
    s.shading.brdf = scaling;
    Texture env;
    env.width = 16, env.height = 8;
    for (int y = 0; y < env.height; ++y)
        for (int x = 0; x < env.width; ++x)
            for (float v : {0.2f + 0.05f * float(y), 0.3f + 0.08f * float(y), 0.5f})
                env.texels.push_back(v);
    s.textures.push_back(env);
    s.environment = 0;
    Material m;
    m.k_d = 0.0f;
    m.c_s = vec3(1.0f);
    if (mirror) {
        m.reflection = 1.0f;
        m.fresnel = false;
    } else {
        m.model = SpecularModel::glossy_phong;
        m.k_s = 1.0f;
        m.exponent = 1e6f;
        m.glossy_samples = 8;
    }
    s.materials.push_back(m);
    s.spheres.push_back(Sphere{vec3(0.0f), 1.0f});
    s.objects.push_back(Object{});
    return s;
}

/// cos(theta_o) at each pixel's hit on the unit sphere (0 for pixels that miss).
std::vector<double> view_cosines(const SceneData& s) {
    const CameraFrame frame = make_camera_frame(s.camera);
    std::vector<double> out;
    for (int y = 0; y < s.camera.height; ++y) {
        for (int x = 0; x < s.camera.width; ++x) {
            const Ray ray = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const dvec3 o(ray.org), d = glm::normalize(dvec3(ray.dir));
            const double b = glm::dot(o, d), disc = b * b - (glm::dot(o, o) - 1.0);
            if (disc <= 0) {
                out.push_back(0.0);
                continue;
            }
            const dvec3 p = o + d * (-b - std::sqrt(disc));
            out.push_back(-glm::dot(p, d));
        }
    }
    return out;
}

/// The report-scaled glossy sphere equals the mirror (the lobe is 1e-3 rad wide); the
/// physically scaled one equals the mirror times cos(theta_o) (modified Phong's albedo).
/// Silhouette pixels (cos < 0.05), where part of the lobe dips below the surface, are left out.
template <class Render>
void check_glossy_is_mirror(Render render, const std::string& path) {
    const SceneData mirror = glossy_sphere(true, BrdfScaling::physical);
    const Accel accel = build_accel(mirror, BuildParams{});
    const RenderResult ref = render(mirror, accel);
    const std::vector<double> cosines = view_cosines(mirror);
    for (BrdfScaling scaling : {BrdfScaling::report, BrdfScaling::physical}) {
        const RenderResult g = render(glossy_sphere(false, scaling), accel);
        EXPECT_EQ(g.stats.bad_samples(), 0u) << path;
        EXPECT_GT(g.stats.glossy_rays, 0u) << path;
        int compared = 0;
        double worst = 0, worst_cos = 0;
        for (size_t i = 0; i < ref.film.pixels.size(); ++i) {
            const vec3 a = g.film.pixels[i], b = ref.film.pixels[i];
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(a[c]) && a[c] >= 0.0f) << path;
            if (cosines[i] < 0.05) continue;
            ++compared;
            const double scale = scaling == BrdfScaling::report ? 1.0 : cosines[i];
            // physical: the weight's ci varies over the lobe by sin(theta_o) / sqrt(e) (one
            // standard deviation), averaged over 8 samples; allow 5 of those
            const double sin_o = std::sqrt(1 - cosines[i] * cosines[i]);
            const double noise = scaling == BrdfScaling::report ? 0.0 : 5 * sin_o / std::sqrt(8e6);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(a[c], b[c] * scale, 5e-4 + noise * b[c]) << path << " pixel " << i;
                if (std::fabs(a[c] - b[c] * scale) > worst) {
                    worst = std::fabs(a[c] - b[c] * scale);
                    worst_cos = cosines[i];
                }
            }
        }
        EXPECT_GT(compared, 200) << path;
        std::printf("%s %s: glossy e = 1e6 vs mirror, max |difference| %.2e (at cos %.3f)\n",
                    path.c_str(), scaling == BrdfScaling::report ? "report" : "physical", worst,
                    worst_cos);
    }
}

TEST(PhongExtremeExponent, GlossySphereAtOneMillionRendersAsTheMirror) {
    check_glossy_is_mirror(
        [](const SceneData& s, const Accel& a) { return render_scalar(s, a, RenderParams{}); },
        "scalar");
}

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class PhongExtremeExponentPacket : public ::testing::Test {};
TYPED_TEST_SUITE(PhongExtremeExponentPacket, Widths, WidthName);

TYPED_TEST(PhongExtremeExponentPacket, SamplersFitTheirPdfsInLobeCoordinates) {
    constexpr int W = TypeParam::value;
    check_sampler_against_pdf<W>("packet W=" + std::to_string(W));
}

/// The extreme random numbers through the packet samplers: the same decisions (pdf == 0,
/// weight == 0) as the scalar, directions within 1e-6, pdfs and weights within the tolerance of
/// brdf_packet_test.cpp ((16 + 4 |ln(v / peak)|) ulps plus 4e-7 per cosine); W = 1 bit for bit.
TYPED_TEST(PhongExtremeExponentPacket, MatchesTheScalarAtExtremeRandomNumbers) {
    constexpr int W = TypeParam::value;
    const vec3 n = glm::normalize(vec3(0.3f, -0.2f, -0.9f));
    const Frame f = frame_of(n);
    const vec3 wo(f.n * std::cos(0.5236) + f.t * std::sin(0.5236));
    const Vec3<W> nn = make_vec3<W>(n.x, n.y, n.z), wwo = make_vec3<W>(wo.x, wo.y, wo.z);
    const vec3 r = mirror_direction(n, wo);
    for (float e : {1e3f, 1e4f, 1e5f, 1e6f, 1e7f}) {  // one exponent per packet (a material's)
        std::vector<float> us1, us2;
        for (float u1 : extreme_u)
            for (float u2 : extreme_u) us1.push_back(u1), us2.push_back(u2);
        while (us1.size() % W != 0) us1.push_back(0.5f), us2.push_back(0.5f);
        const double peak = (e + 1.0) / (2 * pi_d);
        auto tol = [&](double v, double slack) {
            const double amp = v > 0 ? std::fabs(std::log(v / peak)) : 0.0;
            return ((16 + 4 * amp) * 0x1.0p-23 + slack) * v + 1e-30;
        };
        for (size_t i = 0; i < us1.size(); i += W) {
            const vfloat<W> u1 = load<W>(us1.data() + i), u2 = load<W>(us2.data() + i);
            const Vec3<W> ph = sample_phong_lobe<W>(mirror_direction(nn, wwo), e, u1, u2);
            const vfloat<W> php = pdf_phong_lobe<W>(mirror_direction(nn, wwo), e, ph);
            const LobeSamplePacket<W> bs = sample_blinn_phong<W>(nn, wwo, e, u1, u2);
            for (int k = 0; k < W; ++k) {
                const float a = us1[i + size_t(k)], b = us2[i + size_t(k)];
                const std::string at = "e " + std::to_string(e) + " u1 " + std::to_string(a) +
                                       " u2 " + std::to_string(b);
                const vec3 ws = sample_phong_lobe(r, e, a, b);
                const vec3 wp(get(ph.x, k), get(ph.y, k), get(ph.z, k));
                const LobeSample s = sample_blinn_phong(n, wo, e, a, b);
                const vec3 bw(get(bs.wi.x, k), get(bs.wi.y, k), get(bs.wi.z, k));
                const float pp = get(php, k), ps = pdf_phong_lobe(r, e, ws);
                ASSERT_TRUE(finite3(wp) && finite3(bw)) << at;
                ASSERT_TRUE(std::isfinite(pp) && std::isfinite(get(bs.pdf, k)) &&
                            std::isfinite(get(bs.weight, k)))
                    << at;
                if constexpr (W == 1) {
                    EXPECT_EQ(wp, ws) << at;
                    EXPECT_EQ(std::bit_cast<uint32_t>(pp), std::bit_cast<uint32_t>(ps)) << at;
                    EXPECT_EQ(bw, s.wi) << at;
                    EXPECT_EQ(std::bit_cast<uint32_t>(get(bs.pdf, k)),
                              std::bit_cast<uint32_t>(s.pdf))
                        << at;
                    EXPECT_EQ(std::bit_cast<uint32_t>(get(bs.weight, k)),
                              std::bit_cast<uint32_t>(s.weight))
                        << at;
                } else {
                    for (int c = 0; c < 3; ++c) {
                        EXPECT_NEAR(wp[c], ws[c], 1e-6f) << at;
                        EXPECT_NEAR(bw[c], s.wi[c], 1e-6f) << at;
                    }
                    EXPECT_EQ(pp == 0.0f, ps == 0.0f) << at;
                    // pdf re-evaluated at a direction 2e-7 away: d ln pdf = e theta d theta,
                    // with e theta = sqrt(2 e ln(peak / pdf))
                    const double lr = ps > 0.0f ? std::fabs(std::log(double(ps) / peak)) : 0.0;
                    EXPECT_NEAR(pp, ps, tol(ps, 4e-7 * (1 + std::sqrt(2 * double(e) * lr)))) << at;
                    EXPECT_EQ(get(bs.pdf, k) == 0.0f, s.pdf == 0.0f) << at;
                    EXPECT_EQ(get(bs.weight, k) == 0.0f, s.weight == 0.0f) << at;
                    const double oh = 0.5 * glm::length(s.wi + wo);
                    const double ci = std::fabs(glm::dot(n, s.wi));
                    EXPECT_NEAR(get(bs.pdf, k), s.pdf, tol(s.pdf, 4e-7 / oh)) << at;
                    EXPECT_NEAR(get(bs.weight, k), s.weight,
                                tol(s.weight, 4e-7 / std::max(ci, 1e-7) + 4e-7 / oh))
                        << at;
                }
            }
        }
    }
}

TYPED_TEST(PhongExtremeExponentPacket, DirectionalAlbedoStaysBounded) {
    constexpr int W = TypeParam::value;
    check_albedo<W>("packet W=" + std::to_string(W));
}

TYPED_TEST(PhongExtremeExponentPacket, GlossySphereAtOneMillionRendersAsTheMirror) {
    constexpr int W = TypeParam::value;
    check_glossy_is_mirror(
        [](const SceneData& s, const Accel& a) {
            return render_packet_width<W>(s, a, RenderParams{});
        },
        "packet W=" + std::to_string(W));
}

}  // namespace
}  // namespace raylane
