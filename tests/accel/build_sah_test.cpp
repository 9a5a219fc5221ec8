// Tests of accel/build_sah.cpp: the binned SAH build (a comparison option) keeps the BVH
// invariants, its depth within the traversal stack, and is a better tree than the median split
// by the SAH measure.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "accel/bvh.h"
#include "io/load_mesh.h"
#include "support/models.h"
#include "support/random_boxes.h"

namespace raylane {
namespace {

BuildParams sah(int leaf = 4) {
    return BuildParams{.max_leaf_size = leaf, .method = BvhBuild::sah};
}

TEST(BuildSah, EmptyAndSingleInputs) {
    EXPECT_TRUE(build_bvh_sah({}, sah()).nodes.empty());
    const std::vector<Aabb> one = random_boxes(1, 1);
    const Bvh bvh = build_bvh_sah(one, sah());
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_TRUE(bvh.nodes[0].is_leaf());
    EXPECT_EQ(check_bvh(bvh, one, 4), "");
}

TEST(BuildSah, HoldsInvariantsForEveryLeafSize) {
    for (int leaf : {1, 2, 4, 5, 8}) {
        for (size_t n : {2u, 3u, 7u, 100u, 1000u, 4097u}) {
            const std::vector<Aabb> boxes = random_boxes(n, static_cast<uint32_t>(n + leaf));
            const Bvh bvh = build_bvh_sah(boxes, sah(leaf));
            EXPECT_EQ(check_bvh(bvh, boxes, leaf), "") << "n=" << n << " leaf=" << leaf;
        }
    }
}

TEST(BuildSah, FirstChildHoldsTheLowerCentroidsOnTheSplitAxis) {
    const std::vector<Aabb> boxes = random_boxes(2000, 3);
    const Bvh bvh = build_bvh_sah(boxes, sah());
    std::vector<uint32_t> first(bvh.nodes.size()), end(bvh.nodes.size());
    for (size_t i = bvh.nodes.size(); i-- > 0;) {  // each node's primitive range, bottom up
        const BvhNode& n = bvh.nodes[i];
        first[i] = n.is_leaf() ? n.index : first[i + 1];
        end[i] = n.is_leaf() ? n.index + n.count : end[n.index];
    }
    size_t interior = 0;
    for (size_t i = 0; i < bvh.nodes.size(); ++i) {
        const BvhNode& n = bvh.nodes[i];
        if (n.is_leaf()) continue;
        ++interior;
        float hi_first = -infinity, lo_second = infinity;
        for (uint32_t k = first[i + 1]; k < end[i + 1]; ++k)
            hi_first = std::max(hi_first, boxes[bvh.prim_ids[k]].center()[n.axis]);
        for (uint32_t k = first[n.index]; k < end[n.index]; ++k)
            lo_second = std::min(lo_second, boxes[bvh.prim_ids[k]].center()[n.axis]);
        EXPECT_LE(hi_first, lo_second) << "node " << i;
    }
    EXPECT_GT(interior, 100u);
}

TEST(BuildSah, AllCentroidsEqualFallBackToHalves) {
    std::vector<Aabb> boxes(300, Aabb{vec3(1.0f), vec3(2.0f)});
    const Bvh bvh = build_bvh_sah(boxes, sah());
    EXPECT_EQ(check_bvh(bvh, boxes, 4), "");
    EXPECT_LE(compute_stats(bvh).max_leaf_depth, 7);  // ceil(log2(300 / 4)) halvings
}

/// Magnitudes near float's limits: centroid extents that overflow to infinity, denormal ones
/// whose bin scale overflows, and NaN centroids fall back to halving (UBSan checks the bin
/// conversions).
TEST(BuildSah, ExtremeMagnitudesKeepTheInvariants) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < 200; ++i) {
        const float big = 3e38f * (i % 2 ? 1.0f : -1.0f) * (1.0f - 0.001f * float(i));
        boxes.push_back(Aabb{vec3(big, 0.0f, 0.0f), vec3(big, 1.0f, 1.0f)});
        const float tiny = 1e-42f * float(i);
        boxes.push_back(Aabb{vec3(tiny, tiny, 0.0f), vec3(tiny, tiny, 0.0f)});
    }
    // unbounded along x: the centroid's x is NaN (-inf + inf), which the fallback's median
    // order must still place
    for (int i = 0; i < 9; ++i)
        boxes.push_back(
            Aabb{vec3(-infinity, float(i), 0.0f), vec3(infinity, float(i) + 1.0f, 1.0f)});
    const Bvh bvh = build_bvh_sah(boxes, sah());
    EXPECT_EQ(check_bvh(bvh, boxes, 4), "");
    EXPECT_LT(compute_stats(bvh).max_leaf_depth, traversal_stack_size);
}

/// Centroids spaced exponentially (numerics.md §20): every binned split puts almost all of them
/// in the lowest bin, so the SAH tree degenerates; from depth 31 on the build halves instead and
/// the tree still fits the traversal stack.
TEST(BuildSah, ExponentialCentroidsStayWithinTheTraversalStack) {
    const size_t n = 200000;
    std::vector<Aabb> boxes(n);
    for (size_t i = 0; i < n; ++i) {
        const float x = float(std::pow(10.0, -12.0 + 34.0 * double(i) / double(n)));
        boxes[i] = Aabb{vec3(x, 0.0f, 0.0f), vec3(x * 1.00001f, x * 1e-5f, 0.0f)};
    }
    const Bvh bvh = build_bvh_sah(boxes, sah());
    EXPECT_EQ(check_bvh(bvh, boxes, 4), "");
    const BvhStats st = compute_stats(bvh);
    EXPECT_GT(st.max_leaf_depth, 20);  // the degenerate top is really there
    EXPECT_LT(st.max_leaf_depth, traversal_stack_size);
    std::printf("[ measured ] SAH build, exponential centroids, n = %zu: depth %d (stack %d)\n", n,
                st.max_leaf_depth, traversal_stack_size);
}

/// On the dragon the SAH tree has a lower SAH cost than the median split's, in the same memory
/// budget (at most 64 bytes per triangle with the triangle data).
TEST(BuildSah, DragonTreeIsCheaperThanTheMedianSplitInTheSameMemory) {
    const std::string path = std::string(RAYLANE_SHARED_DIR) + "/models/dragon.ply";
    if (!std::filesystem::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    const MeshData mesh = load_mesh(path);
    const MeshAccel median = build_mesh_accel(mesh, BuildParams{});
    const MeshAccel sah_accel = build_mesh_accel(mesh, sah());
    std::vector<Aabb> boxes(mesh.tris.size());
    for (size_t i = 0; i < boxes.size(); ++i)
        for (int c = 0; c < 3; ++c) boxes[i].grow(mesh.positions[mesh.tris[i][c]]);
    EXPECT_EQ(check_bvh(sah_accel.bvh, boxes, 4), "");
    for (size_t k = 0; k < sah_accel.verts.size(); ++k) {  // vertices in the SAH leaf order
        const uvec3 t = mesh.tris[sah_accel.bvh.prim_ids[k]];
        ASSERT_EQ(sah_accel.verts[k].a, mesh.positions[t.x]) << k;
        ASSERT_EQ(sah_accel.verts[k].c, mesh.positions[t.z]) << k;
    }
    const BvhStats m = compute_stats(median.bvh), s = compute_stats(sah_accel.bvh);
    const double per_tri =
        double(s.bytes + sah_accel.verts.size() * sizeof(TriangleVerts)) / double(mesh.tris.size());
    std::printf("[ measured ] dragon SAH cost: median %.1f, SAH %.1f; SAH %.1f bytes/triangle\n",
                m.sah_cost, s.sah_cost, per_tri);
    EXPECT_LT(s.sah_cost, 0.85 * m.sah_cost);
    EXPECT_LE(per_tri, 64.0);
}

}  // namespace
}  // namespace raylane
