// Tests of accel/build_median.cpp and accel/check_bvh.cpp: invariants of the median-split BVH,
// and the timing of a mesh build's phases.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>

#include "accel/bvh.h"
#include "support/random_boxes.h"

namespace raylane {
namespace {

TEST(BuildMedian, EmptyInputGivesEmptyBvh) {
    const Bvh bvh = build_bvh_median({}, BuildParams{});
    EXPECT_TRUE(bvh.nodes.empty());
    EXPECT_EQ(check_bvh(bvh, {}, 4), "");
}

TEST(BuildMedian, SinglePrimitiveIsOneLeaf) {
    const std::vector<Aabb> boxes = random_boxes(1, 1);
    const Bvh bvh = build_bvh_median(boxes, BuildParams{});
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_TRUE(bvh.nodes[0].is_leaf());
    EXPECT_EQ(check_bvh(bvh, boxes, 4), "");
}

TEST(BuildMedian, HoldsInvariantsForEveryLeafSize) {
    for (int leaf : {1, 2, 4, 5, 8}) {
        for (size_t n : {2u, 3u, 7u, 100u, 1000u, 4097u}) {
            const std::vector<Aabb> boxes = random_boxes(n, static_cast<uint32_t>(n + leaf));
            const Bvh bvh = build_bvh_median(boxes, BuildParams{leaf});
            EXPECT_EQ(check_bvh(bvh, boxes, leaf), "") << "n=" << n << " leaf=" << leaf;
        }
    }
}

TEST(BuildMedian, SplitsIntoEqualHalves) {
    const std::vector<Aabb> boxes = random_boxes(1000, 7);
    const Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    // every interior node's children differ in primitive count by at most one
    std::vector<uint32_t> count(bvh.nodes.size(), 0);
    for (size_t i = bvh.nodes.size(); i-- > 0;) {
        const BvhNode& n = bvh.nodes[i];
        count[i] = n.is_leaf() ? n.count : count[i + 1] + count[n.index];
        if (!n.is_leaf()) {
            const int diff = int(count[i + 1]) - int(count[n.index]);
            EXPECT_LE(std::abs(diff), 1) << "node " << i;
        }
    }
    EXPECT_EQ(count[0], 1000u);
}

TEST(BuildMedian, LeftHalfLiesBelowTheMedianOnTheSplitAxis) {
    const std::vector<Aabb> boxes = random_boxes(513, 3);
    const Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    const BvhNode& root = bvh.nodes[0];
    ASSERT_FALSE(root.is_leaf());
    // all centroids of the first child's subtree <= all of the second child's, on root.axis
    auto max_of = [&](uint32_t begin, uint32_t end) {
        float m = -infinity;
        for (uint32_t k = begin; k < end; ++k)
            m = std::max(m, boxes[bvh.prim_ids[k]].center()[root.axis]);
        return m;
    };
    auto min_of = [&](uint32_t begin, uint32_t end) {
        float m = infinity;
        for (uint32_t k = begin; k < end; ++k)
            m = std::min(m, boxes[bvh.prim_ids[k]].center()[root.axis]);
        return m;
    };
    EXPECT_LE(max_of(0, 256), min_of(256, 513));
}

TEST(BuildMedian, AllCentroidsEqualStillTerminates) {
    std::vector<Aabb> boxes(300, Aabb{vec3(1.0f), vec3(2.0f)});
    const Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    EXPECT_EQ(check_bvh(bvh, boxes, 4), "");
}

/// A wavy grid of w x w squares, two triangles each.
MeshData grid_mesh(uint32_t w) {
    MeshData mesh;
    for (uint32_t y = 0; y <= w; ++y)
        for (uint32_t x = 0; x <= w; ++x)
            mesh.positions.push_back(vec3(float(x), float(y), std::sin(0.1f * float(x * y))));
    for (uint32_t y = 0; y < w; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t a = y * (w + 1) + x, b = a + 1, c = a + w + 1, d = c + 1;
            mesh.tris.push_back({a, b, d});
            mesh.tris.push_back({a, d, c});
        }
    return mesh;
}

TEST(BuildMesh, PhasesAreTimedAndAddUpToNoMoreThanTheBuild) {
    const MeshData mesh = grid_mesh(200);  // 80,000 triangles
    const auto start = std::chrono::steady_clock::now();
    const MeshAccel accel = build_mesh_accel(mesh, BuildParams{});
    const double build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const BuildPhases& p = accel.phases;
    for (double ms : {p.centroids, p.sorts, p.splits, p.vertices, p.boxes}) EXPECT_GT(ms, 0.0);
    EXPECT_LE(p.centroids + p.sorts + p.splits + p.vertices + p.boxes, build_ms);
    BuildPhases sum;
    sum += p;
    sum += BuildPhases{1.0, 2.0, 3.0, 4.0, 5.0};
    EXPECT_DOUBLE_EQ(sum.centroids, p.centroids + 1.0);
    EXPECT_DOUBLE_EQ(sum.sorts, p.sorts + 2.0);
    EXPECT_DOUBLE_EQ(sum.splits, p.splits + 3.0);
    EXPECT_DOUBLE_EQ(sum.vertices, p.vertices + 4.0);
    EXPECT_DOUBLE_EQ(sum.boxes, p.boxes + 5.0);

    // the SAH build times no phases
    const BuildPhases sah = build_mesh_accel(mesh, BuildParams{.method = BvhBuild::sah}).phases;
    for (double ms : {sah.centroids, sah.sorts, sah.splits, sah.vertices, sah.boxes})
        EXPECT_EQ(ms, 0.0);
}

TEST(BuildMesh, NodesSplitAboveTheSubtreeSizeGiveTheSameTreeAndVertices) {
    // the mesh build lends its vertex array to the nodes split on their own as well
    const MeshData mesh = grid_mesh(100);  // 20,000 triangles
    const MeshAccel whole = build_mesh_accel(mesh, BuildParams{});
    for (uint32_t subtree : {1u, 3000u, 15000u}) {
        const MeshAccel split = build_mesh_accel(mesh, BuildParams{.median_subtree = subtree});
        ASSERT_EQ(split.bvh.nodes.size(), whole.bvh.nodes.size()) << subtree;
        EXPECT_EQ(std::memcmp(split.bvh.nodes.data(), whole.bvh.nodes.data(),
                              whole.bvh.nodes.size() * sizeof(BvhNode)),
                  0)
            << subtree;
        EXPECT_EQ(split.bvh.prim_ids, whole.bvh.prim_ids) << subtree;
        EXPECT_EQ(std::memcmp(split.verts.data(), whole.verts.data(),
                              whole.verts.size() * sizeof(TriangleVerts)),
                  0)
            << subtree;
        for (double ms : {split.phases.centroids, split.phases.sorts, split.phases.splits})
            EXPECT_GT(ms, 0.0) << subtree;
    }
}

TEST(CheckBvh, DetectsAPrimitiveInTwoLeaves) {
    const std::vector<Aabb> boxes = random_boxes(64, 9);
    Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    bvh.prim_ids[1] = bvh.prim_ids[0];
    EXPECT_NE(check_bvh(bvh, boxes, 4), "");
}

TEST(CheckBvh, DetectsAChildOutsideItsParent) {
    const std::vector<Aabb> boxes = random_boxes(64, 11);
    Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    bvh.nodes[1].hi[0] = bvh.nodes[0].hi[0] + 1.0f;
    EXPECT_NE(check_bvh(bvh, boxes, 4), "");
}

TEST(ComputeStats, CountsNodesLeavesAndDepth) {
    const std::vector<Aabb> boxes = random_boxes(1024, 5);
    const Bvh bvh = build_bvh_median(boxes, BuildParams{4});
    const BvhStats s = compute_stats(bvh);
    EXPECT_EQ(s.nodes, bvh.nodes.size());
    EXPECT_EQ(s.leaves, 256u);  // 1024 halves evenly down to leaves of 4
    EXPECT_EQ(s.nodes, 2 * s.leaves - 1);
    EXPECT_EQ(s.max_leaf_depth, 8);
    EXPECT_DOUBLE_EQ(s.mean_leaf_depth, 8.0);
    EXPECT_GT(s.sah_cost, 1.0);
}

}  // namespace
}  // namespace raylane
