// Golden tests of accel/build_median.cpp: the optimised median-split build must give the tree of
// the plain nth_element build in median_reference.h bit for bit (nodes and primitive order), and
// a fixed SHA-256 of that tree, so that the reference build cannot drift along with it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "accel/bvh.h"
#include "core/rng.h"
#include "io/load_mesh.h"
#include "support/median_reference.h"
#include "support/models.h"
#include "support/sha256.h"

namespace raylane {
namespace {

std::string digest(const Bvh& bvh) {
    test::Sha256 h;
    h.update(bvh.nodes.data(), bvh.nodes.size() * sizeof(BvhNode));
    h.update(bvh.prim_ids.data(), bvh.prim_ids.size() * sizeof(uint32_t));
    return h.hex();
}

std::string digest(std::span<const Aabb> boxes) {
    test::Sha256 h;
    for (const Aabb& b : boxes) {
        const float f[6] = {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z};
        h.update(f, sizeof f);
    }
    return h.hex();
}

/// Index of the first node that differs (bytes), or of the first prim_ids entry, as text.
std::string first_difference(const Bvh& got, const Bvh& want) {
    if (got.nodes.size() != want.nodes.size())
        return "node count " + std::to_string(got.nodes.size()) + " vs " +
               std::to_string(want.nodes.size());
    for (size_t i = 0; i < got.nodes.size(); ++i)
        if (std::memcmp(&got.nodes[i], &want.nodes[i], sizeof(BvhNode)) != 0)
            return "node " + std::to_string(i);
    if (got.prim_ids != want.prim_ids) return "prim_ids";
    return "";
}

/// Uniform float in [lo, hi) from the counter-based hash (the same on every platform).
float uniform(uint32_t i, uint32_t dim, uint32_t seed, float lo, float hi) {
    return lo + (hi - lo) * random_float(i, 0, dim, seed);
}

/// Triangle-like boxes: small boxes scattered in a [-10, 10]^3 cube.
std::vector<Aabb> random_boxes(size_t n, uint32_t seed) {
    std::vector<Aabb> boxes(n);
    for (uint32_t i = 0; i < n; ++i) {
        vec3 lo, size;
        for (uint32_t k = 0; k < 3; ++k) {
            lo[int(k)] = uniform(i, k, seed, -10.0f, 10.0f);
            size[int(k)] = uniform(i, 3 + k, seed, 0.0f, 0.05f);
        }
        boxes[i] = {lo, lo + size};
    }
    return boxes;
}

/// Boxes on a coarse grid, many with equal centroids, and points at -0 and +0 (equal as
/// floats, ordered -0 first by the tie rule).
std::vector<Aabb> tied_boxes(size_t n, uint32_t seed) {
    std::vector<Aabb> boxes(n);
    for (uint32_t i = 0; i < n; ++i) {
        vec3 lo, hi;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t r = hash_sample(i, 1, k, seed);
            const float v = float(int(r % 5u) - 2);  // -2 .. 2
            if (v == 0.0f) {
                // a point at a signed zero: c2 = -0 + -0 = -0 or +0 + +0 = +0
                lo[int(k)] = hi[int(k)] = (r & 0x100u) ? -0.0f : 0.0f;
            } else {
                lo[int(k)] = v;
                hi[int(k)] = v + float((r >> 9) % 2u);
            }
        }
        boxes[i] = {lo, hi};
    }
    return boxes;
}

/// Also returns how the build split its nodes above `subtree` (every way gives the same tree:
/// the tests check which ways they reached).
MedianSplitPaths expect_same_as_reference(std::span<const Aabb> boxes, int leaf,
                                          const std::string& what,
                                          uint32_t subtree = BuildParams{}.median_subtree) {
    MedianSplitPaths paths;
    const Bvh got = build_bvh_median(
        boxes, BuildParams{.max_leaf_size = leaf, .median_subtree = subtree}, &paths);
    const Bvh want = test::MedianReference::build(boxes, leaf);
    EXPECT_EQ(first_difference(got, want), "")
        << what << " leaf=" << leaf << " subtree=" << subtree;
    EXPECT_EQ(check_bvh(got, boxes, leaf), "")
        << what << " leaf=" << leaf << " subtree=" << subtree;
    return paths;
}

TEST(Sha256, MatchesTheFips180Examples) {
    auto hex = [](const std::string& s) {
        test::Sha256 h;
        h.update(s.data(), s.size());
        return h.hex();
    };
    EXPECT_EQ(hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(MedianReference, SatisfiesTheBvhInvariants) {
    const std::vector<Aabb> boxes = random_boxes(3000, 4);
    for (int leaf : {1, 4, 7}) {
        const Bvh bvh = test::MedianReference::build(boxes, leaf);
        EXPECT_EQ(check_bvh(bvh, boxes, leaf), "") << "leaf=" << leaf;
    }
}

TEST(BuildMedianGolden, DragonTreeIsTheReferenceTreeAndTheRecordedOne) {
    const std::string path = std::string(RAYLANE_SHARED_DIR) + "/models/dragon.ply";
    if (!std::filesystem::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    const MeshData mesh = load_mesh(path);
    std::vector<Aabb> bounds(mesh.tris.size());
    for (size_t i = 0; i < mesh.tris.size(); ++i)
        for (uint32_t v : {mesh.tris[i].x, mesh.tris[i].y, mesh.tris[i].z})
            bounds[i].grow(mesh.positions[v]);
    // The SHA-256 of the dragon's triangle boxes (the input) and of the nodes and primitive ids
    // that the plain nth_element build (median_reference.h) makes from them. If the model or the
    // loader changes the boxes, print digest(bounds) and digest(MedianReference::build(bounds,
    // 4)) and put them here: the reference build, never the optimised one, gives the digests.
    ASSERT_EQ(digest(bounds), "c40400b0e1632acf4a1b5304c3cc41c9261dd85036bbf4292f8b3e30f14608ae")
        << "the dragon's triangle boxes changed (loader or model): re-record both digests";

    const MeshAccel accel = build_mesh_accel(mesh, BuildParams{});
    const Bvh want = test::MedianReference::build(bounds, 4);
    EXPECT_EQ(first_difference(accel.bvh, want), "");
    EXPECT_EQ(digest(accel.bvh),
              "9a22534898584c42665f4c9bf4f4218d7444aa8eeec54016f3df97d7f65699e9");
    ASSERT_EQ(accel.verts.size(), mesh.tris.size());
    for (size_t k = 0; k < accel.verts.size(); ++k) {
        const uvec3 t = mesh.tris[accel.bvh.prim_ids[k]];
        ASSERT_EQ(accel.verts[k].a, mesh.positions[t.x]) << k;
        ASSERT_EQ(accel.verts[k].b, mesh.positions[t.y]) << k;
        ASSERT_EQ(accel.verts[k].c, mesh.positions[t.z]) << k;
    }
}

TEST(BuildMedianGolden, RandomBoxesGiveTheReferenceTreeAndTheRecordedOne) {
#ifdef RAYLANE_SANITIZED
    const size_t n = 20000;
#else
    const size_t n = 300000;
#endif
    const std::vector<Aabb> boxes = random_boxes(n, 2);
    const Bvh got = build_bvh_median(boxes, BuildParams{});
    EXPECT_EQ(first_difference(got, test::MedianReference::build(boxes, 4)), "");
    if (n == 300000) {
        // The SHA-256 of the random boxes and of MedianReference's tree over them; after a
        // change to random_boxes, print digest(boxes) and digest(MedianReference::build(boxes,
        // 4)) and put them here.
        ASSERT_EQ(digest(boxes),
                  "0f1d9a55db43458c2fc94497cb4eefcf3435bb55fd7ee4c8708e9cfbafc45417");
        EXPECT_EQ(digest(got), "1c7442c40a04d837c14384d58523a78c0a726547a54507491409df3e1009e726");
    }
}

TEST(BuildMedianGolden, NodesSplitAboveTheSubtreeSizeGiveTheReferenceTree) {
    // every subtree size from one primitive (every node split on its own) up, on boxes with
    // distinct, tied, equal and extreme centroids
    std::vector<Aabb> extremes = random_boxes(3000, 8);
    for (size_t i = 0; i < extremes.size(); i += 7) extremes[i].lo.y = extremes[i].hi.y = -3e38f;
    for (size_t i = 3; i < extremes.size(); i += 11) extremes[i].hi.z = infinity;
    for (size_t i = 5; i < extremes.size(); i += 13) extremes[i].lo.x = extremes[i].hi.x = 1e-40f;
    const std::pair<std::string, std::vector<Aabb>> sets[] = {
        {"random", random_boxes(5000, 3)},
        {"tied", tied_boxes(5000, 4)},
        {"equal", std::vector<Aabb>(2000, Aabb{vec3(-1.0f), vec3(1.0f)})},
        {"extremes", extremes}};
    for (const auto& [what, boxes] : sets)
        for (uint32_t subtree : {1u, 3u, 100u, 1500u})
            for (int leaf : {1, 4, 6}) expect_same_as_reference(boxes, leaf, what, subtree);
}

TEST(BuildMedianGolden, NodesOf65536OrMoreSplitAboveTheSubtreeSizeGiveTheReferenceTree) {
    // a node of 65,536 or more finds its median among the keys that a sample brackets, or by
    // a radix select when the bracket holds too many (equal keys) or misses the median (a
    // sample of every 17th box, each far to the right of the others); n is not a multiple of
    // 16 (the scalar tails of the vector loops)
    const size_t n = 70009;
    std::vector<Aabb> misleading = random_boxes(n, 6);
    for (size_t i = 0; i < n; i += n / 4096) misleading[i].lo.x = misleading[i].hi.x = 1e6f;
    const std::pair<std::string, std::vector<Aabb>> sets[] = {
        {"random", random_boxes(n, 3)},
        {"tied", tied_boxes(n, 4)},
        {"equal", std::vector<Aabb>(n, Aabb{vec3(-1.0f), vec3(1.0f)})},
        {"misleading sample", misleading}};
    for (const auto& [what, boxes] : sets) {
        const MedianSplitPaths paths = expect_same_as_reference(boxes, 4, what, 30000);
        // the root (70,009) samples its keys; its children (35,004 and 35,005) are above the
        // subtree size too, and select_children gathers all of their keys
        const bool bracket_holds = what == "random" || what == "tied";
        EXPECT_EQ(paths.bracketed, bracket_holds ? 1u : 0u) << what;
        EXPECT_EQ(paths.radix, bracket_holds ? 0u : 1u) << what;
        EXPECT_EQ(paths.four_way, 1u) << what;
        EXPECT_EQ(paths.two_way, 0u) << what;
    }
}

TEST(BuildMedianGolden, NodesWhoseChildrenSplitOnTheirOwnGiveTheReferenceTree) {
    // a node whose children are both above the subtree size finds their splits from a sample
    // of its own keys and partitions its four grandchildren at once, or, when a child's
    // bracket holds too many keys (equal keys) or misses its median (a sample of boxes each at
    // one end of x, the axis of the node and of its children; or only the second child's
    // sample at its far end), partitions its two children; n is not a multiple of 16 (the
    // scalar tails of the vector loops)
    const size_t n = 300011, step = n / 8192;  // select_children's sample: every step-th box
    const auto spread_x = [](std::vector<Aabb> boxes) {
        for (Aabb& b : boxes) b.hi.x = b.lo.x = 10.0f * b.lo.x;
        return boxes;
    };
    std::vector<Aabb> misleading = spread_x(random_boxes(n, 9));
    for (size_t i = 0; i < n; i += step)
        misleading[i].lo.x = misleading[i].hi.x = (i / step) % 2 ? 99.9f : -99.9f;
    std::vector<Aabb> second_misleading = spread_x(random_boxes(n, 10));
    for (size_t i = 0; i < n; i += step)
        if (second_misleading[i].lo.x > 0.0f)  // right of the root's median, which is near 0
            second_misleading[i].lo.x = second_misleading[i].hi.x = 99.9f;
    const std::pair<std::string, std::vector<Aabb>> sets[] = {
        {"random", random_boxes(n, 7)},
        {"tied", tied_boxes(n, 8)},
        {"equal", std::vector<Aabb>(n, Aabb{vec3(-1.0f), vec3(1.0f)})},
        {"misleading sample", misleading},
        {"second child's sample misleading", second_misleading}};
    for (const auto& [what, boxes] : sets) {
        const MedianSplitPaths paths = expect_same_as_reference(boxes, 4, what, 60000);
        // the root (300,011) and its children (150,005 and 150,006) are above 60,000, and so
        // are its grandchildren (75,002 or 75,003), whose children are not. A four-way root
        // leaves four grandchildren that select their own splits (5 selects); a two-way root
        // leaves two children that do (3), and each tries the four-way step on its own (the
        // misleading samples were the root's): when it fails too (equal keys), the
        // grandchildren select theirs (7)
        const bool misleading_sets = what != "random" && what != "tied" && what != "equal";
        const uint32_t four_way = misleading_sets ? 2u : what == "equal" ? 0u : 1u;
        EXPECT_EQ(paths.four_way, four_way) << what;
        EXPECT_EQ(paths.two_way, what == "equal" ? 3u : four_way == 1u ? 0u : 1u) << what;
        EXPECT_EQ(paths.bracketed + paths.radix, misleading_sets   ? 3u
                                                 : what == "equal" ? 7u
                                                                   : 5u)
            << what;
        EXPECT_EQ(paths.radix, what == "equal" ? 7u : 0u) << what;
    }
}

TEST(BuildMedianGolden, MoreThanTheDefaultSubtreeSizeGivesTheReferenceTree) {
#ifdef RAYLANE_SANITIZED
    GTEST_SKIP() << "600,000 primitives: release builds only";
#endif
    // the default subtree size, passed: the root is split on its own
    const std::vector<Aabb> boxes = random_boxes(size_t(BuildParams{}.median_subtree) + 75000, 5);
    expect_same_as_reference(boxes, 4, "random");
}

TEST(BuildMedianGolden, EverySmallSizeAndLeafSizeGivesTheReferenceTree) {
    for (int leaf : {1, 2, 3, 4, 5, 8, 65535, 70000})
        for (size_t n = 1; n <= 70; ++n) {
            const std::vector<Aabb> boxes = random_boxes(n, uint32_t(n));
            expect_same_as_reference(boxes, leaf, "random n=" + std::to_string(n));
            const std::vector<Aabb> ties = tied_boxes(n, uint32_t(n));
            expect_same_as_reference(ties, leaf, "tied n=" + std::to_string(n));
        }
}

TEST(BuildMedianGolden, TiedCentroidsGiveTheReferenceTree) {
    // below and above 2^16 primitives (the radix sort's digit width changes there)
    for (size_t n : {1000u, 4096u, 4097u, 50000u, 70000u})
        for (int leaf : {1, 4, 6}) {
            const std::vector<Aabb> ties = tied_boxes(n, 11);
            expect_same_as_reference(ties, leaf, "tied n=" + std::to_string(n));
        }
}

TEST(BuildMedianGolden, EqualCentroidsKeepIndexOrder) {
    // all centroids equal: every split takes the lower indices first, leaves list them in order
    for (size_t n : {1000u, 70000u}) {
        const std::vector<Aabb> boxes(n, Aabb{vec3(-1.0f), vec3(1.0f)});
        const Bvh bvh = build_bvh_median(boxes, BuildParams{4});
        for (uint32_t i = 0; i < boxes.size(); ++i) ASSERT_EQ(bvh.prim_ids[i], i) << "n=" << n;
        EXPECT_EQ(first_difference(bvh, test::MedianReference::build(boxes, 4)), "") << n;
    }
}

TEST(BuildMedianGolden, NegativeZeroCentroidSortsBeforePositiveZero) {
    // primitive 0 at +0, primitive 1 at -0 on every axis: equal floats, but -0 goes first
    const Aabb plus{vec3(0.0f), vec3(0.0f)}, minus{vec3(-0.0f), vec3(-0.0f)};
    const std::vector<Aabb> boxes = {plus, minus};
    const Bvh bvh = build_bvh_median(boxes, BuildParams{1});
    ASSERT_EQ(bvh.nodes.size(), 3u);
    EXPECT_EQ(std::vector<uint32_t>(bvh.prim_ids.begin(), bvh.prim_ids.end()),
              (std::vector<uint32_t>{1, 0}));
    // the root keeps the first -0 it meets in leaf order
    EXPECT_TRUE(std::signbit(bvh.nodes[0].lo[0]));
    EXPECT_TRUE(std::signbit(bvh.nodes[0].hi[0]));
}

TEST(BuildMedianGolden, LargeAndSmallMagnitudesAndInfinitiesGiveTheReferenceTree) {
    std::vector<Aabb> boxes = random_boxes(5000, 8);
    const float big = std::numeric_limits<float>::max();
    for (size_t i = 0; i < boxes.size(); i += 7) boxes[i].lo.y = -big, boxes[i].hi.y = -big;
    for (size_t i = 3; i < boxes.size(); i += 11) boxes[i].hi.z = infinity;
    for (size_t i = 5; i < boxes.size(); i += 13) boxes[i].lo.x = boxes[i].hi.x = 1e-40f;
    for (int leaf : {1, 4}) expect_same_as_reference(boxes, leaf, "extremes");
}

TEST(BuildMedianGolden, NanCentroidsGiveTheReferenceTree) {
    // a box infinite both ways on an axis has a NaN centroid there (-inf + inf, whose sign bit
    // is set on x86: below every key), a box of NaNs one of their sign (+NaN above every key,
    // -NaN below); in small nodes, in nodes split on their own, and in nodes whose children are
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t n : {size_t(5000), size_t(70009)}) {
        std::vector<Aabb> boxes = random_boxes(n, 12);
        for (size_t i = 0; i < n; i += 5) boxes[i].lo.x = -infinity, boxes[i].hi.x = infinity;
        for (size_t i = 2; i < n; i += 9) boxes[i].lo.y = boxes[i].hi.y = nan;
        for (size_t i = 4; i < n; i += 4) boxes[i].lo.z = boxes[i].hi.z = -nan;
        const Bvh want = test::MedianReference::build(boxes, 4);
        for (uint32_t subtree : {1u, 100u, 30000u, BuildParams{}.median_subtree}) {
            if (n == 5000 && subtree >= 30000u) continue;
            // only the trees are compared: no box contains a box of NaNs (check_bvh)
            const Bvh got = build_bvh_median(boxes, BuildParams{.median_subtree = subtree});
            EXPECT_EQ(first_difference(got, want), "") << "n=" << n << " subtree=" << subtree;
        }
    }
}

}  // namespace
}  // namespace raylane
