// Tests of shade/brdf_packet.h and shade/optics_packet.h against the scalar references
// shade/brdf_scalar.h and shade/optics_scalar.h, at every width of the program's instruction
// set. W = 1 must match bit for bit (same std:: calls, same operation order). Wider packets call
// the same std:: transcendentals lane by lane, but group some products differently; an error of
// d ulps in the argument x of exp(x) becomes |x| d ulps in the result, so values are compared
// with a relative tolerance of (16 + 4 |ln v|) * 2^-23 where v is the lobe value relative to its
// peak (typically <= 1e-5 relative), and directions with an absolute 1e-6.
#include "shade/brdf_packet.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/ray_packet.h"
#include "shade/brdf_scalar.h"
#include "shade/optics_packet.h"
#include "shade/optics_scalar.h"
#include "simd/lanes.h"
#include "support/widths.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int brdf_rounds = 64;
#else
constexpr int brdf_rounds = 1024;
#endif

constexpr double ulp1 = 0x1.0p-23;

struct LaneRng {
    std::mt19937_64 engine;
    explicit LaneRng(uint64_t seed) : engine(seed) {}
    float uniform() { return static_cast<float>(engine() >> 40) * 0x1.0p-24f; }
    vec3 direction() {
        const float z = 2.0f * uniform() - 1.0f, phi = 6.2831853f * uniform();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::normalize(vec3(r * std::cos(phi), r * std::sin(phi), z));
    }
};

/// One shading configuration per lane: n, wo, wi, random numbers and a cosine for Fresnel.
struct Lane {
    vec3 n, wo, wi;
    float u1, u2, cos_i, eta, distance;
};

/// Mixes random pairs (half below the surface), near-mirror pairs (the lobes' peaks), exact
/// degenerate pairs (wi = wo = n, exact mirror, cosines 1e-12) and extreme random numbers.
Lane make_lane(LaneRng& rng, int i) {
    Lane l;
    l.n = rng.direction();
    l.wo = rng.direction();
    if (glm::dot(l.wo, l.n) < 0.0f && i % 4 != 0) l.wo = -l.wo;
    const vec3 r = mirror_direction(l.n, l.wo);
    const float spread = std::pow(10.0f, -4.0f * rng.uniform());  // 1e-4 .. 1 rad
    switch (i % 8) {
        case 0:
        case 1:
            l.wi = rng.direction();
            break;
        case 2:
            l.wi = l.n, l.wo = l.n;
            break;
        case 3:
            l.wi = r;
            break;
        case 4: {
            l.n = vec3(0, 0, 1);
            const float c = std::pow(10.0f, -12.0f * rng.uniform());
            l.wo = vec3(std::sqrt(1 - c * c), 0, c);
            l.wi = vec3(-l.wo.x, 0, std::pow(10.0f, -12.0f * rng.uniform()));
            l.wi = glm::normalize(l.wi);
            break;
        }
        default:
            l.wi = glm::normalize(r + rng.direction() * spread);
            break;
    }
    const float extremes[] = {0.0f, 1e-12f, 0.5f, 1.0f - 0x1.0p-24f};
    l.u1 = i % 16 == 5 ? extremes[(i / 16) % 4] : rng.uniform();
    l.u2 = i % 16 == 6 ? extremes[(i / 16) % 4] : rng.uniform();
    l.cos_i = i % 16 == 7 ? extremes[(i / 16) % 4] : rng.uniform();
    const float etas[] = {1.0f, 1.5f, 1.0f / 1.5f, 4.0f, 0.25f, 1.0001f};
    l.eta = etas[i % 6];
    const float distances[] = {0.0f, 1e-9f, 0.7f, 30.0f, std::numeric_limits<float>::infinity()};
    l.distance = distances[i % 5] * (1.0f + rng.uniform());
    return l;
}

template <int W>
struct Packets {
    std::vector<Lane> lanes;
    Vec3<W> n, wo, wi;
    vfloat<W> u1, u2, cos_i, eta, distance;
};

template <int W>
Vec3<W> gather3(const std::vector<Lane>& lanes, vec3 Lane::*member) {
    float x[W], y[W], z[W];
    for (int k = 0; k < W; ++k) {
        const vec3 v = lanes[size_t(k)].*member;
        x[k] = v.x, y[k] = v.y, z[k] = v.z;
    }
    return load_vec3<W>(x, y, z);
}
template <int W>
vfloat<W> gather1(const std::vector<Lane>& lanes, float Lane::*member) {
    float v[W];
    for (int k = 0; k < W; ++k) v[k] = lanes[size_t(k)].*member;
    return load<W>(v);
}

template <int W>
Packets<W> make_packets(LaneRng& rng, int round) {
    Packets<W> p;
    for (int k = 0; k < W; ++k) p.lanes.push_back(make_lane(rng, round * W + k));
    p.n = gather3<W>(p.lanes, &Lane::n);
    p.wo = gather3<W>(p.lanes, &Lane::wo);
    p.wi = gather3<W>(p.lanes, &Lane::wi);
    p.u1 = gather1<W>(p.lanes, &Lane::u1);
    p.u2 = gather1<W>(p.lanes, &Lane::u2);
    p.cos_i = gather1<W>(p.lanes, &Lane::cos_i);
    p.eta = gather1<W>(p.lanes, &Lane::eta);
    p.distance = gather1<W>(p.lanes, &Lane::distance);
    return p;
}

template <int W>
vec3 lane_of(const Vec3<W>& v, int k) {
    return vec3(get(v.x, k), get(v.y, k), get(v.z, k));
}

/// Largest relative deviation seen per quantity, reported at the end of each test.
struct Worst {
    std::string name;
    double rel = 0;
};

/// Packet value p against scalar s: bit-identical at W = 1; else |p - s| <= tol |s| + 1e-30
/// with tol = (16 + 4 |ln(|s| / peak)|) ulps (peak: the quantity's value scale) + slack.
template <int W>
void expect_match(float p, float s, double peak, Worst& worst, const std::string& what,
                  double slack = 0.0) {
    ASSERT_TRUE(std::isfinite(s)) << what;
    if constexpr (W == 1) {
        EXPECT_EQ(std::bit_cast<uint32_t>(p), std::bit_cast<uint32_t>(s))
            << what << ": " << p << " vs " << s;
    } else {
        const double mag = std::fabs(double(s));
        const double amp = mag > 0 ? std::fabs(std::log(mag / peak)) : 0.0;
        const double tol = (16 + 4 * amp) * ulp1 + slack;
        EXPECT_NEAR(p, s, tol * mag + 1e-30) << what;
        if (mag > 1e-30) worst.rel = std::max(worst.rel, std::fabs(p - s) / mag);
    }
}

template <int W>
void expect_match(vec3 p, vec3 s, double peak, Worst& worst, const std::string& what) {
    for (int c = 0; c < 3; ++c) expect_match<W>(p[c], s[c], peak, worst, what);
}

/// Directions: exact at W = 1, else within 1e-6 per component.
template <int W>
void expect_direction(vec3 p, vec3 s, const std::string& what) {
    if constexpr (W == 1) {
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(std::bit_cast<uint32_t>(p[c]), std::bit_cast<uint32_t>(s[c])) << what;
    } else {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], s[c], 1e-6f) << what;
    }
}

template <class T>
class BrdfPacket : public ::testing::Test {};
TYPED_TEST_SUITE(BrdfPacket, Widths, WidthName);

const float packet_alphas[] = {1e-4f, 0.0141f, 0.162f, 1.0f};
const float packet_exponents[] = {0.0f, 50.0f, 1040.0f, 1e6f};

TYPED_TEST(BrdfPacket, FramesMatchScalar) {
    constexpr int W = TypeParam::value;
    LaneRng rng(10);
    for (int round = 0; round < brdf_rounds; ++round) {
        const Packets<W> p = make_packets<W>(rng, round);
        Vec3<W> t, b;
        orthonormal_basis(p.n, t, b);
        const Vec3<W> r = mirror_direction(p.n, p.wo);
        const Vec3<W> refl = reflect_direction(p.wi, p.n);
        for (int k = 0; k < W; ++k) {
            const Lane& l = p.lanes[size_t(k)];
            vec3 ts, bs;
            orthonormal_basis(l.n, ts, bs);
            // no transcendental functions here: identical at every width
            EXPECT_EQ(lane_of(t, k), ts);
            EXPECT_EQ(lane_of(b, k), bs);
            EXPECT_EQ(lane_of(r, k), mirror_direction(l.n, l.wo));
            EXPECT_EQ(lane_of(refl, k), reflect_direction(l.wi, l.n));
        }
    }
}

TYPED_TEST(BrdfPacket, LobesMatchScalar) {
    constexpr int W = TypeParam::value;
    LaneRng rng(11);
    Worst worst;
    for (int round = 0; round < brdf_rounds; ++round) {
        const Packets<W> p = make_packets<W>(rng, round);
        const float alpha = packet_alphas[round % 4], e = packet_exponents[(round / 4) % 4];
        const Vec3<W> r = mirror_direction(p.n, p.wo);
        const vfloat<W> ph = phong_lobe(r, p.wi, e), bp = blinn_phong_lobe(p.n, p.wi, p.wo, e);
        const vfloat<W> wa = ward_lobe(p.n, p.wi, p.wo, alpha);
        const vfloat<W> wd = ward_duer_lobe(p.n, p.wi, p.wo, alpha);
        const vfloat<W> pw = pdf_ward(p.n, p.wi, p.wo, alpha);
        const vfloat<W> pb = pdf_blinn_phong(p.n, p.wi, p.wo, e);
        const vfloat<W> pp = pdf_phong_lobe(r, e, p.wi);
        const double ward_peak = 1.0 / (4 * 3.14159265 * alpha * alpha);
        const double bp_peak = (e + 2.0) / (2 * 3.14159265);
        for (int k = 0; k < W; ++k) {
            const Lane& l = p.lanes[size_t(k)];
            const vec3 rs = mirror_direction(l.n, l.wo);
            const std::string at = " lane " + std::to_string(round * W + k);
            expect_match<W>(get(ph, k), phong_lobe(rs, l.wi, e), 1.0, worst, "phong" + at);
            expect_match<W>(get(bp, k), blinn_phong_lobe(l.n, l.wi, l.wo, e), bp_peak, worst,
                            "blinn_phong" + at);
            expect_match<W>(get(wa, k), ward_lobe(l.n, l.wi, l.wo, alpha), ward_peak, worst,
                            "ward" + at);
            expect_match<W>(get(wd, k), ward_duer_lobe(l.n, l.wi, l.wo, alpha), ward_peak, worst,
                            "ward_duer" + at);
            expect_match<W>(get(pw, k), pdf_ward(l.n, l.wi, l.wo, alpha), ward_peak, worst,
                            "pdf_ward" + at);
            expect_match<W>(get(pb, k), pdf_blinn_phong(l.n, l.wi, l.wo, e), bp_peak, worst,
                            "pdf_blinn_phong" + at);
            expect_match<W>(get(pp, k), pdf_phong_lobe(rs, e, l.wi), bp_peak, worst,
                            "pdf_phong_lobe" + at);
        }
    }
    std::printf("W=%d lobes: max relative deviation %.3g\n", W, worst.rel);
}

/// phong_lobe skips exp and log1p for a packet whose every lane lies past phong_zero_chord2:
/// there the lobe is exactly 0 by the formula itself (scalar and packet), the threshold sits at
/// e ln cos = -110 (a margin of 6 over the smallest float), and a packet with lanes inside still
/// computes them, every lane as the scalar lobe does.
TYPED_TEST(BrdfPacket, PhongLobeIsExactlyZeroWhereItsPacketsSkipIt) {
    constexpr int W = TypeParam::value;
    const vec3 axis(0.0f, 0.0f, 1.0f);
    const Vec3<W> ax = make_vec3<W>(0.0f, 0.0f, 1.0f);
    // a direction whose chord to the axis has length^2 about c: unit with cos = 1 - c / 2, or
    // for tiny c (huge e, where 1 - c / 2 rounds to 1) the axis plus a side step of sqrt(c)
    auto at_chord2 = [&](float c) {
        if (c < 1e-3f) return vec3(std::sqrt(c), 0.0f, 1.0f);
        const float cos_t = 1.0f - 0.5f * c;
        return vec3(std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t)), 0.0f, cos_t);
    };
    auto chord2 = [&](vec3 w) { return glm::dot(w - axis, w - axis); };
    // e = 7 and 10: the threshold just under 2; 1e7: the scene loader's largest; 1e20: huge
    for (float e : {1.0f, 7.0f, 10.0f, 50.0f, 1000.0f, 1e6f, 1e7f, 1e20f}) {
        SCOPED_TRACE("e = " + std::to_string(e));
        const float c = phong_zero_chord2(e);
        ASSERT_GT(c, 0.0f);
        ASSERT_LE(c, 2.0f);
        // at c the lobe is at most exp(-110); two floats below c it is above it (unless c is 2)
        auto exponent_at = [&](float x) { return double(e) * std::log1p(-0.5 * double(x)); };
        EXPECT_LE(exponent_at(c), -110.0 + 1e-9);
        if (c < 2.0f) {
            EXPECT_GT(exponent_at(std::nextafter(std::nextafter(c, 0.0f), 0.0f)), -110.0);
        }
        // lanes from the first direction whose computed chord^2 reaches c up to the lobe's edge:
        // 0 from the scalar formula, and from the packet (which skips)
        vec3 first = at_chord2(c);
        for (float k = c; chord2(first) < c && k < 2.0f;) {
            k *= 1.0f + 1e-7f;
            first = at_chord2(k);
        }
        alignas(64) float x[W], y[W], z[W];
        for (int k = 0; k < W; ++k) {
            const float ck = c + (2.0f - c) * static_cast<float>(k) / static_cast<float>(W);
            const vec3 w = k == 0 ? first : at_chord2(ck);
            x[k] = w.x, y[k] = w.y, z[k] = w.z;
            if (chord2(w) >= c) {
                EXPECT_EQ(phong_lobe(axis, w, e), 0.0f) << "chord^2 " << chord2(w);
            }
        }
        EXPECT_GE(chord2(first), c);
        Vec3<W> ws = load_vec3<W>(x, y, z);
        for (int k = 0; k < W; ++k)
            EXPECT_EQ(get(phong_lobe(ax, ws, e), k), phong_lobe(axis, vec3(x[k], y[k], z[k]), e));
        // lanes inside the lobe (lane 0 well inside, the last one at the mirror direction itself)
        // and, at W > 1, one NaN lane: the packet computes, every lane as the scalar lobe
        const vec3 inside = at_chord2(0.25f * c);
        set(ws.x, 0, inside.x), set(ws.y, 0, inside.y), set(ws.z, 0, inside.z);
        if constexpr (W > 1) {
            set(ws.x, W - 1, 0.0f), set(ws.y, W - 1, 0.0f), set(ws.z, W - 1, 1.0f);
            set(ws.x, 1, std::numeric_limits<float>::quiet_NaN());
        }
        const vfloat<W> got = phong_lobe(ax, ws, e);
        EXPECT_GT(get(got, 0), 0.0f);
        for (int k = 0; k < W; ++k) {
            const float want = phong_lobe(axis, get_vec3(ws, k), e);
            if (std::isnan(want)) {
                EXPECT_TRUE(std::isnan(get(got, k))) << "lane " << k;
            } else {
                EXPECT_NEAR(get(got, k), want, 1e-5f * want) << "lane " << k;
            }
        }
    }
}

TYPED_TEST(BrdfPacket, ShadingFactorsMatchScalar) {
    constexpr int W = TypeParam::value;
    LaneRng rng(12);
    Worst worst;
    Material m;
    m.k_s = 0.8f;
    m.k_d = 0.45f;
    m.c_s = vec3(1.0f, 0.9f, 0.25f);
    const vec3 c_d(0.3f, 0.6f, 0.9f);
    for (int round = 0; round < brdf_rounds; ++round) {
        const Packets<W> p = make_packets<W>(rng, round);
        m.alpha = packet_alphas[round % 4];
        m.exponent = packet_exponents[(round / 4) % 4];
        const Vec3<W> cd = make_vec3<W>(c_d.x, c_d.y, c_d.z);
        const Vec3<W> cs = p.wo;  // a per-lane specular colour (a texture)
        for (SpecularModel model :
             {SpecularModel::phong, SpecularModel::glossy_phong, SpecularModel::blinn_phong,
              SpecularModel::ward, SpecularModel::ward_duer}) {
            m.model = model;
            const double peak = model == SpecularModel::phong ? 1.0
                                : model == SpecularModel::blinn_phong
                                    ? (m.exponent + 2.0) / (2 * 3.14159265)
                                    : 1.0 / (4 * 3.14159265 * m.alpha * m.alpha);
            for (BrdfScaling s : {BrdfScaling::physical, BrdfScaling::report}) {
                const Vec3<W> spec = specular_factor(m, s, p.n, p.wi, p.wo);
                const Vec3<W> spec_tex = specular_factor(m, s, cs, p.n, p.wi, p.wo);
                const Vec3<W> diff = diffuse_factor(m, s, cd, p.n, p.wi);
                const Vec3<W> gloss = glossy_weight(m, s, p.n, p.wi);
                const Vec3<W> gloss_tex = glossy_weight(m, s, cs, p.n, p.wi);
                for (int k = 0; k < W; ++k) {
                    const Lane& l = p.lanes[size_t(k)];
                    const std::string at = " model " + std::to_string(int(model)) + " lane " +
                                           std::to_string(round * W + k);
                    expect_match<W>(lane_of(spec, k), specular_factor(m, s, l.n, l.wi, l.wo), peak,
                                    worst, "specular" + at);
                    expect_match<W>(lane_of(spec_tex, k),
                                    specular_factor(m, s, l.wo, l.n, l.wi, l.wo), peak, worst,
                                    "specular(c_s)" + at);
                    expect_match<W>(lane_of(diff, k), diffuse_factor(m, s, c_d, l.n, l.wi), 1.0,
                                    worst, "diffuse" + at);
                    expect_match<W>(lane_of(gloss, k), glossy_weight(m, s, l.n, l.wi), 1.0, worst,
                                    "glossy" + at);
                    expect_match<W>(lane_of(gloss_tex, k), glossy_weight(m, s, l.wo, l.n, l.wi),
                                    1.0, worst, "glossy(c_s)" + at);
                }
            }
        }
    }
    std::printf("W=%d factors: max relative deviation %.3g\n", W, worst.rel);
}

TYPED_TEST(BrdfPacket, SamplersMatchScalar) {
    constexpr int W = TypeParam::value;
    LaneRng rng(13);
    Worst worst;
    for (int round = 0; round < brdf_rounds; ++round) {
        const Packets<W> p = make_packets<W>(rng, round);
        const float alpha = packet_alphas[round % 4], e = packet_exponents[(round / 4) % 4];
        const Vec3<W> ph = sample_phong_lobe(p.wo, e, p.u1, p.u2);
        const LobeSamplePacket<W> sw = sample_ward(p.n, p.wo, alpha, p.u1, p.u2);
        const LobeSamplePacket<W> sd = sample_ward_duer(p.n, p.wo, alpha, p.u1, p.u2);
        const LobeSamplePacket<W> sb = sample_blinn_phong(p.n, p.wo, e, p.u1, p.u2);
        for (int k = 0; k < W; ++k) {
            const Lane& l = p.lanes[size_t(k)];
            const std::string at = " lane " + std::to_string(round * W + k);
            expect_direction<W>(lane_of(ph, k), sample_phong_lobe(l.wo, e, l.u1, l.u2),
                                "phong" + at);
            const LobeSample scalar[] = {sample_ward(l.n, l.wo, alpha, l.u1, l.u2),
                                         sample_ward_duer(l.n, l.wo, alpha, l.u1, l.u2),
                                         sample_blinn_phong(l.n, l.wo, e, l.u1, l.u2)};
            const LobeSamplePacket<W>* packet[] = {&sw, &sd, &sb};
            for (int j = 0; j < 3; ++j) {
                const LobeSample& s = scalar[j];
                const std::string what = std::to_string(j) + at;
                expect_direction<W>(lane_of(packet[j]->wi, k), s.wi, "wi " + what);
                const double peak =
                    j < 2 ? 1.0 / (4 * 3.14159265 * alpha * alpha) : (e + 1.0) / (2 * 3.14159265);
                // pdf and weight divide by wo.h = |wi + wo| / 2 and scale with ci, both from
                // the sampled direction (absolute error ~1e-7): relative slack 4e-7 / cosine
                const double ci = std::fabs(glm::dot(l.n, s.wi));
                const double oh = 0.5 * glm::length(s.wi + l.wo);
                expect_match<W>(get(packet[j]->pdf, k), s.pdf, peak, worst, "pdf " + what,
                                4e-7 / oh);
                // the weight's zero test (ci > 0) is a decision on the sampled direction
                if (W == 1 || ci > 1e-5)
                    expect_match<W>(get(packet[j]->weight, k), s.weight, 1.0, worst,
                                    "weight " + what, 4e-7 / ci + 4e-7 / oh);
            }
        }
    }
    std::printf("W=%d samplers: max relative deviation %.3g\n", W, worst.rel);
}

TYPED_TEST(BrdfPacket, OpticsMatchScalar) {
    constexpr int W = TypeParam::value;
    LaneRng rng(14);
    Worst worst;
    const vec3 filters[] = {vec3(0.9f, 0.5f, 0.0f), vec3(1.0f, 0.999f, 1e-9f)};
    for (int round = 0; round < brdf_rounds; ++round) {
        const Packets<W> p = make_packets<W>(rng, round);
        const vfloat<W> r0 = p.u1 * 1.5f;
        const vfloat<W> sch = schlick<W>(r0, p.cos_i);
        const vfloat<W> fr2 = fresnel_dielectric<W>(p.cos_i, p.eta);
        const vfloat<W> fr3 = fresnel_dielectric<W>(p.cos_i, p.eta, p.u2);
        const Vec3<W> d = -p.wi;
        const Vec3<W> nf = select(dot(d, p.n) > vfloat<W>(0.0f), -p.n, p.n);
        Vec3<W> t;
        vfloat<W> cos_t;
        const vmask<W> refracts = refract_direction(d, nf, p.eta, t, cos_t);
        const Vec3<W> beer = beer_transmittance<W>(filters[round % 2], p.distance);
        for (int k = 0; k < W; ++k) {
            const Lane& l = p.lanes[size_t(k)];
            const std::string at = " lane " + std::to_string(round * W + k);
            // no transcendental functions: identical at every width
            EXPECT_EQ(get(sch, k), schlick(l.u1 * 1.5f, l.cos_i)) << at;
            EXPECT_EQ(get(fr2, k), fresnel_dielectric(l.cos_i, l.eta)) << at;
            EXPECT_EQ(get(fr3, k), fresnel_dielectric(l.cos_i, l.eta, l.u2)) << at;
            vec3 ts;
            float cts;
            const vec3 ds = -l.wi, nfs = glm::dot(ds, l.n) > 0.0f ? -l.n : l.n;
            EXPECT_EQ(get(refracts, k), refract_direction(ds, nfs, l.eta, ts, cts)) << at;
            EXPECT_EQ(lane_of(t, k), ts) << at;
            EXPECT_EQ(get(cos_t, k), cts) << at;
            expect_match<W>(lane_of(beer, k), beer_transmittance(filters[round % 2], l.distance),
                            1.0, worst, "beer" + at);
        }
    }
    std::printf("W=%d optics: max relative deviation %.3g\n", W, worst.rel);
}

}  // namespace
}  // namespace raylane
