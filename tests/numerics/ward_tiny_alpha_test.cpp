// Numerical stability suite, shading (numerics.md §12): the Ward and
// Ward-Duer lobes, pdf and samplers of shade/brdf_scalar.h and brdf_packet.h for roughness alpha
// from 1 down to 0 (and garbage below), at exact mirror pairs, grazing cosines down to 1e-12
// and extreme random numbers: no NaN or infinity, every alpha below brdf_alpha_min behaves as
// the threshold, where sampling is a mirror; chi-square in lobe coordinates for alpha >= 1e-3.
// Raylane's Ward is isotropic (one alpha), so the alpha_x != alpha_y cases of §12 do not apply.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "shade/brdf_packet.h"
#include "shade/brdf_scalar.h"
#include "simd/lanes.h"
#include "support/chi_square.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

using chi_square::chi2_p_value;
using chi_square::Frame;
using chi_square::frame_of;
using dvec2 = glm::dvec2;
using dvec3 = glm::dvec3;

/// From rough to zero, then values no material should hold.
const float alphas[] = {1.0f, 0.1f, 1e-2f, 1e-3f, 1e-4f, 1e-6f, 1e-20f, 0.0f};
const float below_threshold[] = {9.9e-5f, 1e-6f,  1e-20f, 1e-40f, 0.0f,
                                 -0.0f,   -1e-3f, -inf_f, nan_f};

/// One lane's configuration.
struct Config {
    vec3 n, wo, wi;
    float u1, u2;
};

vec3 tilt(vec3 n, vec3 t, double cos_theta) {
    const double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    return vec3(glm::normalize(dvec3(n) * cos_theta + dvec3(t) * s));
}

/// wi = wo = n; exact mirror pairs; cosines down to 1e-12 (mirror pair, same side, opposite
/// sides, one of them below the surface); random pairs; each with extreme random numbers.
std::vector<Config> configs() {
    std::vector<Config> out;
    std::mt19937_64 rng(12);
    std::normal_distribution<float> g;
    const float cosines[] = {1.0f, 0.5f, 1e-3f, 1e-6f, 1e-12f};
    for (int i = 0; i < 6; ++i) {
        const vec3 n = i == 0   ? vec3(0, 0, 1)
                       : i == 1 ? vec3(0, 0, -1)
                                : glm::normalize(vec3(g(rng), g(rng), g(rng)));
        const dvec3 nd(n), gd = std::fabs(n.x) < 0.6f ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
        const vec3 t(glm::normalize(gd - nd * glm::dot(gd, nd)));
        std::vector<std::pair<vec3, vec3>> pairs = {{n, n}};
        for (float co : cosines) {
            const vec3 wo = tilt(n, t, co);
            pairs.push_back({mirror_direction(n, wo), wo});
            pairs.push_back({wo, wo});
            for (float ci : cosines) {
                pairs.push_back({tilt(n, -t, ci), wo});
                pairs.push_back({tilt(-n, -t, ci), wo});  // below the surface
            }
        }
        for (int k = 0; k < 8; ++k) {
            pairs.push_back({glm::normalize(vec3(g(rng), g(rng), g(rng))),
                             glm::normalize(vec3(g(rng), g(rng), g(rng)))});
        }
        for (size_t p = 0; p < pairs.size(); ++p) {
            const float u1 = extreme_u[p % 6], u2 = extreme_u[(p / 6 + p) % 6];
            out.push_back({n, pairs[p].second, pairs[p].first, u1, u2});
        }
    }
    return out;
}

/// Everything a Ward lane produces, in a fixed order.
struct WardOut {
    float lobe = 0, duer = 0, pdf = 0;
    LobeSample s, sd;
    vec3 spec_phys{0.0f}, spec_report{0.0f}, duer_phys{0.0f}, duer_report{0.0f};
};

Material ward_material(SpecularModel model, float alpha) {
    Material m;
    m.model = model;
    m.k_s = 1.0f;
    m.c_s = vec3(1.0f);
    m.alpha = alpha;
    return m;
}

WardOut ward_scalar(const Config& c, float alpha) {
    WardOut o;
    o.lobe = ward_lobe(c.n, c.wi, c.wo, alpha);
    o.duer = ward_duer_lobe(c.n, c.wi, c.wo, alpha);
    o.pdf = pdf_ward(c.n, c.wi, c.wo, alpha);
    o.s = sample_ward(c.n, c.wo, alpha, c.u1, c.u2);
    o.sd = sample_ward_duer(c.n, c.wo, alpha, c.u1, c.u2);
    const Material w = ward_material(SpecularModel::ward, alpha);
    const Material d = ward_material(SpecularModel::ward_duer, alpha);
    o.spec_phys = specular_factor(w, BrdfScaling::physical, c.n, c.wi, c.wo);
    o.spec_report = specular_factor(w, BrdfScaling::report, c.n, c.wi, c.wo);
    o.duer_phys = specular_factor(d, BrdfScaling::physical, c.n, c.wi, c.wo);
    o.duer_report = specular_factor(d, BrdfScaling::report, c.n, c.wi, c.wo);
    return o;
}

template <int W>
Vec3<W> pack3(const std::vector<Config>& cs, size_t i, vec3 Config::*member) {
    float x[W], y[W], z[W];
    for (int k = 0; k < W; ++k) {
        const vec3 v = cs[std::min(i + size_t(k), cs.size() - 1)].*member;
        x[k] = v.x, y[k] = v.y, z[k] = v.z;
    }
    return load_vec3<W>(x, y, z);
}
template <int W>
vfloat<W> pack1(const std::vector<Config>& cs, size_t i, float Config::*member) {
    float v[W];
    for (int k = 0; k < W; ++k) v[k] = cs[std::min(i + size_t(k), cs.size() - 1)].*member;
    return load<W>(v);
}

/// The packet twin of ward_scalar for configs [i, i + W).
template <int W>
std::vector<WardOut> ward_packet(const std::vector<Config>& cs, size_t i, float alpha) {
    const Vec3<W> n = pack3<W>(cs, i, &Config::n), wo = pack3<W>(cs, i, &Config::wo);
    const Vec3<W> wi = pack3<W>(cs, i, &Config::wi);
    const vfloat<W> u1 = pack1<W>(cs, i, &Config::u1), u2 = pack1<W>(cs, i, &Config::u2);
    const vfloat<W> lobe = ward_lobe(n, wi, wo, alpha), duer = ward_duer_lobe(n, wi, wo, alpha);
    const vfloat<W> pdf = pdf_ward(n, wi, wo, alpha);
    const LobeSamplePacket<W> s = sample_ward<W>(n, wo, alpha, u1, u2);
    const LobeSamplePacket<W> sd = sample_ward_duer<W>(n, wo, alpha, u1, u2);
    const Material w = ward_material(SpecularModel::ward, alpha);
    const Material d = ward_material(SpecularModel::ward_duer, alpha);
    const Vec3<W> sp = specular_factor<W>(w, BrdfScaling::physical, n, wi, wo);
    const Vec3<W> sr = specular_factor<W>(w, BrdfScaling::report, n, wi, wo);
    const Vec3<W> dp = specular_factor<W>(d, BrdfScaling::physical, n, wi, wo);
    const Vec3<W> dr = specular_factor<W>(d, BrdfScaling::report, n, wi, wo);
    std::vector<WardOut> out(W);
    for (int k = 0; k < W; ++k) {
        WardOut& o = out[size_t(k)];
        o.lobe = get(lobe, k), o.duer = get(duer, k), o.pdf = get(pdf, k);
        o.s = {lane3(s.wi, k), get(s.pdf, k), get(s.weight, k)};
        o.sd = {lane3(sd.wi, k), get(sd.pdf, k), get(sd.weight, k)};
        o.spec_phys = lane3(sp, k), o.spec_report = lane3(sr, k);
        o.duer_phys = lane3(dp, k), o.duer_report = lane3(dr, k);
    }
    return out;
}

bool good(float v) { return std::isfinite(v) && v >= 0.0f; }
bool good(vec3 v) { return good(v.x) && good(v.y) && good(v.z); }

void expect_finite(const WardOut& o, const std::string& at) {
    EXPECT_TRUE(good(o.lobe)) << at << ": ward " << o.lobe;
    EXPECT_TRUE(good(o.duer)) << at << ": ward-duer " << o.duer;
    EXPECT_TRUE(good(o.pdf)) << at << ": pdf " << o.pdf;
    for (const LobeSample& s : {o.s, o.sd}) {
        EXPECT_TRUE(finite3(s.wi)) << at;
        EXPECT_TRUE(good(s.pdf)) << at << ": sample pdf " << s.pdf;
        EXPECT_TRUE(good(s.weight)) << at << ": sample weight " << s.weight;
    }
    for (vec3 f : {o.spec_phys, o.spec_report, o.duer_phys, o.duer_report})
        EXPECT_TRUE(good(f)) << at << ": specular factor";
}

std::string where(const Config& c, float alpha, size_t i) {
    return "alpha " + std::to_string(alpha) + " config " + std::to_string(i) + " (n.wo " +
           std::to_string(glm::dot(c.n, c.wo)) + ", n.wi " + std::to_string(glm::dot(c.n, c.wi)) +
           ", u " + std::to_string(c.u1) + " " + std::to_string(c.u2) + ")";
}

bool same_bits(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}
bool same_bits(vec3 a, vec3 b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}
bool same_bits(const WardOut& a, const WardOut& b) {
    return same_bits(a.lobe, b.lobe) && same_bits(a.duer, b.duer) && same_bits(a.pdf, b.pdf) &&
           same_bits(a.s.wi, b.s.wi) && same_bits(a.s.pdf, b.s.pdf) &&
           same_bits(a.s.weight, b.s.weight) && same_bits(a.sd.wi, b.sd.wi) &&
           same_bits(a.sd.pdf, b.sd.pdf) && same_bits(a.sd.weight, b.sd.weight) &&
           same_bits(a.spec_phys, b.spec_phys) && same_bits(a.spec_report, b.spec_report) &&
           same_bits(a.duer_phys, b.duer_phys) && same_bits(a.duer_report, b.duer_report);
}

TEST(WardTinyAlpha, StaysFiniteForAlphaDownToZero) {
    const std::vector<Config> cs = configs();
    for (float alpha : alphas)
        for (size_t i = 0; i < cs.size(); ++i)
            expect_finite(ward_scalar(cs[i], alpha), where(cs[i], alpha, i));
}

TEST(WardTinyAlpha, AlphaBelowTheThresholdIsTheThreshold) {
    const std::vector<Config> cs = configs();
    for (float alpha : below_threshold) {
        for (size_t i = 0; i < cs.size(); ++i) {
            const WardOut o = ward_scalar(cs[i], alpha);
            expect_finite(o, where(cs[i], alpha, i));
            EXPECT_TRUE(same_bits(o, ward_scalar(cs[i], brdf_alpha_min))) << where(cs[i], alpha, i);
        }
    }
}

/// At the threshold the lobe is a mirror: sampled directions within 8.2 alpha of the mirror
/// direction (2 theta_h, tan^2 theta_h <= alpha^2 ln 2^24), and the sample weights at their
/// alpha -> 0 limits, 1 for Ward-Duer and cos(theta_o) for Ward (brdf-reference.md §6), up to
/// the tilt of h: (wo.h) / co and sqrt(ci / co) each change by tan(theta_o) theta_h. Explicit
/// evaluation at the exact mirror pair is the finite peak 1 / (4 pi alpha^2 co^2) (Ward-Duer).
TEST(WardTinyAlpha, SamplesTheMirrorDirectionAtTheThreshold) {
    std::mt19937_64 rng(13);
    std::normal_distribution<float> g;
    const double a = brdf_alpha_min, theta_max = std::sqrt(24 * std::log(2.0)) * a;
    double worst_angle = 0;
    for (double theta_o : {0.0, 30.0, 60.0, 80.0, 89.0}) {
        for (int k = 0; k < 4; ++k) {
            const vec3 n = glm::normalize(vec3(g(rng), g(rng), g(rng)));
            const dvec3 nd(n), gd = std::fabs(n.x) < 0.6f ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
            const vec3 t(glm::normalize(gd - nd * glm::dot(gd, nd)));
            const double co = std::cos(theta_o * pi_d / 180);
            const vec3 wo = tilt(n, t, co);
            const dvec3 r(mirror_direction(n, wo));
            const double tan_o = std::tan(theta_o * pi_d / 180);
            for (int i = 0; i < 500; ++i) {
                const float u1 = float(rng() >> 40) * 0x1.0p-24f;
                const float u2 = i < 6 ? extreme_u[i % 5] : float(rng() >> 40) * 0x1.0p-24f;
                for (bool duer : {false, true}) {
                    const LobeSample s = duer ? sample_ward_duer(n, wo, 0.0f, u1, u2)
                                              : sample_ward(n, wo, 0.0f, u1, u2);
                    const dvec3 w(s.wi);
                    const double angle = std::atan2(glm::length(glm::cross(w, r)), glm::dot(w, r));
                    EXPECT_LE(angle, 2 * theta_max + 1e-6) << theta_o;
                    worst_angle = std::max(worst_angle, angle);
                    const double limit = duer ? 1.0 : co;
                    EXPECT_NEAR(s.weight, limit, limit * (2.5 * tan_o * theta_max + 1e-5))
                        << theta_o << (duer ? " ward-duer" : " ward");
                }
            }
            if (co >= 1e-3) {
                const double peak = 1.0 / (4 * pi_d * a * a * co * co);
                EXPECT_NEAR(ward_duer_lobe(n, vec3(r), wo, 0.0f), peak, 1e-4 * peak) << theta_o;
            }
        }
    }
    std::printf("alpha -> 0: sampled directions within %.3g rad of the mirror (bound %.3g)\n",
                worst_angle, 2 * theta_max);
}

// ---- chi-square in lobe coordinates ---------------------------------------------------------

/// Lobe coordinates: the half vector's tangent components divided by alpha, in which the
/// sampled density is (1 / pi) exp(-x^2 - y^2) at every alpha.
dvec2 local_of(const Frame& f, vec3 wo, float alpha, vec3 wi) {
    const dvec3 h = glm::normalize(dvec3(wi) + dvec3(wo));
    return dvec2(glm::dot(h, f.t), glm::dot(h, f.b)) / (glm::dot(h, f.n) * double(alpha));
}

int ward_bin_of(dvec2 xy) {
    if (!(std::fabs(xy.x) < 3 && std::fabs(xy.y) < 3)) return 256;
    return int((xy.y + 3) * 16 / 6) * 16 + int((xy.x + 3) * 16 / 6);
}

/// pdf_ward (scalar when W == 0, else packets) integrated over a 256 x 256 grid on [-6, 6]^2 of
/// lobe coordinates, and the sampler binned into 16 x 16 bins on [-3, 3]^2 plus the outside.
template <int W>
void check_ward_chi_square(const std::string& path) {
    // the same samples in every build, sanitizers included (a tenth of them would leave too few
    // bins with 5 expected samples for the test's power)
    const int count = 200000;
    std::mt19937_64 rng(14);
    std::normal_distribution<float> g;
    for (float alpha : {1e-4f, 1e-3f, 1e-2f}) {
        for (double theta_o : {0.0, 45.0}) {
            const vec3 n = glm::normalize(vec3(g(rng), g(rng), g(rng)));
            const Frame f = frame_of(n);
            const vec3 wo(f.n * std::cos(theta_o * pi_d / 180) +
                          f.t * std::sin(theta_o * pi_d / 180));
            const std::string what = path + " alpha " + std::to_string(alpha) + " at " +
                                     std::to_string(int(theta_o)) + " degrees";
            // expected bin masses from the production pdf: dwi = 4 (wo.h) alpha^2 dx dy /
            // (1 + alpha^2 r^2)^(3/2)
            const int cells = 256;
            const double step = 12.0 / cells;
            std::vector<vec3> wis;
            std::vector<double> jac;
            std::vector<int> bins;
            for (int iy = 0; iy < cells; ++iy) {
                for (int ix = 0; ix < cells; ++ix) {
                    const dvec2 xy(-6 + (ix + 0.5) * step, -6 + (iy + 0.5) * step);
                    const double r2 = glm::dot(xy, xy), a = alpha;
                    const dvec3 h = glm::normalize((f.t * xy.x + f.b * xy.y) * a + f.n);
                    const double oh = glm::dot(dvec3(wo), h);
                    wis.push_back(vec3(h * (2 * oh) - dvec3(wo)));
                    jac.push_back(4 * oh * a * a / std::pow(1 + a * a * r2, 1.5) * step * step);
                    bins.push_back(ward_bin_of(xy));
                }
            }
            std::vector<double> pdf(wis.size());
            if constexpr (W == 0) {
                for (size_t i = 0; i < wis.size(); ++i) pdf[i] = pdf_ward(n, wis[i], wo, alpha);
            } else {
                const Vec3<W> nn = make_vec3<W>(n.x, n.y, n.z), ww = make_vec3<W>(wo.x, wo.y, wo.z);
                for (size_t i = 0; i < wis.size(); i += W) {
                    float x[W], y[W], z[W];
                    for (int k = 0; k < W; ++k) {
                        const vec3 v = wis[i + size_t(k)];  // wis.size() is a multiple of 16
                        x[k] = v.x, y[k] = v.y, z[k] = v.z;
                    }
                    const vfloat<W> p = pdf_ward<W>(nn, load_vec3<W>(x, y, z), ww, alpha);
                    for (int k = 0; k < W; ++k) pdf[i + size_t(k)] = get(p, k);
                }
            }
            std::vector<double> mass(257, 0.0);
            double total = 0;
            for (size_t i = 0; i < pdf.size(); ++i) {
                total += pdf[i] * jac[i];
                mass[size_t(bins[i])] += pdf[i] * jac[i];
            }
            EXPECT_NEAR(total, 1.0, 1e-3) << what << ": the pdf integrates to 1";
            // samples
            std::vector<int> counts(257, 0);
            std::vector<float> u1(static_cast<size_t>(count)), u2(static_cast<size_t>(count));
            for (int i = 0; i < count; ++i) {
                u1[size_t(i)] = float(rng() >> 40) * 0x1.0p-24f;
                u2[size_t(i)] = float(rng() >> 40) * 0x1.0p-24f;
            }
            if constexpr (W == 0) {
                for (int i = 0; i < count; ++i) {
                    const LobeSample s = sample_ward(n, wo, alpha, u1[size_t(i)], u2[size_t(i)]);
                    ++counts[size_t(ward_bin_of(local_of(f, wo, alpha, s.wi)))];
                }
            } else {
                const Vec3<W> nn = make_vec3<W>(n.x, n.y, n.z), ww = make_vec3<W>(wo.x, wo.y, wo.z);
                for (size_t i = 0; i + W <= u1.size(); i += W) {
                    const LobeSamplePacket<W> s = sample_ward<W>(
                        nn, ww, alpha, load<W>(u1.data() + i), load<W>(u2.data() + i));
                    for (int k = 0; k < W; ++k)
                        ++counts[size_t(ward_bin_of(local_of(f, wo, alpha, lane3(s.wi, k))))];
                }
            }
            std::vector<double> expected(257);
            for (size_t i = 0; i < 257; ++i) expected[i] = mass[i] * count;
            int used = 0;
            const double p = chi2_p_value(expected, counts, &used);
            EXPECT_GT(p, 0.01) << what << ": chi-square over " << used << " bins";
            EXPECT_GT(used, 150) << what;
            std::printf("%s: integral of pdf - 1 = %.2e, chi-square p = %.3f (%d bins)\n",
                        what.c_str(), total - 1, p, used);
        }
    }
}

TEST(WardTinyAlpha, SamplerFitsItsPdfInLobeCoordinates) { check_ward_chi_square<0>("scalar"); }

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class WardTinyAlphaPacket : public ::testing::Test {};
TYPED_TEST_SUITE(WardTinyAlphaPacket, Widths, WidthName);

/// Every alpha (the threshold's stand-ins included) through the packet functions: finite, the
/// same zero decisions as the scalar, values within brdf_packet_test.cpp's tolerance
/// ((16 + 4 |ln(v / peak)|) ulps, plus 4e-7 per cosine of the sampled direction), W = 1 bit
/// for bit.
TYPED_TEST(WardTinyAlphaPacket, MatchesTheScalarForAlphaDownToZero) {
    constexpr int W = TypeParam::value;
    const std::vector<Config> cs = configs();
    std::vector<float> all(std::begin(alphas), std::end(alphas));
    all.insert(all.end(), std::begin(below_threshold), std::end(below_threshold));
    for (float alpha : all) {
        const double a = std::max(double(alpha), double(brdf_alpha_min));
        const double peak = std::isnan(alpha) ? 1 / (4 * pi_d * 1e-8) : 1 / (4 * pi_d * a * a);
        auto near = [&](float p, float s, double slack, const std::string& at) {
            ASSERT_TRUE(good(p)) << at << ": " << p;
            EXPECT_EQ(p == 0.0f, s == 0.0f) << at << ": " << p << " vs " << s;
            const double mag = std::fabs(double(s));
            const double amp = mag > 0 ? std::fabs(std::log(mag / peak)) : 0.0;
            EXPECT_NEAR(p, s, ((16 + 4 * amp) * 0x1.0p-23 + slack) * mag + 1e-30) << at;
        };
        for (size_t i = 0; i < cs.size(); i += W) {
            const std::vector<WardOut> po = ward_packet<W>(cs, i, alpha);
            for (int k = 0; k < W && i + size_t(k) < cs.size(); ++k) {
                const Config& c = cs[i + size_t(k)];
                const std::string at = where(c, alpha, i + size_t(k));
                const WardOut so = ward_scalar(c, alpha);
                const WardOut& p = po[size_t(k)];
                if constexpr (W == 1) {
                    EXPECT_TRUE(same_bits(p, so)) << at;
                    continue;
                }
                near(p.lobe, so.lobe, 0, at + " ward");
                near(p.duer, so.duer, 0, at + " ward-duer");
                near(p.pdf, so.pdf, 0, at + " pdf");
                for (int j = 0; j < 2; ++j) {
                    const LobeSample& a1 = j ? p.sd : p.s;
                    const LobeSample& b1 = j ? so.sd : so.s;
                    for (int q = 0; q < 3; ++q) EXPECT_NEAR(a1.wi[q], b1.wi[q], 1e-6f) << at;
                    const double ci = std::fabs(glm::dot(c.n, b1.wi));
                    const double oh = std::fabs(glm::dot(c.wo, b1.wi + c.wo)) / 2 + 1e-30;
                    near(a1.pdf, b1.pdf, 4e-7 / oh, at + " sample pdf");
                    // the weight's zero test (ci > 0) is a decision on the sampled direction
                    if (ci > 1e-5)
                        near(a1.weight, b1.weight, 4e-7 / ci + 4e-7 / oh, at + " weight");
                }
                for (int q = 0; q < 3; ++q) {
                    near(p.spec_phys[q], so.spec_phys[q], 0, at + " specular");
                    near(p.spec_report[q], so.spec_report[q], 0, at + " specular");
                    near(p.duer_phys[q], so.duer_phys[q], 0, at + " specular");
                    near(p.duer_report[q], so.duer_report[q], 0, at + " specular");
                }
            }
        }
    }
}

TYPED_TEST(WardTinyAlphaPacket, AlphaBelowTheThresholdIsTheThreshold) {
    constexpr int W = TypeParam::value;
    const std::vector<Config> cs = configs();
    for (float alpha : below_threshold) {
        for (size_t i = 0; i < cs.size(); i += W) {
            const std::vector<WardOut> below = ward_packet<W>(cs, i, alpha);
            const std::vector<WardOut> at = ward_packet<W>(cs, i, brdf_alpha_min);
            for (int k = 0; k < W; ++k)
                EXPECT_TRUE(same_bits(below[size_t(k)], at[size_t(k)]))
                    << where(cs[std::min(i + size_t(k), cs.size() - 1)], alpha, i + size_t(k));
        }
    }
}

TYPED_TEST(WardTinyAlphaPacket, SamplerFitsItsPdfInLobeCoordinates) {
    constexpr int W = TypeParam::value;
    check_ward_chi_square<W>("packet W=" + std::to_string(W));
}

}  // namespace
}  // namespace raylane
