// Tests of traverse/triangle_scalar.h: the watertight ray/triangle test on hand-made cases,
// against a double oracle, on degenerate triangles, and for watertightness on closed meshes.
#include "traverse/triangle_scalar.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr size_t target_stride = 5;  // every 5th target of a mesh with more than 1000
constexpr int exterior_directions = 2;
constexpr int triangle_oracle_rays = 2000;
#else
constexpr size_t target_stride = 1;
constexpr int exterior_directions = 8;
constexpr int triangle_oracle_rays = 100000;
#endif

struct Hit3 {
    bool hit = false;
    float t = 0.0f, u = 0.0f, v = 0.0f;
};

Hit3 trace(const Ray& ray, vec3 a, vec3 b, vec3 c) {
    Hit3 h;
    h.hit =
        intersect_triangle(make_watertight_ray(ray), a, b, c, ray.t_min, ray.t_max, h.t, h.u, h.v);
    return h;
}

Ray ray_from(vec3 org, vec3 dir) {
    Ray r;
    r.org = org;
    r.dir = dir;
    return r;
}

// --- contraction canary (numerics.md §0.2) -------------------------------------------------

TEST(WatertightTriangle, BuildDoesNotContractMultiplyAdd) {
    // a*b - c*d with a = b = c = d = 1 + 2^-12: 0 without contraction, 2^-24 with an FMA.
    volatile float va = 1.0f + 0x1.0p-12f, vb = va, vc = va, vd = va;
    const float a = va, b = vb, c = vc, d = vd;
    EXPECT_EQ(a * b - c * d, 0.0f) << "FMA contraction is on: the triangle test is not watertight";
}

// --- hand-made cases ---------------------------------------------------------------------------

TEST(WatertightTriangle, ChoosesTheDominantAxisAndKeepsTheWinding) {
    WatertightRay wr = make_watertight_ray(ray_from(vec3(0.0f), vec3(0.5f, -2.0f, 1.0f)));
    EXPECT_EQ(wr.kz, 1);
    EXPECT_EQ(wr.kx, 0);  // swapped because dir[kz] < 0
    EXPECT_EQ(wr.ky, 2);
    EXPECT_EQ(wr.sx, 0.5f / -2.0f);
    EXPECT_EQ(wr.sy, 1.0f / -2.0f);
    EXPECT_EQ(wr.sz, 1.0f / -2.0f);
    wr = make_watertight_ray(ray_from(vec3(0.0f), vec3(1.0f, 1.0f, 1.0f)));
    EXPECT_EQ(wr.kz, 0);  // ties go to the lower axis
    EXPECT_EQ(wr.kx, 1);
    EXPECT_EQ(wr.ky, 2);
    wr = make_watertight_ray(ray_from(vec3(0.0f), vec3(0.0f, -0.0f, 3.0f)));
    EXPECT_EQ(wr.kz, 2);
    EXPECT_EQ(wr.kx, 0);
    EXPECT_EQ(wr.ky, 1);
}

TEST(WatertightTriangle, HitsAtTheExactDistanceAndBarycentrics) {
    const vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    const Hit3 h = trace(ray_from(vec3(0.25f, 0.5f, -2.0f), vec3(0.0f, 0.0f, 4.0f)), a, b, c);
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t, 0.5f);
    EXPECT_EQ(h.u, 0.25f);
    EXPECT_EQ(h.v, 0.5f);
    const LocalGeometry g = geometry_triangle(a, b, c, h.u, h.v);
    EXPECT_EQ(g.normal, vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(g.uv, vec2(0.25f, 0.5f));
}

TEST(WatertightTriangle, HitsFromBothSidesWithTheWindingNormal) {
    const vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    const Hit3 h = trace(ray_from(vec3(0.25f, 0.25f, 3.0f), vec3(0.0f, 0.0f, -1.0f)), a, b, c);
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.t, 3.0f);
    EXPECT_EQ(h.u, 0.25f);
    EXPECT_EQ(h.v, 0.25f);
    EXPECT_EQ(geometry_triangle(a, b, c, h.u, h.v).normal, vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(geometry_triangle(a, c, b, h.v, h.u).normal, vec3(0.0f, 0.0f, -1.0f));
}

TEST(WatertightTriangle, MissesOutsideBehindAndOutsideTheInterval) {
    const vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    EXPECT_FALSE(trace(ray_from(vec3(0.75f, 0.5f, -1.0f), vec3(0, 0, 1)), a, b, c).hit);
    EXPECT_FALSE(trace(ray_from(vec3(-0.1f, 0.5f, -1.0f), vec3(0, 0, 1)), a, b, c).hit);
    EXPECT_FALSE(trace(ray_from(vec3(0.2f, 0.2f, 1.0f), vec3(0, 0, 1)), a, b, c).hit);  // behind
    Ray r = ray_from(vec3(0.2f, 0.2f, -1.0f), vec3(0, 0, 1));
    r.t_max = 1.0f;  // the hit is at t = 1 exactly: open interval
    EXPECT_FALSE(trace(r, a, b, c).hit);
    r.t_max = infinity;
    r.t_min = 1.0f;
    EXPECT_FALSE(trace(r, a, b, c).hit);
    r.t_min = std::nextafter(1.0f, 0.0f);
    EXPECT_TRUE(trace(r, a, b, c).hit);
}

TEST(WatertightTriangle, LeavesOutputsAloneOnAMiss) {
    float t = -7.0f, u = -7.0f, v = -7.0f;
    const bool hit =
        intersect_triangle(make_watertight_ray(ray_from(vec3(2.0f, 2.0f, -1.0f), vec3(0, 0, 1))),
                           vec3(0.0f), vec3(1, 0, 0), vec3(0, 1, 0), 0.0f, infinity, t, u, v);
    EXPECT_FALSE(hit);
    EXPECT_EQ(t, -7.0f);
    EXPECT_EQ(u, -7.0f);
    EXPECT_EQ(v, -7.0f);
}

TEST(WatertightTriangle, CountsRaysThroughVerticesAndEdgesAsHits) {
    const vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    const vec3 points[] = {
        a, b, c, vec3(0.5f, 0.0f, 0.0f), vec3(0.0f, 0.25f, 0.0f), vec3(0.5f, 0.5f, 0.0f)};
    for (const vec3 p : points) {
        for (const float dz : {1.0f, -1.0f}) {
            const Hit3 h =
                trace(ray_from(p - vec3(0.0f, 0.0f, 2.0f * dz), vec3(0, 0, dz)), a, b, c);
            EXPECT_TRUE(h.hit) << p.x << " " << p.y;
            EXPECT_EQ(h.t, 2.0f);
        }
    }
}

TEST(WatertightTriangle, ZeroDirectionAndNanInputsNeverHit) {
    const vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
    const float qnan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(trace(ray_from(vec3(0.2f, 0.2f, -1.0f), vec3(0.0f)), a, b, c).hit);
    EXPECT_FALSE(trace(ray_from(vec3(0.2f, 0.2f, -1.0f), vec3(0, 0, qnan)), a, b, c).hit);
    EXPECT_FALSE(trace(ray_from(vec3(0.2f, qnan, -1.0f), vec3(0, 0, 1)), a, b, c).hit);
    EXPECT_FALSE(
        trace(ray_from(vec3(0.2f, 0.2f, -1.0f), vec3(0, 0, 1)), vec3(qnan, 0, 0), b, c).hit);
    EXPECT_FALSE(
        trace(ray_from(vec3(0.2f, 0.2f, -1.0f), vec3(0, 0, 1)), vec3(0, 0, qnan), b, c).hit);
}

TEST(WatertightTriangle, DecidesEdgeFunctionsThatRoundToZeroInDouble) {
    // The ray is the +z axis (no shear). The edge (b, c) passes the axis so closely that
    // c.x * b.y and c.y * b.x round to the same float: the float edge function is 0 while the
    // exact one is not. Of two triangles sharing the edge, one on each side, exactly the one on
    // the exact side must be hit (without the double fallback both claim the ray).
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> uni(0.5f, 2.0f);
    const Ray ray = ray_from(vec3(0.0f), vec3(0.0f, 0.0f, 1.0f));
    int found = 0;
    for (int i = 0; i < 100000 && found < 50; ++i) {
        const vec3 b(uni(rng), uni(rng), 1.0f);
        vec3 c(-2.0f * b.x, -2.0f * b.y, 1.0f);
        c.x = std::nextafter(c.x, i % 2 ? 0.0f : -8.0f);
        const double exact = double(c.x) * double(b.y) - double(c.y) * double(b.x);
        if (c.x * b.y - c.y * b.x != 0.0f || exact == 0.0) continue;
        ++found;
        const vec3 mid = 0.5f * (b + c);
        const vec3 n(b.y - c.y, c.x - b.x, 0.0f);  // perpendicular to the edge in xy
        for (const vec3 a : {mid + n, mid - n}) {
            // the axis is inside iff it is on a's side of the edge line
            const double side_a = (double(c.x) - b.x) * (double(a.y) - b.y) -
                                  (double(c.y) - b.y) * (double(a.x) - b.x);
            const bool expected = (side_a > 0.0) == (-exact > 0.0);
            const Hit3 h = trace(ray, a, b, c);
            EXPECT_EQ(h.hit, expected) << i;
            if (h.hit) {
                EXPECT_EQ(h.t, 1.0f);
            }
        }
    }
    EXPECT_GE(found, 10);
}

// --- degenerate triangles (numerics.md §8) ----------------------------------------------------

TEST(WatertightTriangle, NeverHitsZeroAreaOrCollinearTriangles) {
    // Exactly collinear in float: c - a = 2 (b - a), and three identical vertices.
    struct Corners {
        vec3 a, b, c;
    };
    const Corners tris[] = {
        {vec3(0.0f), vec3(1.0f, 1.0f, 1.0f), vec3(2.0f, 2.0f, 2.0f)},
        {vec3(0.5f, -0.25f, 0.0f), vec3(1.5f, 0.75f, 0.5f), vec3(3.5f, 2.75f, 1.5f)},
        {vec3(-1.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, 0.0f)},
        {vec3(1e4f, 7e3f, -3e3f), vec3(1e4f + 0.125f, 7e3f + 0.5f, -3e3f - 0.25f),
         vec3(1e4f + 0.375f, 7e3f + 1.5f, -3e3f - 0.75f)},
        {vec3(0.3f, 0.3f, 0.3f), vec3(0.3f, 0.3f, 0.3f), vec3(0.3f, 0.3f, 0.3f)},
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    int rays = 0;
    for (const Corners& tri : tris) {
        ASSERT_TRUE(is_zero_area_triangle(tri.a, tri.b, tri.c));
        for (int i = 0; i < 2000; ++i) {
            // aim at a point of the segment (or the vertex) from a random direction
            const float s = uni(rng);
            const vec3 target = tri.a + s * (tri.c - tri.a);
            const vec3 dir(uni(rng) - 0.5f, uni(rng) - 0.5f, uni(rng) - 0.5f);
            const Ray ray = ray_from(target - 3.0f * dir, dir);
            float t = 0.0f, u = 0.0f, v = 0.0f;
            const bool hit = intersect_triangle(make_watertight_ray(ray), tri.a, tri.b, tri.c,
                                                -infinity, infinity, t, u, v);
            EXPECT_FALSE(hit);
            EXPECT_FALSE(std::isnan(t) || std::isnan(u) || std::isnan(v));
            ++rays;
        }
    }
    EXPECT_EQ(rays, 10000);
    // A genuine sliver is not mistaken for a zero-area triangle.
    EXPECT_FALSE(
        is_zero_area_triangle(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.5f, 0x1.0p-20f, 0.0f)));
}

// --- against a double oracle -------------------------------------------------------------------

struct OracleHit {
    double t, u, v;
};

/// Moeller-Trumbore in double on the float inputs (accurate far beyond float on these rays).
OracleHit oracle(const Ray& ray, vec3 a, vec3 b, vec3 c) {
    const glm::dvec3 o(ray.org), d(ray.dir), A(a), e1 = glm::dvec3(b) - A, e2 = glm::dvec3(c) - A;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    const glm::dvec3 s = o - A;
    const double u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(d, q) / det;
    const double t = glm::dot(e2, q) / det;
    return {t, u, v};
}

TEST(WatertightTriangle, MatchesADoubleOracleOnRandomRays) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    int hits = 0, misses = 0;
    for (int i = 0; i < triangle_oracle_rays; ++i) {
        const vec3 a(uni(rng), uni(rng), uni(rng)), b(uni(rng), uni(rng), uni(rng)),
            c(uni(rng), uni(rng), uni(rng));
        const vec3 n = glm::cross(b - a, c - a);
        if (glm::length(n) < 1e-2f)
            continue;  // skip slivers: the oracle's margin below is absolute
        // Barycentrics of the target: inside with margin 0.01, or outside by at least 0.01.
        float wb = 0.5f * (uni(rng) + 1.0f), wc = 0.5f * (uni(rng) + 1.0f);
        const bool inside = i % 2 == 0;
        if (inside && wb + wc > 1.0f) wb = 1.0f - wb, wc = 1.0f - wc;
        const float wa = 1.0f - wb - wc;
        const float margin = std::min({wa, wb, wc});
        if (inside ? margin < 0.01f : margin > -0.01f) continue;
        const vec3 target = a + wb * (b - a) + wc * (c - a);
        const vec3 org = 3.0f * vec3(uni(rng), uni(rng), uni(rng));
        const Ray ray = ray_from(org, (target - org) * (1.0f + 0.5f * uni(rng)));
        if (std::abs(glm::dot(glm::normalize(n), glm::normalize(ray.dir))) < 0.05f) continue;
        const OracleHit o = oracle(ray, a, b, c);
        const Hit3 h = trace(ray, a, b, c);
        ASSERT_EQ(h.hit, inside) << "ray " << i;
        if (!inside) {
            ++misses;
            continue;
        }
        ++hits;
        EXPECT_NEAR(h.t, o.t, 1e-5 * o.t) << "ray " << i;
        EXPECT_NEAR(h.u, o.u, 1e-4) << "ray " << i;
        EXPECT_NEAR(h.v, o.v, 1e-4) << "ray " << i;
    }
    EXPECT_GT(hits, triangle_oracle_rays / 10);
    EXPECT_GT(misses, triangle_oracle_rays / 10);
}

// --- watertightness (numerics.md §1) -----------------------------------------------------------

struct TestMesh {
    std::vector<vec3> positions;
    std::vector<std::array<uint32_t, 3>> tris;
};

/// Icosphere of radius 1 around the origin, outward winding: the icosahedron subdivided
/// `levels` times, new vertices projected onto the sphere (computed in double).
TestMesh make_icosphere(int levels) {
    const double g = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<glm::dvec3> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                 {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                 {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (auto& v : p) v = glm::normalize(v);
    std::vector<std::array<uint32_t, 3>> tris = {
        {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
        auto mid = [&](uint32_t i, uint32_t j) {
            const auto key = std::minmax(i, j);
            auto it = midpoint.find(key);
            if (it != midpoint.end()) return it->second;
            p.push_back(glm::normalize(p[i] + p[j]));
            const auto k = static_cast<uint32_t>(p.size() - 1);
            midpoint.emplace(key, k);
            return k;
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (const auto& t : tris) {
            const uint32_t ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        tris = std::move(next);
    }
    TestMesh m;
    for (const auto& v : p) m.positions.push_back(vec3(v));
    m.tris = tris;
    return m;
}

/// The cube [-1, 1]^3 as 12 triangles, outward winding.
TestMesh make_cube() {
    TestMesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back(
            vec3(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f));
    const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        m.tris.push_back({q[0], q[1], q[2]});
        m.tris.push_back({q[0], q[2], q[3]});
    }
    return m;
}

TestMesh translated(TestMesh m, vec3 offset) {
    for (vec3& p : m.positions) p += offset;
    return m;
}

/// A point the rays aim at, and the triangles it lies on (to decide whether it faces a viewer).
struct Target {
    vec3 p;
    std::vector<uint32_t> tris;
};

/// Step through the targets: all of them, or every target_stride-th of a large mesh.
size_t stride(const std::vector<Target>& targets) {
    return targets.size() > 1000 ? target_stride : 1;
}

/// Every vertex and 4 random points a + s (b - a) on every edge.
std::vector<Target> make_targets(const TestMesh& m, uint32_t seed) {
    std::vector<Target> targets(m.positions.size());
    for (uint32_t i = 0; i < m.positions.size(); ++i) targets[i].p = m.positions[i];
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
    for (uint32_t f = 0; f < m.tris.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
            targets[m.tris[f][k]].tris.push_back(f);
            edges[std::minmax(m.tris[f][k], m.tris[f][(k + 1) % 3])].push_back(f);
        }
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (const auto& [edge, faces] : edges) {
        EXPECT_EQ(faces.size(), 2u) << "mesh is not closed";
        const vec3 a = m.positions[edge.first], b = m.positions[edge.second];
        for (int k = 0; k < 4; ++k) targets.push_back({a + uni(rng) * (b - a), faces});
    }
    return targets;
}

struct Coverage {
    int rays = 0;
    int misses = 0;
    int non_positive_t = 0;
    int far_from_target = 0;
};

/// Brute force over all triangles; the ray aims at the target at t = 1. A ray from inside a
/// closed convex mesh leaves it exactly once, near the target: checked with `t_tol`.
void trace_brute_force(const TestMesh& m, const Ray& ray, bool from_inside, double t_tol,
                       Coverage& cov) {
    const WatertightRay wr = make_watertight_ray(ray);
    float best = infinity;
    for (const auto& tri : m.tris) {
        float t, u, v;
        if (intersect_triangle(wr, m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]],
                               ray.t_min, ray.t_max, t, u, v)) {
            if (!(t > 0.0f)) ++cov.non_positive_t;
            best = std::min(best, t);
        }
    }
    ++cov.rays;
    if (best == infinity)
        ++cov.misses;
    else if (from_inside && std::abs(best - 1.0) > t_tol)
        ++cov.far_from_target;
}

Coverage interior_coverage(const TestMesh& m, vec3 center, double t_tol) {
    const vec3 offsets[] = {vec3(0.0f), vec3(0.3f, -0.2f, 0.1f), vec3(-0.1f, 0.45f, -0.35f),
                            vec3(0.05f, 0.1f, 0.5f)};
    const std::vector<Target> targets = make_targets(m, 1);
    Coverage cov;
    for (const vec3 off : offsets) {
        const vec3 org = center + off;
        for (size_t i = 0; i < targets.size(); i += stride(targets))
            trace_brute_force(m, {org, targets[i].p - org}, true, t_tol, cov);
    }
    return cov;
}

/// Origins at `distance` from the centre in random directions; targets all of whose triangles
/// face the origin within 60 degrees (so the ray enters the mesh through them, with margin).
Coverage exterior_coverage(const TestMesh& m, vec3 center, float distance) {
    const std::vector<Target> targets = make_targets(m, 2);
    std::mt19937 rng(3);
    std::normal_distribution<float> normal;
    Coverage cov;
    for (int k = 0; k < exterior_directions; ++k) {
        const vec3 w = glm::normalize(vec3(normal(rng), normal(rng), normal(rng)));
        const vec3 org = center + distance * w;
        for (size_t i = 0; i < targets.size(); i += stride(targets)) {
            const Target& tg = targets[i];
            const vec3 to_org(glm::normalize(glm::dvec3(org) - glm::dvec3(tg.p)));
            bool facing = true;
            for (uint32_t f : tg.tris) {
                const auto& tri = m.tris[f];
                const vec3 n =
                    glm::normalize(glm::cross(m.positions[tri[1]] - m.positions[tri[0]],
                                              m.positions[tri[2]] - m.positions[tri[0]]));
                facing = facing && glm::dot(n, to_org) >= 0.5f;
            }
            if (facing) trace_brute_force(m, {org, tg.p - org}, false, 0.0, cov);
        }
    }
    return cov;
}

void expect_watertight(const TestMesh& m, vec3 center) {
    // The ray aims at the target at t = 1; rounding of the target - origin difference moves the
    // exit by a few ulps of the coordinates, relative to |dir| >= 0.5.
    const double t_tol = 1e-5 + 64.0 * std::ldexp(1.0, std::ilogb(glm::length(center) + 2.0) - 23);
    const Coverage in = interior_coverage(m, center, t_tol);
    EXPECT_GE(in.rays, 4 * 26);
    EXPECT_EQ(in.misses, 0) << "of " << in.rays << " rays from inside";
    EXPECT_EQ(in.non_positive_t, 0);
    EXPECT_EQ(in.far_from_target, 0);
    int exterior_rays = 0;
    for (const float distance : {10.0f, 1e3f, 1e5f}) {
        const Coverage out = exterior_coverage(m, center, distance);
        EXPECT_GT(out.rays, 10) << distance;
        EXPECT_EQ(out.misses, 0) << "of " << out.rays << " rays from " << distance;
        EXPECT_EQ(out.non_positive_t, 0);
        exterior_rays += out.rays;
    }
    std::printf("%zu triangles: %d rays from inside, %d from outside\n", m.tris.size(), in.rays,
                exterior_rays);
}

const vec3 far_offset(1e4f, 7e3f, -3e3f);

TEST(WatertightTriangle, IcosphereHasNoCracks) {
    const TestMesh m = make_icosphere(3);
    ASSERT_EQ(m.tris.size(), 1280u);
    ASSERT_EQ(m.positions.size(), 642u);
    expect_watertight(m, vec3(0.0f));
}

TEST(WatertightTriangle, IcosphereFarFromTheOriginHasNoCracks) {
    expect_watertight(translated(make_icosphere(3), far_offset), far_offset);
}

TEST(WatertightTriangle, CubeHasNoCracks) { expect_watertight(make_cube(), vec3(0.0f)); }

TEST(WatertightTriangle, CubeFarFromTheOriginHasNoCracks) {
    expect_watertight(translated(make_cube(), far_offset), far_offset);
}

}  // namespace
}  // namespace raylane
