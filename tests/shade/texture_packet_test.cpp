// Equivalence of shade/texture_packet.h with texture_scalar.h at every packet width this machine
// runs, bit for bit: texture look-ups (inactive lanes 0), latlong_uv, environment look-ups,
// normal maps and keep_above, on random and adversarial inputs.
#include "shade/texture_packet.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "io/load_image.h"
#include "shade/texture_scalar.h"
#include "support/float_values.h"
#include "support/random_unit.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

#ifdef RAYLANE_SANITIZED
constexpr int texture_rounds = 300;
#else
constexpr int texture_rounds = 6000;
#endif

float uniform(std::mt19937& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}
int pick(std::mt19937& rng, int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }

/// Same bits, or both NaN.
bool same(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) ||
           (std::isnan(a) && std::isnan(b));
}

/// A texture coordinate: ordinary, on texel centres and edges, outside [0, 1], or special.
float coordinate(std::mt19937& rng, int size) {
    const float n = static_cast<float>(size);
    switch (pick(rng, 6)) {
        case 0:
        case 1:
            return uniform(rng, 0.0f, 1.0f);
        case 2:  // texel centres and edges, and the points where the nearest rule rounds at .5
            return static_cast<float>(pick(rng, 4 * size + 1)) / (4.0f * n) +
                   static_cast<float>(pick(rng, 5) - 2);
        case 3:
            return static_cast<float>(pick(rng, 2 * size)) / (2.0f * (n - 1.0f + 1e-3f));
        case 4:
            return uniform(rng, -50.0f, 50.0f);
        default: {
            const float values[] = {0.0f,  -0.0f,  1.0f,  -1.0f,  1e-30f, -1e-30f, 1.0f - 6e-8f,
                                    1e20f, -1e20f, inf_f, -inf_f, nan_f,  2.0f,    0.5f};
            return values[pick(rng, 14)];
        }
    }
}

Texture random_image(std::mt19937& rng) {
    const int sizes[] = {1, 2, 3, 5, 8, 17};
    Texture t;
    t.width = sizes[pick(rng, 6)];
    t.height = sizes[pick(rng, 6)];
    t.filter = pick(rng, 2) ? TextureFilter::nearest : TextureFilter::bilinear;
    t.repeat = pick(rng, 2) != 0;
    t.texels.resize(static_cast<size_t>(t.width) * static_cast<size_t>(t.height) * 3);
    for (float& x : t.texels) x = uniform(rng, 0.0f, 4.0f);
    return t;
}

template <int W>
vec3 lane(const Vec3<W>& v, int i) {
    return vec3(get(v.x, i), get(v.y, i), get(v.z, i));
}

/// Packs W vectors into a Vec3<W>.
template <int W>
Vec3<W> pack(const std::vector<vec3>& v) {
    alignas(64) float x[W], y[W], z[W];
    for (int i = 0; i < W; ++i) {
        x[i] = v[static_cast<size_t>(i)].x;
        y[i] = v[static_cast<size_t>(i)].y;
        z[i] = v[static_cast<size_t>(i)].z;
    }
    return load_vec3<W>(x, y, z);
}

template <class T>
class TexturePacket : public ::testing::Test {};
TYPED_TEST_SUITE(TexturePacket, Widths, WidthName);

/// Compares lane i of a packet colour with the scalar colour; inactive lanes must be 0.
template <int W>
void expect_lane(const Vec3<W>& got, int i, bool active, vec3 want, const char* what) {
    const vec3 g = lane<W>(got, i);
    if (!active) want = vec3(0.0f);
    EXPECT_TRUE(same(g.x, want.x) && same(g.y, want.y) && same(g.z, want.z))
        << what << " lane " << i << ": packet (" << g.x << ", " << g.y << ", " << g.z
        << ") scalar (" << want.x << ", " << want.y << ", " << want.z << ")";
}

TYPED_TEST(TexturePacket, ImageLookupMatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(11 + W);
    for (int r = 0; r < texture_rounds; ++r) {
        const Texture t = random_image(rng);
        alignas(64) float us[W], vs[W];
        for (int i = 0; i < W; ++i) {
            us[i] = coordinate(rng, t.width);
            vs[i] = coordinate(rng, t.height);
        }
        const uint32_t active_bits = r % 4 == 0 ? 0xffffu : static_cast<uint32_t>(rng());
        const vmask<W> active = mask_from_bits<W>(active_bits);
        const Vec3<W> c = texture_lookup<W>(t, load<W>(us), load<W>(vs), active);
        for (int i = 0; i < W; ++i)
            expect_lane<W>(c, i, get(active, i), texture_lookup(t, vec2(us[i], vs[i])), "image");
        if (::testing::Test::HasFailure()) return;
    }
}

TYPED_TEST(TexturePacket, CheckerMatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(12 + W);
    for (int r = 0; r < texture_rounds; ++r) {
        const Texture t = make_checker(vec3(uniform(rng, 0, 1), 0.5f, 0.25f),
                                       vec3(0.0f, uniform(rng, 0, 1), 1.0f),
                                       static_cast<float>(1 + pick(rng, 16)) * 0.5f);
        alignas(64) float us[W], vs[W];
        for (int i = 0; i < W; ++i) {
            us[i] = coordinate(rng, 8);
            vs[i] = coordinate(rng, 8);
        }
        const vmask<W> active = mask_from_bits<W>(static_cast<uint32_t>(rng()));
        const Vec3<W> c = texture_lookup<W>(t, load<W>(us), load<W>(vs), active);
        for (int i = 0; i < W; ++i)
            expect_lane<W>(c, i, get(active, i), texture_lookup(t, vec2(us[i], vs[i])), "checker");
        if (::testing::Test::HasFailure()) return;
    }
}

TYPED_TEST(TexturePacket, EmptyImagesAndNoActiveLanesGiveZero) {
    constexpr int W = TypeParam::value;
    Texture empty;
    empty.width = 3;
    empty.height = 3;
    const Vec3<W> a = texture_lookup<W>(empty, vfloat<W>(0.5f), vfloat<W>(0.5f), vmask<W>(true));
    Texture full = empty;
    full.texels.assign(27, 1.0f);
    const Vec3<W> b = texture_lookup<W>(full, vfloat<W>(0.5f), vfloat<W>(0.5f), vmask<W>(false));
    const Vec3<W> c = texture_lookup<W>(full, vfloat<W>(0.5f), vfloat<W>(0.5f), vmask<W>(true));
    for (int i = 0; i < W; ++i) {
        EXPECT_EQ(lane<W>(a, i), vec3(0.0f));
        EXPECT_EQ(lane<W>(b, i), vec3(0.0f));
        EXPECT_EQ(lane<W>(c, i), vec3(1.0f));
    }
}

/// A direction: random, along or near the axes and the seam, huge, tiny, zero or NaN.
vec3 direction(std::mt19937& rng) {
    switch (pick(rng, 6)) {
        case 0:
        case 1:
            return random_unit(rng) * uniform(rng, 0.1f, 10.0f);
        case 2: {  // axes with signed zeros
            vec3 d(0.0f);
            d[pick(rng, 3)] = pick(rng, 2) ? 1.0f : -1.0f;
            for (int k = 0; k < 3; ++k)
                if (d[k] == 0.0f && pick(rng, 2)) d[k] = -0.0f;
            return d;
        }
        case 3:  // near the seam (-x) and the poles
            return vec3(-1.0f, uniform(rng, -1e-3f, 1e-3f), uniform(rng, -1e-6f, 1e-6f));
        case 4:
            return random_unit(rng) * (pick(rng, 2) ? 1e30f : 1e-30f);
        default: {
            const vec3 specials[] = {vec3(0.0f), vec3(nan_f, 0, 1), vec3(0, inf_f, 0),
                                     vec3(0, 1, 1e-30f), vec3(1e-30f, -1, 0)};
            return specials[pick(rng, 5)];
        }
    }
}

TYPED_TEST(TexturePacket, LatlongUvMatchesTheScalarBitForBit) {
    // bit for bit at every W (std::atan2 / std::asin lane by lane): a nearest look-up flips
    // texel on a one-ulp difference
    constexpr int W = TypeParam::value;
    std::mt19937 rng(13 + W);
    for (int r = 0; r < texture_rounds; ++r) {
        std::vector<vec3> dirs;
        for (int i = 0; i < W; ++i) dirs.push_back(direction(rng));
        const Uv<W> uv = latlong_uv<W>(pack<W>(dirs));
        for (int i = 0; i < W; ++i) {
            const vec2 want = latlong_uv(dirs[static_cast<size_t>(i)]);
            const float u = get(uv.u, i), v = get(uv.v, i);
            EXPECT_TRUE(same(u, want.x) && same(v, want.y))
                << "lane " << i << ": packet (" << u << ", " << v << ") scalar (" << want.x << ", "
                << want.y << ")";
            if (!std::isnan(u)) {
                EXPECT_GE(u, 0.0f);
                EXPECT_LE(u, 1.0f);
            }
            if (!std::isnan(v)) {
                EXPECT_GE(v, 0.0f);
                EXPECT_LE(v, 1.0f);
            }
        }
        if (::testing::Test::HasFailure()) return;
    }
}

TYPED_TEST(TexturePacket, EnvironmentLookupMatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(14 + W);
    for (int r = 0; r < texture_rounds; ++r) {
        const Texture t = random_image(rng);
        std::vector<vec3> dirs;
        for (int i = 0; i < W; ++i) dirs.push_back(direction(rng));
        const vmask<W> active = mask_from_bits<W>(static_cast<uint32_t>(rng()));
        const Vec3<W> d = pack<W>(dirs);
        const Uv<W> uv = latlong_uv<W>(d);
        const Vec3<W> c = environment_lookup<W>(t, d, active);
        for (int i = 0; i < W; ++i) {
            // the look-up of the packet's own uv (u repeats, v clamps) and the scalar one
            const vec2 lane_uv(get(uv.u, i), get(uv.v, i));
            expect_lane<W>(c, i, get(active, i), texture_lookup(t, lane_uv, true, false), "uv");
            expect_lane<W>(c, i, get(active, i),
                           environment_lookup(t, dirs[static_cast<size_t>(i)]), "environment");
        }
        if (::testing::Test::HasFailure()) return;
    }
}

TYPED_TEST(TexturePacket, NormalFromMapMatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(15 + W);
    for (int r = 0; r < texture_rounds; ++r) {
        glm::mat3 m(1.0f);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) m[c][k] = uniform(rng, -2.0f, 2.0f);
        std::vector<vec3> texels, normals, tangents;
        for (int i = 0; i < W; ++i) {
            vec3 texel(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
            if (pick(rng, 8) == 0) texel = vec3(0.5f);  // decodes to zero
            if (pick(rng, 8) == 0) texel = vec3(0.5f, 0.5f, 1.0f);
            vec3 n = random_unit(rng) * (pick(rng, 4) ? 1.0f : uniform(rng, 0.5f, 2.0f));
            if (pick(rng, 16) == 0) n = vec3(0, 0, pick(rng, 2) ? 1.0f : -1.0f);
            vec3 dpdu = random_unit(rng) * uniform(rng, 1e-3f, 10.0f);
            switch (pick(rng, 8)) {  // degenerate tangents
                case 0:
                    dpdu = vec3(0.0f);
                    break;
                case 1:
                    dpdu = n * 3.0f;
                    break;
                case 2:
                    dpdu = vec3(nan_f, 1, 0);
                    break;
                default:
                    break;
            }
            texels.push_back(texel);
            normals.push_back(n);
            tangents.push_back(dpdu);
        }
        for (NormalMapMode mode : {NormalMapMode::tangent, NormalMapMode::replace}) {
            const Vec3<W> got =
                normal_from_map<W>(mode, pack<W>(texels), pack<W>(normals), pack<W>(tangents), m);
            for (int i = 0; i < W; ++i) {
                const auto k = static_cast<size_t>(i);
                expect_lane<W>(got, i, true,
                               normal_from_map(mode, texels[k], normals[k], tangents[k], m),
                               mode == NormalMapMode::tangent ? "tangent" : "replace");
            }
        }
        if (::testing::Test::HasFailure()) return;
    }
}

TYPED_TEST(TexturePacket, KeepAboveMatchesTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    std::mt19937 rng(16 + W);
    for (int r = 0; r < texture_rounds; ++r) {
        std::vector<vec3> ns, refs;
        for (int i = 0; i < W; ++i) {
            const vec3 ref = random_unit(rng);
            vec3 n = random_unit(rng);
            switch (pick(rng, 6)) {
                case 0:
                    n = -ref;
                    break;
                case 1:
                    n = vec3(nan_f, 0, 0);
                    break;
                case 2:  // near the threshold
                    n = glm::normalize(n - ref * glm::dot(n, ref) + ref * uniform(rng, 0, 0.02f));
                    break;
                default:
                    break;
            }
            ns.push_back(n);
            refs.push_back(ref);
        }
        const Vec3<W> got = keep_above<W>(pack<W>(ns), pack<W>(refs));
        for (int i = 0; i < W; ++i) {
            const auto k = static_cast<size_t>(i);
            expect_lane<W>(got, i, true, keep_above(ns[k], refs[k]), "keep_above");
        }
        if (::testing::Test::HasFailure()) return;
    }
}

}  // namespace
}  // namespace raylane
