// tests/api: raylane::Mesh's ray queries through libraylane.so: hits, misses, strided arrays,
// both paths bit for bit on a real model, and bad arrays refused with one Error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "raylane/raylane.h"
#include "support/api_error.h"

namespace {

using raylane::test::error_of;

const float inf = std::numeric_limits<float>::infinity();

/// The unit square in z = 0 as two triangles: (0,0)-(1,0)-(1,1) and (0,0)-(1,1)-(0,1).
raylane::Mesh square() {
    const float vertices[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    return raylane::Mesh(vertices, 4, triangles, 2);
}

TEST(Mesh, RaysDownOntoASquareHitTheirTriangleAndMissBesideIt) {
    const raylane::Mesh mesh = square();
    EXPECT_EQ(mesh.vertex_count(), 4u);
    EXPECT_EQ(mesh.triangle_count(), 2u);
    EXPECT_EQ(mesh.triangles()[5], 3u);
    // (N, 6) rows: origin, direction; the third misses, the fourth is NaN (never traced)
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float rays[] = {0.75f, 0.25f, 2, 0, 0, -1, 0.25f, 0.75f, 3, 0, 0, -1,
                          2.0f,  2.0f,  2, 0, 0, -1, nan,   0.5f,  2, 0, 0, -1};
    raylane::Rays r;
    r.count = 4;
    r.origins = rays;
    r.directions = rays + 3;
    r.origin_stride = r.direction_stride = 6 * sizeof(float);
    for (raylane::TracePath path : {raylane::TracePath::packet, raylane::TracePath::scalar}) {
        float t[4], u[4], v[4], normal[12];
        int32_t triangle[4];
        raylane::Hits hits;
        hits.t = t, hits.triangle = triangle, hits.u = u, hits.v = v, hits.normal = normal;
        raylane::QuerySettings settings;
        settings.path = path;
        mesh.intersect(r, hits, settings);
        EXPECT_EQ(triangle[0], 0);
        EXPECT_EQ(triangle[1], 1);
        EXPECT_FLOAT_EQ(t[0], 2.0f);
        EXPECT_FLOAT_EQ(t[1], 3.0f);
        EXPECT_FLOAT_EQ(std::abs(normal[2]), 1.0f);
        EXPECT_GE(u[0], 0.0f);
        EXPECT_LE(u[0] + v[0], 1.0f);
        for (int miss : {2, 3}) {
            EXPECT_EQ(triangle[miss], -1);
            EXPECT_EQ(t[miss], inf);
        }
        uint8_t occluded[4];
        mesh.occluded(r, occluded, settings);
        EXPECT_EQ(occluded[0], 1);
        EXPECT_EQ(occluded[1], 1);
        EXPECT_EQ(occluded[2], 0);
        EXPECT_EQ(occluded[3], 0);
        // t_max short of the square: no hit
        r.t_max_all = 1.5f;
        mesh.occluded(r, occluded, settings);
        EXPECT_EQ(occluded[0], 0);
        r.t_max_all = inf;
    }
}

TEST(Mesh, BothPathsGiveTheSameHitsOnTheBunnyBitForBit) {
    std::string path;
    try {
        path = raylane::find_model("bunny.ply");
    } catch (const raylane::Error& e) {
        GTEST_SKIP() << e.what();
    }
    const raylane::Mesh mesh = raylane::Mesh::load(path);
    ASSERT_GT(mesh.triangle_count(), 60000u);
    // rays from points around the bunny towards its vertices, jittered: most hit, some miss
    const size_t n = 20000;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> d(-0.2f, 0.2f);
    std::uniform_int_distribution<size_t> vertex(0, mesh.vertex_count() - 1);
    std::vector<float> org(3 * n), dir(3 * n);
    for (size_t i = 0; i < n; ++i) {
        const float* target = mesh.vertices() + 3 * vertex(rng);
        for (size_t k = 0; k < 3; ++k) {
            org[3 * i + k] = d(rng);
            dir[3 * i + k] = target[k] + 0.05f * d(rng) - org[3 * i + k];
        }
    }
    raylane::Rays r;
    r.count = n;
    r.origins = org.data();
    r.directions = dir.data();
    std::vector<float> t[2];
    std::vector<int32_t> tri[2];
    std::vector<uint8_t> occ[2];
    for (int p = 0; p < 2; ++p) {
        t[p].resize(n), tri[p].resize(n), occ[p].resize(n);
        raylane::Hits hits;
        hits.t = t[p].data(), hits.triangle = tri[p].data();
        raylane::QuerySettings settings;
        settings.path = p == 0 ? raylane::TracePath::packet : raylane::TracePath::scalar;
        mesh.intersect(r, hits, settings);
        mesh.occluded(r, occ[p].data(), settings);
    }
    EXPECT_EQ(tri[0], tri[1]);
    EXPECT_EQ(0, std::memcmp(t[0].data(), t[1].data(), n * sizeof(float)));
    EXPECT_EQ(occ[0], occ[1]);
    size_t hits = 0;
    for (size_t i = 0; i < n; ++i) hits += tri[0][i] >= 0;
    EXPECT_GT(hits, n / 20) << "almost every ray missed";
    EXPECT_LT(hits, n) << "every ray hit";
}

TEST(Mesh, BadArraysAreOneError) {
    const float vertices[] = {0, 0, 0, 1, 0, 0, 1, 1, 0};
    const uint32_t bad_index[] = {0, 1, 3};
    EXPECT_EQ(error_of([&] { raylane::Mesh(vertices, 3, bad_index, 1); }),
              "triangles: row 0 holds index 3, outside 0 .. 2 (vertices has 3 rows)");
    const float nan_vertex[] = {0, 0, 0, 1, std::nanf(""), 0, 1, 1, 0};
    const uint32_t ok[] = {0, 1, 2};
    EXPECT_EQ(error_of([&] { raylane::Mesh(nan_vertex, 3, ok, 1); }).rfind("vertices: row 1", 0),
              0u);
    EXPECT_EQ(error_of([&] { raylane::Mesh(nullptr, 3, ok, 1); }), "vertices: null");
    EXPECT_EQ(error_of([&] { raylane::Mesh(vertices, 3, nullptr, 1); }), "triangles: null");
    EXPECT_EQ(error_of([] { raylane::Mesh::load("no-such-model.ply"); }).find("no-such-model.ply"),
              0u);

    const raylane::Mesh mesh = square();
    float floats[12] = {};
    raylane::Rays r;
    r.count = 2;
    r.directions = floats;
    uint8_t occluded[2];
    EXPECT_EQ(error_of([&] { mesh.occluded(r, occluded); }), "origins: null, for 2 rays");
    r.origins = floats;
    EXPECT_EQ(error_of([&] { mesh.occluded(r, nullptr); }), "occluded: null, for 2 rays");
    r.origin_stride = 6;
    EXPECT_EQ(error_of([&] { mesh.occluded(r, occluded); }),
              "origin_stride: 6 bytes, not a multiple of 4");
    r.origin_stride = 12;
    alignas(4) unsigned char bytes[64] = {};
    r.origins = reinterpret_cast<const float*>(bytes + 1);
    EXPECT_EQ(error_of([&] { mesh.occluded(r, occluded); }), "origins: not aligned to 4 bytes");
    r.origins = floats;
    raylane::QuerySettings settings;
    settings.threads = -2;
    EXPECT_EQ(error_of([&] { mesh.occluded(r, occluded, settings); }),
              "threads: -2 is outside 0 .. 1024");
    // zero rays and no arrays at all: nothing to do, no error
    raylane::Rays none;
    EXPECT_EQ(error_of([&] { mesh.intersect(none, raylane::Hits{}); }), "");
}

}  // namespace
