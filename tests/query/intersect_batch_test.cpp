// Tests of query/intersect_batch.cpp: the packet path over ray arrays (blocks, streams, and the
// automatic choice between them) gives the scalar path's hits bit for bit; rays that cannot be
// traced are misses; strided arrays, per-ray t_max and empty batches.
#include "query/intersect_batch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>

namespace raylane {
namespace {

/// A scene of one mesh: 3000 random triangles in the unit cube (fixed seed).
struct BatchScene {
    SceneData scene;
    Accel accel;
    BatchScene() {
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> uni(0.0f, 1.0f), small(-0.05f, 0.05f);
        MeshData mesh;
        for (uint32_t i = 0; i < 3000; ++i) {
            const vec3 c(uni(rng), uni(rng), uni(rng));
            for (int k = 0; k < 3; ++k)
                mesh.positions.push_back(c + vec3(small(rng), small(rng), small(rng)));
            mesh.tris.push_back(glm::uvec3(3 * i, 3 * i + 1, 3 * i + 2));
        }
        scene.materials.push_back(Material{});
        scene.meshes.push_back(mesh);
        Object object;
        object.kind = ShapeKind::mesh;
        scene.objects.push_back(object);
        accel = build_accel(scene, BuildParams{});
    }
};

/// (N, 6) rays: the first half from one point in a narrow cone (coherent, in blocks of 256),
/// the rest from random points in random directions.
std::vector<float> batch_rays(size_t count) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    std::vector<float> rays;
    for (size_t i = 0; i < count; ++i) {
        vec3 o, d;
        if (i < count / 2) {
            o = vec3(0.5f, 0.5f, -2.0f);
            d = vec3(0.2f * uni(rng), 0.2f * uni(rng), 1.0f);
        } else {
            o = vec3(0.5f) + vec3(uni(rng), uni(rng), uni(rng));
            d = vec3(uni(rng), uni(rng), uni(rng));
        }
        rays.insert(rays.end(), {o.x, o.y, o.z, d.x, d.y, d.z});
    }
    return rays;
}

struct BatchHits {
    std::vector<float> t, u, v, normal;
    std::vector<int32_t> prim, object;
    explicit BatchHits(size_t n) : t(n), u(n), v(n), normal(3 * n), prim(n), object(n) {}
    HitBuffers buffers() {
        return {t.data(), prim.data(), object.data(), u.data(), v.data(), normal.data()};
    }
};

RayArrays batch_arrays(const std::vector<float>& rays) {
    RayArrays a;
    a.org = rays.data(), a.dir = rays.data() + 3;
    a.org_stride = a.dir_stride = 6;
    a.count = rays.size() / 6;
    return a;
}

bool batch_same_bits(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
}

void expect_same_batch_hits(const BatchHits& a, const BatchHits& b) {
    size_t bad = 0;
    for (size_t i = 0; i < a.t.size(); ++i) {
        bool same = a.prim[i] == b.prim[i] && a.object[i] == b.object[i] &&
                    batch_same_bits(a.t[i], b.t[i]) && batch_same_bits(a.u[i], b.u[i]) &&
                    batch_same_bits(a.v[i], b.v[i]);
        for (int k = 0; k < 3; ++k)
            same = same && batch_same_bits(a.normal[3 * i + k], b.normal[3 * i + k]);
        bad += !same;
    }
    EXPECT_EQ(bad, 0u);
}

TEST(IntersectBatch, PacketPathMatchesScalarPathBitForBit) {
    const BatchScene m;
    const std::vector<float> rays = batch_rays(20000);
    const RayArrays a = batch_arrays(rays);
    BatchHits scalar(a.count);
    intersect_closest_batch(m.scene, m.accel, a, scalar.buffers(),
                            {BatchPath::scalar, Coherence::automatic, 0});
    size_t hits = 0;
    for (int32_t p : scalar.prim) hits += p >= 0;
    EXPECT_GT(hits, a.count / 10);
    EXPECT_LT(hits, a.count);
    std::vector<uint8_t> blocked(a.count);
    intersect_any_batch(m.scene, m.accel, a, blocked.data(),
                        {BatchPath::scalar, Coherence::automatic, 0});
    for (size_t i = 0; i < a.count; ++i) EXPECT_EQ(blocked[i], scalar.prim[i] >= 0 ? 1 : 0);
    for (Coherence c : {Coherence::automatic, Coherence::coherent, Coherence::incoherent}) {
        for (int threads : {1, 2}) {
            BatchHits packet(a.count);
            intersect_closest_batch(m.scene, m.accel, a, packet.buffers(),
                                    {BatchPath::packet, c, threads});
            expect_same_batch_hits(packet, scalar);
            // the normals from a table of the triangles' normals: the same bits
            const TriangleNormals normals = make_triangle_normals(m.scene);
            BatchHits tabled(a.count);
            intersect_closest_batch(m.scene, m.accel, a, tabled.buffers(),
                                    {BatchPath::packet, c, threads}, &normals);
            expect_same_batch_hits(tabled, scalar);
            std::vector<uint8_t> occluded(a.count, 7);
            intersect_any_batch(m.scene, m.accel, a, occluded.data(),
                                {BatchPath::packet, c, threads});
            EXPECT_EQ(occluded, blocked);
        }
    }
}

TEST(IntersectBatch, AutomaticChoiceTellsCoherentBlocksFromScatteredOnes) {
    const std::vector<float> rays = batch_rays(1024);
    const RayArrays a = batch_arrays(rays);
    EXPECT_TRUE(rays_coherent(a, 0, 256));
    EXPECT_TRUE(rays_coherent(a, 256, 256));
    EXPECT_FALSE(rays_coherent(a, 512, 256));
    EXPECT_FALSE(rays_coherent(a, 768, 256));
}

TEST(IntersectBatch, RaysThatCannotBeTracedAreMisses) {
    const BatchScene m;
    const float nan = std::nanf("");
    // a good ray at the cube, then NaN origin, infinite origin, NaN direction, zero direction
    std::vector<float> rays = {0.5f,  0.5f, -2.0f, 0.0f, 0.0f,      1.0f, nan,   0.5f, -2.0f, 0.0f,
                               0.0f,  1.0f, 0.5f,  0.5f, -infinity, 0.0f, 0.0f,  1.0f, 0.5f,  0.5f,
                               -2.0f, nan,  0.0f,  1.0f, 0.5f,      0.5f, -2.0f, 0.0f, 0.0f,  0.0f};
    for (BatchPath path : {BatchPath::scalar, BatchPath::packet}) {
        BatchHits h(5);
        intersect_closest_batch(m.scene, m.accel, batch_arrays(rays), h.buffers(),
                                {path, Coherence::automatic, 0});
        EXPECT_GE(h.prim[0], 0);
        for (size_t i = 1; i < 5; ++i) {
            EXPECT_EQ(h.prim[i], -1) << i;
            EXPECT_EQ(h.t[i], infinity) << i;
            EXPECT_EQ(h.normal[3 * i + 2], 0.0f) << i;
        }
        std::vector<uint8_t> occluded(5, 7);
        intersect_any_batch(m.scene, m.accel, batch_arrays(rays), occluded.data(),
                            {path, Coherence::automatic, 0});
        EXPECT_EQ(occluded, (std::vector<uint8_t>{1, 0, 0, 0, 0}));
    }
}

TEST(IntersectBatch, PerRayTmaxAndSeparateArrays) {
    const BatchScene m;
    const std::vector<float> org = {0.5f, 0.5f, -2.0f, 0.5f, 0.5f, -2.0f};
    const std::vector<float> dir = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f};
    const std::vector<float> t_max = {1.0f, infinity};  // the cube starts at z = -0.05
    RayArrays a;
    a.org = org.data(), a.dir = dir.data(), a.t_max = t_max.data(), a.count = 2;
    for (BatchPath path : {BatchPath::scalar, BatchPath::packet}) {
        BatchHits h(2);
        intersect_closest_batch(m.scene, m.accel, a, h.buffers(), {path, Coherence::automatic, 0});
        EXPECT_EQ(h.prim[0], -1);
        EXPECT_GE(h.prim[1], 0);
        EXPECT_GT(h.t[1], 1.9f);
        EXPECT_NEAR(glm::length(vec3(h.normal[3], h.normal[4], h.normal[5])), 1.0f, 1e-6f);
    }
}

TEST(IntersectBatch, EmptyBatchWritesNothing) {
    const BatchScene m;
    const std::vector<float> rays = batch_rays(4);
    RayArrays a = batch_arrays(rays);
    a.count = 0;
    BatchHits h(4);
    h.t.assign(4, 5.0f);
    intersect_closest_batch(m.scene, m.accel, a, h.buffers(), {});
    EXPECT_EQ(h.t, std::vector<float>(4, 5.0f));
    std::vector<uint8_t> occluded(4, 7);
    intersect_any_batch(m.scene, m.accel, a, occluded.data(), {});
    EXPECT_EQ(occluded, std::vector<uint8_t>(4, 7));
}

TEST(IntersectBatch, SceneWithoutObjectsGivesMisses) {
    SceneData scene;
    const Accel accel = build_accel(scene, BuildParams{});
    const std::vector<float> rays = batch_rays(600);
    const RayArrays a = batch_arrays(rays);
    for (BatchPath path : {BatchPath::scalar, BatchPath::packet}) {
        BatchHits h(a.count);
        intersect_closest_batch(scene, accel, a, h.buffers(), {path, Coherence::automatic, 0});
        EXPECT_EQ(h.prim, std::vector<int32_t>(a.count, -1));
        std::vector<uint8_t> occluded(a.count, 7);
        intersect_any_batch(scene, accel, a, occluded.data(), {path, Coherence::automatic, 0});
        EXPECT_EQ(occluded, std::vector<uint8_t>(a.count, 0));
    }
}

}  // namespace
}  // namespace raylane
