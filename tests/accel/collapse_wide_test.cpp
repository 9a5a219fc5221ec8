// Tests of accel/collapse_wide.cpp: the wide tree collapsed from the median-split and SAH
// binary trees keeps its invariants (check_wide_bvh) on small, flat, degenerate, huge and tiny
// inputs and on the dragon, adopts the largest child first, and stays in its memory budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include "accel/bvh.h"
#include "accel/wide_bvh.h"
#include "io/load_mesh.h"
#include "support/models.h"
#include "support/random_boxes.h"

namespace raylane {
namespace {

BuildParams wide_params(BvhBuild method, int leaf = 4) {
    return BuildParams{.max_leaf_size = leaf, .method = method};
}

Bvh build_either(std::span<const Aabb> boxes, BvhBuild method, int leaf = 4) {
    return method == BvhBuild::median ? build_bvh_median(boxes, wide_params(method, leaf))
                                      : build_bvh_sah(boxes, wide_params(method, leaf));
}

/// Collapses the tree of `boxes` and checks the wide tree, the binary tree and that the wide
/// tree's leaves cover every primitive; returns the wide tree.
WideBvh collapse_checked(std::span<const Aabb> boxes, BvhBuild method, int leaf = 4) {
    const Bvh bvh = build_either(boxes, method, leaf);
    EXPECT_EQ(check_bvh(bvh, boxes, leaf), "");
    WideBvh wide = collapse_to_wide(bvh);
    EXPECT_EQ(check_wide_bvh(wide, bvh), "") << boxes.size() << " boxes";
    EXPECT_EQ(compute_wide_stats(wide).prims, boxes.size());
    return wide;
}

TEST(CollapseWide, EmptyTreeGivesNoNodes) {
    const Bvh empty;
    EXPECT_TRUE(collapse_to_wide(empty).nodes.empty());
    EXPECT_EQ(check_wide_bvh(collapse_to_wide(empty), empty), "");
}

TEST(CollapseWide, SmallMeshesForBothBuilds) {
    for (BvhBuild method : {BvhBuild::median, BvhBuild::sah}) {
        for (size_t n : {1u, 2u, 3u, 5u}) {
            const std::vector<Aabb> boxes = random_boxes(n, static_cast<uint32_t>(n));
            for (int leaf : {1, 4}) {
                const WideBvh wide = collapse_checked(boxes, method, leaf);
                ASSERT_FALSE(wide.nodes.empty());
                EXPECT_LE(int(wide.nodes[0].children), wide_arity);
            }
        }
    }
    // one leaf: a root with one child
    const std::vector<Aabb> one = random_boxes(1, 9);
    const WideBvh wide = collapse_checked(one, BvhBuild::median);
    ASSERT_EQ(wide.nodes.size(), 1u);
    EXPECT_EQ(wide.nodes[0].children, 1);
    EXPECT_EQ(wide.nodes[0].count[0], 1);
}

TEST(CollapseWide, NodesFillUpUnlessOnlyLeavesAreLeft) {
    for (BvhBuild method : {BvhBuild::median, BvhBuild::sah}) {
        for (size_t n : {100u, 1000u, 4097u, 30000u}) {
            const std::vector<Aabb> boxes = random_boxes(n, static_cast<uint32_t>(n + 7));
            for (int leaf : {1, 4}) {
                const WideBvh wide = collapse_checked(boxes, method, leaf);
                for (size_t i = 0; i < wide.nodes.size(); ++i) {
                    const WideNode& w = wide.nodes[i];
                    if (w.children == wide_arity) continue;
                    for (int k = 0; k < w.children; ++k)
                        EXPECT_TRUE(w.is_leaf(k)) << "n=" << n << " node " << i << " slot " << k;
                }
                // leaves hold at most wide_leaf_size primitives, or one binary leaf's
                for (const WideNode& w : wide.nodes)
                    for (int k = 0; k < w.children; ++k)
                        EXPECT_LE(w.count[k], std::max<uint32_t>(wide_leaf_size, uint32_t(leaf)));
            }
        }
    }
}

TEST(CollapseWide, CoplanarAndDegenerateBoxes) {
    for (BvhBuild method : {BvhBuild::median, BvhBuild::sah}) {
        std::vector<Aabb> flat = random_boxes(500, 3);
        for (Aabb& b : flat) b.lo.z = b.hi.z = 1.0f;  // all in the plane z = 1
        collapse_checked(flat, method);
        std::vector<Aabb> points(300);
        for (Aabb& b : points) b.lo = b.hi = vec3(2.0f, -1.0f, 0.5f);  // all one point
        collapse_checked(points, method);
    }
}

TEST(CollapseWide, HugeAndTinyBoxes) {
    std::vector<Aabb> boxes = random_boxes(2000, 5);
    for (size_t i = 0; i < boxes.size(); ++i) {
        const float scale = i % 3 == 0 ? 1e29f : (i % 3 == 1 ? 1e-31f : 1.0f);
        boxes[i].lo *= scale;
        boxes[i].hi *= scale;
    }
    boxes[0] = Aabb{vec3(-1e30f), vec3(1e30f)};
    boxes[1] = Aabb{vec3(1e-30f), vec3(2e-30f)};
    for (BvhBuild method : {BvhBuild::median, BvhBuild::sah}) collapse_checked(boxes, method);
}

TEST(CollapseWide, AdoptsTheLargestInteriorChildFirst) {
    // 128 boxes on the x axis: 64 small ones on the left, 64 large ones on the right. The
    // median build's root splits them 64 and 64. The root's wide node opens the large right
    // half down to merged leaves of 8 boxes and keeps the small left half as one child.
    std::vector<Aabb> boxes;
    for (int i = 0; i < 64; ++i)
        boxes.push_back({vec3(float(i), 0.0f, 0.0f), vec3(float(i) + 0.5f, 0.5f, 0.5f)});
    for (int i = 0; i < 64; ++i) {
        const float x = 100.0f + 100.0f * float(i);
        boxes.push_back({vec3(x, 0.0f, 0.0f), vec3(x + 50.0f, 50.0f, 50.0f)});
    }
    const Bvh bvh = build_bvh_median(boxes, wide_params(BvhBuild::median, 1));
    const WideBvh wide = collapse_to_wide(bvh);
    ASSERT_EQ(check_wide_bvh(wide, bvh), "");
    ASSERT_EQ(wide.nodes[0].children, wide_arity);
    EXPECT_FALSE(wide.nodes[0].is_leaf(0));  // the small half, one interior child
    int leaves = 0;
    for (int k = 1; k < wide_arity; ++k) leaves += wide.nodes[0].is_leaf(k);
    EXPECT_GE(leaves, wide_arity / 2);    // the large half opened down to its leaves first
    for (int k = 1; k < wide_arity; ++k)  // and every slot of it lies on the right
        EXPECT_GE(wide.nodes[0].lo[0][k], 100.0f);
}

TEST(CollapseWide, CheckerFindsBrokenTrees) {
    const std::vector<Aabb> boxes = random_boxes(200, 11);
    const Bvh bvh = build_bvh_median(boxes, wide_params(BvhBuild::median));
    const WideBvh good = collapse_to_wide(bvh);
    ASSERT_EQ(check_wide_bvh(good, bvh), "");
    ASSERT_GT(good.nodes.size(), 1u);
    {
        WideBvh bad = good;  // a leaf referenced twice
        const int last = bad.nodes[0].children - 1;
        for (int k = 0; k < bad.nodes[0].children; ++k) {
            if (bad.nodes[0].is_leaf(k)) continue;
            bad.nodes[0].child[last] = bad.nodes[0].child[k];
            bad.nodes[0].count[last] = bad.nodes[0].count[k];
            break;
        }
        EXPECT_NE(check_wide_bvh(bad, bvh), "");
    }
    {
        WideBvh bad = good;  // a child box sticking out of its parent's slot
        for (int k = 0; k < bad.nodes[0].children; ++k) {
            if (bad.nodes[0].is_leaf(k)) continue;
            bad.nodes[bad.nodes[0].child[k]].hi[0][0] += 100.0f;
            break;
        }
        EXPECT_NE(check_wide_bvh(bad, bvh), "");
    }
    {
        WideBvh bad = good;  // an unused slot with a box
        auto with_room = std::find_if(bad.nodes.begin(), bad.nodes.end(),
                                      [](const WideNode& w) { return w.children < wide_arity; });
        ASSERT_NE(with_room, bad.nodes.end()) << "every node is full: no unused slot to break";
        with_room->lo[1][wide_arity - 1] = 0.0f;
        EXPECT_NE(check_wide_bvh(bad, bvh), "");
    }
}

/// Each leaf's triangles in WideBvh::tris are the vertices in leaf order, as nine arrays of the
/// leaf's size, followed by zeros; a zero-area triangle's are NaN. Meshes of 1, 2, 3, 5 and 1000
/// triangles (every seventh one a point), both builds.
TEST(CollapseWide, LeafTrianglesAreTheLeafOrderVerticesInSoa) {
    for (size_t n : {1, 2, 3, 5, 1000}) {
        MeshData mesh;
        std::mt19937 rng(static_cast<unsigned>(n));
        std::uniform_real_distribution<float> uni(-10.0f, 10.0f);
        for (size_t i = 0; i < n; ++i) {
            const vec3 c(uni(rng), uni(rng), uni(rng));
            for (int k = 0; k < 3; ++k)
                mesh.positions.push_back(
                    i % 7 == 3 ? c : c + vec3(uni(rng), uni(rng), uni(rng)) * 0.1f);
            const auto v = static_cast<uint32_t>(3 * i);
            mesh.tris.push_back(uvec3(v, v + 1, v + 2));
        }
        for (BvhBuild method : {BvhBuild::median, BvhBuild::sah}) {
            const MeshAccel accel = build_mesh_accel(mesh, wide_params(method));
            ASSERT_EQ(check_wide_bvh(accel.wide, accel.bvh), "");
            ASSERT_EQ(accel.wide.tris.size(), 9 * n + wide_tris_pad);
            size_t checked = 0;
            for (const WideNode& w : accel.wide.nodes) {
                for (int s = 0; s < w.children; ++s) {
                    if (!w.is_leaf(s)) continue;
                    const uint32_t first = w.child[s], count = w.count[s];
                    const float* group = accel.wide.tris.data() + 9 * size_t(first);
                    for (uint32_t k = 0; k < count; ++k, ++checked) {
                        const TriangleVerts& tv = accel.verts[first + k];
                        const vec3 corner[3] = {tv.a, tv.b, tv.c};
                        const bool point = tv.a == tv.b && tv.b == tv.c;
                        for (int c = 0; c < 9; ++c) {
                            const float got = group[c * count + k];
                            if (point)
                                ASSERT_TRUE(std::isnan(got)) << "a zero-area triangle";
                            else
                                ASSERT_EQ(got, corner[c / 3][c % 3])
                                    << n << " triangles, leaf at " << first << ", triangle " << k;
                        }
                    }
                }
            }
            EXPECT_EQ(checked, n);
            for (size_t i = 9 * n; i < accel.wide.tris.size(); ++i)
                EXPECT_EQ(accel.wide.tris[i], 0.0f);
        }
    }
}

/// The dragon: both builds collapse correctly, and the packet path's data (wide nodes, the
/// leaves' triangles, the primitive ids) stays within 64 bytes per triangle.
TEST(CollapseWide, DragonWithinTheMemoryBudget) {
    const std::string path = std::string(RAYLANE_SHARED_DIR) + "/models/dragon.ply";
    if (!std::filesystem::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    const MeshData mesh = load_mesh(path);
    for (BvhBuild method : {BvhBuild::median, BvhBuild::sah}) {
        const MeshAccel accel = build_mesh_accel(mesh, wide_params(method));
        ASSERT_EQ(check_wide_bvh(accel.wide, accel.bvh), "");
        const WideStats s = compute_wide_stats(accel.wide);
        EXPECT_EQ(s.prims, mesh.tris.size());
        const double per_tri = double(s.bytes +  // nodes and leaf triangles
                                      accel.bvh.prim_ids.size() * sizeof(uint32_t)) /
                               double(mesh.tris.size());
        EXPECT_LE(per_tri, 64.0);
        std::printf("[ measured ] dragon %s: %zu wide nodes, %.2f children each, %.1f bytes/tri\n",
                    method == BvhBuild::median ? "median" : "SAH", s.nodes, s.mean_children,
                    per_tri);
    }
}

}  // namespace
}  // namespace raylane
