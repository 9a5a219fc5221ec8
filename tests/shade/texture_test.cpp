// tests for shade/texture_scalar.cpp: the report's nearest-texel rule and v = 1 at the top of
// the file (through a PNG written here and loaded), bilinear filtering, repeat and clamp, the
// checker, the latitude-longitude mapping's stated directions, normal maps and keep_above.
#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/load_image.h"
#include "shade/texture_scalar.h"
#include "support/float_values.h"
#include "support/random_unit.h"

namespace raylane {
namespace {

using namespace test;

namespace fs = std::filesystem;

/// A W x H image whose texel (x, y) (y from the top) is (x, y, 100 + x + 10 y): every texel
/// says where it is.
Texture coordinate_image(int width, int height, TextureFilter filter, bool repeat) {
    Texture t;
    t.width = width;
    t.height = height;
    t.filter = filter;
    t.repeat = repeat;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            t.texels.push_back(static_cast<float>(x));
            t.texels.push_back(static_cast<float>(y));
            t.texels.push_back(static_cast<float>(100 + x + 10 * y));
        }
    }
    return t;
}

vec3 texel(int x, int y) {
    return vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(100 + x + 10 * y));
}

void expect_vec_near(vec3 a, vec3 b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// image look-up ------------------------------------------------------------------------------

TEST(TextureLookup, PutsVOneAtTheTopRowOfAPngFile) {
    // 2 x 2 file: top row red, green; bottom row blue, white
    const std::vector<uint8_t> pixels = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    const fs::path path =
        fs::temp_directory_path() / ("raylane_texture_test_" + std::to_string(getpid()) + ".png");
    ASSERT_NE(stbi_write_png(path.c_str(), 2, 2, 3, pixels.data(), 6), 0);
    Texture t = load_texture(path.string());
    fs::remove(path);
    for (bool repeat : {false, true}) {
        t.repeat = repeat;
        t.filter = TextureFilter::nearest;
        EXPECT_EQ(texture_lookup(t, vec2(0.0f, 1.0f)), vec3(1, 0, 0));    // top left
        EXPECT_EQ(texture_lookup(t, vec2(0.9f, 0.9f)), vec3(0, 1, 0));    // top right
        EXPECT_EQ(texture_lookup(t, vec2(0.1f, 0.0f)), vec3(0, 0, 1));    // bottom left
        EXPECT_EQ(texture_lookup(t, vec2(0.99f, 0.01f)), vec3(1, 1, 1));  // bottom right
        // bilinear: at the texel centres the texels themselves
        t.filter = TextureFilter::bilinear;
        EXPECT_EQ(texture_lookup(t, vec2(0.25f, 0.75f)), vec3(1, 0, 0));
        EXPECT_EQ(texture_lookup(t, vec2(0.75f, 0.25f)), vec3(1, 1, 1));
        // between all four centres: their mean
        expect_vec_near(texture_lookup(t, vec2(0.5f, 0.5f)), vec3(0.5f, 0.5f, 0.5f), 1e-6f);
    }
}

TEST(TextureLookup, NearestFollowsTheReportsRoundingRule) {
    // column round(u (W - 1)), row round((1 - v) (H - 1)), for u, v in [0, 1]
    const Texture t = coordinate_image(5, 3, TextureFilter::nearest, false);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const float u = i < 3 ? 0.5f * static_cast<float>(i) : unit(rng);
        const float v = i < 3 ? 0.5f * static_cast<float>(i) : unit(rng);
        const int x = static_cast<int>(std::lround(static_cast<double>(u) * 4.0));
        const int y = static_cast<int>(std::lround((1.0 - static_cast<double>(v)) * 2.0));
        EXPECT_EQ(texture_lookup(t, vec2(u, v)), texel(x, y)) << u << " " << v;
    }
    // halfway between two columns rounds away from zero: u (W - 1) = 0.5 -> column 1
    EXPECT_EQ(texture_lookup(t, vec2(0.125f, 1.0f)), texel(1, 0));
    EXPECT_EQ(texture_lookup(t, vec2(0.124f, 1.0f)), texel(0, 0));
}

TEST(TextureLookup, BilinearBlendsTheFourNearestTexelCentres) {
    const int w = 4, h = 3;
    const Texture t = coordinate_image(w, h, TextureFilter::bilinear, false);
    // a point a quarter of the way from centre (1, 1) to centre (2, 2): x = 1.25, y = 1.25
    const float u = (1.25f + 0.5f) / w;
    const float v = 1.0f - (1.25f + 0.5f) / h;
    const vec3 expected = (texel(1, 1) * 0.75f + texel(2, 1) * 0.25f) * 0.75f +
                          (texel(1, 2) * 0.75f + texel(2, 2) * 0.25f) * 0.25f;
    expect_vec_near(texture_lookup(t, vec2(u, v)), expected, 1e-5f);
    // every texel centre returns the texel exactly
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec2 uv((static_cast<float>(x) + 0.5f) / w,
                          1.0f - (static_cast<float>(y) + 0.5f) / h);
            expect_vec_near(texture_lookup(t, uv), texel(x, y), 1e-5f);
        }
}

TEST(TextureLookup, BilinearWrapsOrClampsAtTheEdges) {
    const int w = 4, h = 3;
    Texture t = coordinate_image(w, h, TextureFilter::bilinear, true);
    // u = 0 under repeat: halfway between the last and the first column
    const float v_row1 = 1.0f - 1.5f / h;
    expect_vec_near(texture_lookup(t, vec2(0.0f, v_row1)), (texel(3, 1) + texel(0, 1)) * 0.5f,
                    1e-5f);
    expect_vec_near(texture_lookup(t, vec2(1.0f, v_row1)), (texel(3, 1) + texel(0, 1)) * 0.5f,
                    1e-5f);
    // v = 1 under repeat: halfway between the top and the bottom row
    expect_vec_near(texture_lookup(t, vec2(1.5f / w, 1.0f)), (texel(1, 0) + texel(1, 2)) * 0.5f,
                    1e-5f);
    t.repeat = false;  // clamp: the edge texel
    expect_vec_near(texture_lookup(t, vec2(0.0f, v_row1)), texel(0, 1), 1e-5f);
    expect_vec_near(texture_lookup(t, vec2(1.0f, v_row1)), texel(3, 1), 1e-5f);
    expect_vec_near(texture_lookup(t, vec2(-3.0f, 7.0f)), texel(0, 0), 1e-5f);
    expect_vec_near(texture_lookup(t, vec2(2.0f, -1.0f)), texel(3, 2), 1e-5f);
}

TEST(TextureLookup, RepeatWrapsNegativeAndLargeCoordinates) {
    for (TextureFilter filter : {TextureFilter::nearest, TextureFilter::bilinear}) {
        const Texture t = coordinate_image(5, 4, filter, true);
        // quarters are exact in float, so u + k wraps to exactly u
        for (float u : {0.25f, 0.5f, 0.75f}) {
            for (float v : {0.25f, 0.5f, 0.75f}) {
                const vec3 base = texture_lookup(t, vec2(u, v));
                for (float k : {-1000.0f, -3.0f, -1.0f, 1.0f, 2.0f, 4096.0f}) {
                    EXPECT_EQ(texture_lookup(t, vec2(u + k, v)), base) << u << " " << k;
                    EXPECT_EQ(texture_lookup(t, vec2(u, v + k)), base) << v << " " << k;
                }
            }
        }
        // integers: 0 and 1 are kept as they are (the two edges, v = 1 the top row); every other
        // integer wraps to 0
        const vec3 zero = texture_lookup(t, vec2(0.0f, 0.5f));
        for (float k : {-1000.0f, -1.0f, 2.0f, 3.0f, 1e9f})
            EXPECT_EQ(texture_lookup(t, vec2(k, 0.5f)), zero) << k;
        const vec3 top = texture_lookup(t, vec2(0.5f, 1.0f));
        if (filter == TextureFilter::nearest) {
            EXPECT_EQ(texture_lookup(t, vec2(1.0f, 0.5f)), texture_lookup(t, vec2(0.999f, 0.5f)));
            EXPECT_EQ(top.y, 0.0f);
        } else {
            EXPECT_EQ(texture_lookup(t, vec2(1.0f, 0.5f)), zero);  // both halfway across the seam
            EXPECT_EQ(top, texture_lookup(t, vec2(0.5f, 0.0f)));
        }
    }
}

TEST(TextureLookup, StaysInBoundsForExtremeCoordinates) {
    const float big = std::numeric_limits<float>::max();
    const float specials[] = {0.0f,  -0.0f,  1.0f, -1e-30f, 1e-30f, 1.0f - 1e-7f, -1e-7f,
                              1e30f, -1e30f, big,  -big,    inf_f,  -inf_f,       nan_f};
    for (int w : {1, 2, 7}) {
        for (int h : {1, 3}) {
            for (TextureFilter filter : {TextureFilter::nearest, TextureFilter::bilinear}) {
                for (bool repeat : {false, true}) {
                    const Texture t = coordinate_image(w, h, filter, repeat);
                    for (float u : specials) {
                        for (float v : specials) {
                            const vec3 c = texture_lookup(t, vec2(u, v));
                            if (std::isnan(u) || std::isnan(v)) {
                                EXPECT_EQ(c, vec3(0.0f));  // NaN coordinates: black
                                continue;
                            }
                            // a blend of texels: inside the range of the texel values
                            EXPECT_GE(c.x, 0.0f);
                            EXPECT_LE(c.x, static_cast<float>(w - 1) + 1e-4f);
                            EXPECT_GE(c.y, 0.0f);
                            EXPECT_LE(c.y, static_cast<float>(h - 1) + 1e-4f);
                        }
                    }
                }
            }
        }
    }
}

TEST(TextureLookup, ReturnsBlackForAnImageWithoutTexels) {
    Texture t;
    t.width = 4;
    t.height = 4;
    EXPECT_EQ(texture_lookup(t, vec2(0.5f, 0.5f)), vec3(0.0f));
    t.texels.assign(4 * 4 * 3 - 1, 1.0f);  // one float short
    EXPECT_EQ(texture_lookup(t, vec2(0.5f, 0.5f)), vec3(0.0f));
}

TEST(TextureLookup, CheckerAlternatesOnFloorParity) {
    const vec3 a(1.0f, 0.5f, 0.25f), b(0.0f, 0.125f, 1.0f);
    const Texture t = make_checker(a, b, 4.0f);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> any(-10.0f, 10.0f);
    for (int i = 0; i < 2000; ++i) {
        const float u = any(rng), v = any(rng);
        const double sum = std::floor(double{u} * 4.0f) + std::floor(double{v} * 4.0f);
        const bool even = std::fmod(std::fabs(sum), 2.0) == 0.0;
        EXPECT_EQ(texture_lookup(t, vec2(u, v)), even ? a : b) << u << " " << v;
    }
    EXPECT_EQ(texture_lookup(t, vec2(0.1f, 0.1f)), a);
    EXPECT_EQ(texture_lookup(t, vec2(0.3f, 0.1f)), b);
    EXPECT_EQ(texture_lookup(t, vec2(-0.1f, 0.1f)), b);  // floor(-0.4) = -1
    EXPECT_EQ(texture_lookup(t, vec2(-0.1f, -0.1f)), a);
    EXPECT_EQ(texture_lookup(t, vec2(nan_f, 0.1f)), vec3(0.0f));
    EXPECT_EQ(texture_lookup(t, vec2(std::numeric_limits<float>::infinity(), 0.1f)), b);
}

// latitude-longitude environment --------------------------------------------------------------

TEST(LatlongUv, MapsTheReportsDirections) {
    // report-scenes.md 1.6: up is the top row (v = 1), the horizon v = 1/2, -z is u = 1/4,
    // +x u = 1/2, +z u = 3/4, -x the seam
    EXPECT_EQ(latlong_uv(vec3(0, 1, 0)), vec2(0.5f, 1.0f));  // poles: u = 1/2, exactly v = 1
    EXPECT_EQ(latlong_uv(vec3(0, -1, 0)), vec2(0.5f, 0.0f));
    EXPECT_EQ(latlong_uv(vec3(-0.0f, 2, -0.0f)), vec2(0.5f, 1.0f));
    for (float scale : {1.0f, 3.5f, 1e-20f, 1e20f}) {
        SCOPED_TRACE(scale);
        EXPECT_FLOAT_EQ(latlong_uv(vec3(0, 0, -1) * scale).x, 0.25f);
        EXPECT_FLOAT_EQ(latlong_uv(vec3(1, 0, 0) * scale).x, 0.5f);
        EXPECT_FLOAT_EQ(latlong_uv(vec3(0, 0, 1) * scale).x, 0.75f);
        EXPECT_FLOAT_EQ(latlong_uv(vec3(0, 0, 1) * scale).y, 0.5f);
        EXPECT_FLOAT_EQ(latlong_uv(vec3(0, 1, 0) * scale).y, 1.0f);
        EXPECT_NEAR(latlong_uv(vec3(1, 1, 0) * scale).y, 0.75f, 1e-6f);  // 45 degrees up
    }
    const float seam_a = latlong_uv(vec3(-1, 0, 0)).x;
    const float seam_b = latlong_uv(vec3(-1, 0, -0.0f)).x;
    EXPECT_TRUE(seam_a == 0.0f || seam_a == 1.0f) << seam_a;
    EXPECT_TRUE(seam_b == 0.0f || seam_b == 1.0f) << seam_b;
}

TEST(EnvironmentLookup, ReadsTheTexelTheDirectionNames) {
    // 8 x 4 coordinate image, nearest and clamped as in the report
    const Texture t = coordinate_image(8, 4, TextureFilter::nearest, false);
    EXPECT_EQ(environment_lookup(t, vec3(0, 1, 0)).y, 0.0f);   // up: top row
    EXPECT_EQ(environment_lookup(t, vec3(0, -1, 0)).y, 3.0f);  // down: bottom row
    // the standard camera looks along +z: the column at 3/4 of the width
    EXPECT_EQ(environment_lookup(t, vec3(0, 0, 1)).x, std::round(0.75f * 7.0f));
    EXPECT_EQ(environment_lookup(t, vec3(1, 0, 0)).x, std::round(0.5f * 7.0f));
    // every direction, seam and poles included, reads a real texel
    std::mt19937 rng(3);
    std::normal_distribution<float> gauss;
    for (bool repeat : {false, true}) {
        Texture e = coordinate_image(8, 4, TextureFilter::bilinear, repeat);
        for (int i = 0; i < 3000; ++i) {
            vec3 d(gauss(rng), gauss(rng), gauss(rng));
            if (i % 3 == 0) d.x = 0.0f;
            if (i % 5 == 0) d.z = i % 2 ? 0.0f : -0.0f;
            if (i % 7 == 0) d = vec3(-1.0f, 0.0f, i % 2 ? 0.0f : -0.0f);
            const vec2 uv = latlong_uv(d);
            ASSERT_GE(uv.x, 0.0f);
            ASSERT_LE(uv.x, 1.0f);
            ASSERT_GE(uv.y, 0.0f);
            ASSERT_LE(uv.y, 1.0f);
            const vec3 c = environment_lookup(e, d);
            ASSERT_GE(c.z, 100.0f);
            ASSERT_LE(c.z, 100.0f + 7.0f + 30.0f);
        }
        // bilinear at the poles: the top (bottom) row only, never blended with the other pole;
        // at the seam: halfway between the last and the first column, from either side
        EXPECT_EQ(environment_lookup(e, vec3(0, 1, 0)).y, 0.0f);
        EXPECT_EQ(environment_lookup(e, vec3(0, -1, 0)).y, 3.0f);
        EXPECT_FLOAT_EQ(environment_lookup(e, vec3(-1, 0, 0)).x, 3.5f);
        EXPECT_FLOAT_EQ(environment_lookup(e, vec3(-1, 0, -0.0f)).x, 3.5f);
        EXPECT_EQ(environment_lookup(e, vec3(0.0f)), vec3(0.0f));  // no direction: black
        EXPECT_EQ(environment_lookup(e, vec3(nan_f, 0, 1)), vec3(0.0f));
    }
}

// normal maps --------------------------------------------------------------------------------

TEST(NormalFromMap, FlatTangentTexelReturnsTheNormal) {
    std::mt19937 rng(4);
    for (int i = 0; i < 1000; ++i) {
        const vec3 n = random_unit(rng);
        const vec3 dpdu = random_unit(rng) * 3.0f;
        expect_vec_near(normal_from_map(NormalMapMode::tangent, vec3(0.5f, 0.5f, 1.0f), n, dpdu,
                                        glm::mat3(1.0f)),
                        n, 1e-6f);
    }
}

TEST(NormalFromMap, TangentAxesAreDpduAndNCrossDpdu) {
    const vec3 n(0, 0, 1);
    const vec3 dpdu(2, 0, 1);  // not perpendicular to n: its tangent part is +x
    const glm::mat3 id(1.0f);
    const auto map = [&](vec3 texel) {
        return normal_from_map(NormalMapMode::tangent, texel, n, dpdu, id);
    };
    expect_vec_near(map(vec3(1.0f, 0.5f, 0.5f)), vec3(1, 0, 0), 1e-6f);   // red: +T
    expect_vec_near(map(vec3(0.0f, 0.5f, 0.5f)), vec3(-1, 0, 0), 1e-6f);  // -T
    expect_vec_near(map(vec3(0.5f, 1.0f, 0.5f)), vec3(0, 1, 0), 1e-6f);   // green: +v
    expect_vec_near(map(vec3(0.5f, 0.0f, 0.5f)), vec3(0, -1, 0), 1e-6f);
    expect_vec_near(map(vec3(1.0f, 0.5f, 1.0f)), glm::normalize(vec3(1, 0, 1)), 1e-6f);
    // a tilted frame: the result is m.x T + m.y B + m.z n with T = dpdu's tangent part
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 1000; ++i) {
        const vec3 nn = random_unit(rng);
        const vec3 du = random_unit(rng);
        if (std::fabs(glm::dot(nn, du)) > 0.99f) continue;
        const vec3 t = glm::normalize(du - nn * glm::dot(nn, du));
        const vec3 b = glm::cross(nn, t);
        const vec3 texel(unit(rng), unit(rng), unit(rng));
        const vec3 m = texel * 2.0f - 1.0f;
        if (glm::dot(m, m) < 1e-3f) continue;
        expect_vec_near(normal_from_map(NormalMapMode::tangent, texel, nn, du, id),
                        glm::normalize(m.x * t + m.y * b + m.z * nn), 2e-6f);
    }
}

TEST(NormalFromMap, DegenerateTangentsAndTexelsStayFinite) {
    const glm::mat3 id(1.0f);
    std::mt19937 rng(6);
    for (int i = 0; i < 500; ++i) {
        // numerics.md 13's hard cases for a basis: n = (0, 0, +-1), normalize(1e-8, 0, -1)
        const vec3 special[] = {vec3(0, 0, 1), vec3(0, 0, -1), glm::normalize(vec3(1e-8f, 0, -1)),
                                glm::normalize(vec3(0, -1e-8f, 1))};
        const vec3 n = i < 4 ? special[i] : random_unit(rng);
        const vec3 dpdus[] = {vec3(0.0f), n * 2.0f, -n, vec3(nan_f, 0, 0),
                              vec3(std::numeric_limits<float>::infinity(), 0, 0)};
        for (vec3 dpdu : dpdus) {
            // red and green: T and B of a right-handed orthonormal frame around n
            const vec3 t =
                normal_from_map(NormalMapMode::tangent, vec3(1, 0.5f, 0.5f), n, dpdu, id);
            const vec3 b =
                normal_from_map(NormalMapMode::tangent, vec3(0.5f, 1, 0.5f), n, dpdu, id);
            EXPECT_NEAR(glm::length(t), 1.0f, 1e-6f);
            EXPECT_NEAR(glm::length(b), 1.0f, 1e-6f);
            EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-6f);
            EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-6f);
            EXPECT_NEAR(glm::dot(t, b), 0.0f, 1e-6f);
            expect_vec_near(glm::cross(t, b), n, 1e-6f);
        }
        // a texel decoding to the zero vector gives n (numerics.md 13)
        expect_vec_near(normal_from_map(NormalMapMode::tangent, vec3(0.5f), n, vec3(1, 0, 0), id),
                        n, 1e-6f);
        expect_vec_near(normal_from_map(NormalMapMode::replace, vec3(0.5f), n, vec3(1, 0, 0), id),
                        n, 1e-6f);
    }
    // an unnormalized n is normalized (the report's interpolated normals are not)
    expect_vec_near(normal_from_map(NormalMapMode::tangent, vec3(0.5f, 0.5f, 1.0f), vec3(0, 3, 0),
                                    vec3(1, 0, 0), id),
                    vec3(0, 1, 0), 1e-6f);
}

TEST(NormalFromMap, ReplaceModeTransformsTheTexelAsAnObjectSpaceNormal) {
    // the report: n = RGB - 1/2 in object space, then normal_to_world; here a 90 degree turn
    // about z (x -> y, y -> -x)
    glm::mat3 turn(0.0f);
    turn[0] = vec3(0, 1, 0);   // column 0: image of x
    turn[1] = vec3(-1, 0, 0);  // image of y
    turn[2] = vec3(0, 0, 1);
    const vec3 n(0, 0, 1), dpdu(1, 0, 0);
    expect_vec_near(normal_from_map(NormalMapMode::replace, vec3(1.0f, 0.5f, 0.5f), n, dpdu, turn),
                    vec3(0, 1, 0), 1e-6f);
    expect_vec_near(normal_from_map(NormalMapMode::replace, vec3(0.5f, 0.0f, 0.5f), n, dpdu, turn),
                    vec3(1, 0, 0), 1e-6f);
    // not scaled by 2 and not affected by n or dp/du: only the direction of RGB - 1/2 counts
    const vec3 texel(0.9f, 0.2f, 0.6f);
    expect_vec_near(
        normal_from_map(NormalMapMode::replace, texel, vec3(1, 0, 0), vec3(0, 1, 0), turn),
        glm::normalize(turn * (texel - 0.5f)), 1e-6f);
    // a non-uniform scale diag(2, 1, 1) has normal_to_world diag(1/2, 1, 1)
    const glm::mat3 squash(vec3(0.5f, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1));
    expect_vec_near(
        normal_from_map(NormalMapMode::replace, vec3(1.0f, 1.0f, 0.5f), n, dpdu, squash),
        glm::normalize(vec3(0.25f, 0.5f, 0.0f)), 1e-6f);
}

TEST(NormalFromMap, AlwaysReturnsAUnitVector) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    glm::mat3 m(1.0f);
    m[0] = vec3(1.5f, 0.2f, 0.0f);
    for (int i = 0; i < 2000; ++i) {
        const vec3 texel(unit(rng), unit(rng), unit(rng));
        for (NormalMapMode mode : {NormalMapMode::tangent, NormalMapMode::replace}) {
            const vec3 r = normal_from_map(mode, texel, random_unit(rng), random_unit(rng), m);
            EXPECT_NEAR(glm::length(r), 1.0f, 1e-5f);
        }
    }
}

// keep_above ---------------------------------------------------------------------------------

TEST(KeepAbove, LeavesNormalsInTheHemisphereAlone) {
    std::mt19937 rng(8);
    for (int i = 0; i < 1000; ++i) {
        const vec3 r = random_unit(rng);
        vec3 ns = random_unit(rng);
        if (glm::dot(ns, r) < 0.02f) ns = glm::normalize(ns + r * (0.05f - glm::dot(ns, r)));
        if (glm::dot(ns, r) < texture_detail::keep_above_cos) continue;
        EXPECT_EQ(keep_above(ns, r), ns);
    }
}

TEST(KeepAbove, BendsNormalsBelowTheHemisphereJustAboveIt) {
    // numerics.md 13: normals tilted up to and past 90 degrees, in random directions
    std::mt19937 rng(9);
    for (int i = 0; i < 3000; ++i) {
        const vec3 r = random_unit(rng);
        const vec3 ns = random_unit(rng);
        const vec3 k = keep_above(ns, r);
        ASSERT_NEAR(glm::length(k), 1.0f, 1e-5f);
        ASSERT_GE(glm::dot(k, r), texture_detail::keep_above_cos - 1e-5f);
        if (glm::dot(ns, r) >= texture_detail::keep_above_cos) continue;
        EXPECT_NEAR(glm::dot(k, r), texture_detail::keep_above_cos, 1e-5f);
        // in the plane of ns and r, on ns's side
        EXPECT_NEAR(glm::dot(k, glm::normalize(glm::cross(ns, r))), 0.0f, 1e-4f);
        const vec3 ns_tangent = ns - r * glm::dot(ns, r);
        EXPECT_GT(glm::dot(k, ns_tangent), 0.0f);
    }
    const vec3 r(0, 1, 0);
    EXPECT_EQ(keep_above(-r, r), r);  // opposite: no direction to bend towards
    EXPECT_EQ(keep_above(vec3(nan_f, 0, 0), r), r);
    expect_vec_near(keep_above(vec3(1, 0, 0), r),
                    vec3(std::sqrt(1.0f - 0.01f * 0.01f), 0.01f, 0.0f), 1e-6f);
}

}  // namespace
}  // namespace raylane
