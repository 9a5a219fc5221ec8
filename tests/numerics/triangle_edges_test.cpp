// numerics.md §1 : rays through the shared edges and vertices of closed meshes
// never slip through (traverse/triangle_scalar.h, triangle_packet.h), from inside and outside,
// near and far from the origin; the same decisions through the BVH and the packet path.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <random>

#include "support/geometry_support.h"
#include "traverse/triangle_scalar.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// Points on the mesh the rays aim at: every vertex, and `per_edge` random points a + s (b - a)
/// on every edge (each edge once), with the unit normals of the triangles around them (all the
/// triangles of a vertex, the two of an edge).
struct Target {
    vec3 p;
    std::vector<glm::dvec3> normals;
};

std::vector<Target> edge_and_vertex_targets(const MeshData& m, int per_edge, uint32_t seed) {
    std::vector<glm::dvec3> tri_normal;
    for (uvec3 t : m.tris) {
        const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
        tri_normal.push_back(glm::normalize(glm::cross(b - a, c - a)));
    }
    std::vector<Target> out(m.positions.size());
    std::map<std::pair<uint32_t, uint32_t>, std::vector<glm::dvec3>> edges;
    for (size_t k = 0; k < m.tris.size(); ++k) {
        const uint32_t c[3] = {m.tris[k].x, m.tris[k].y, m.tris[k].z};
        for (int e = 0; e < 3; ++e) {
            out[c[e]].normals.push_back(tri_normal[k]);
            edges[std::minmax(c[e], c[(e + 1) % 3])].push_back(tri_normal[k]);
        }
    }
    for (size_t v = 0; v < m.positions.size(); ++v) out[v].p = m.positions[v];
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> s01(0.0f, 1.0f);
    for (const auto& [key, normals] : edges) {
        const vec3 a = m.positions[key.first], b = m.positions[key.second];
        for (int k = 0; k < per_edge; ++k) {
            // a point that rounds onto an end is that vertex, whose triangles differ
            const vec3 p = a + s01(rng) * (b - a);
            if (p != a && p != b) out.push_back({p, normals});
        }
    }
    return out;
}

/// Rays from interior points to every target, and from exterior points at 10, 1e3 and 1e5
/// times `size` from the centre to every target whose surrounding triangles all face the ray's
/// origin within 60 degrees (so the ray enters the solid there rather than grazing it). Every
/// one of them must hit the closed mesh.
std::vector<Ray> edge_rays(const MeshData& m, vec3 center, float size, int per_edge) {
    const std::vector<Target> targets = edge_and_vertex_targets(m, per_edge, 7);
    std::vector<Ray> rays;
    const vec3 inside[] = {vec3(0.0f), vec3(0.3f, 0.2f, -0.1f), vec3(-0.25f, 0.4f, 0.3f)};
    for (vec3 q : inside) {
        const vec3 o = center + size * q;
        for (const Target& t : targets) rays.push_back({o, t.p - o, 0.0f, infinity});
    }
    std::mt19937 rng(11);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    for (float dist : {10.0f, 1e3f, 1e5f}) {
        for (int k = 0; k < 4; ++k) {
            const vec3 u = glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)));
            const vec3 o = center + (dist * size) * u;
            for (const Target& t : targets) {
                const glm::dvec3 to_o = glm::normalize(glm::dvec3(o) - glm::dvec3(t.p));
                bool facing = true;
                for (const glm::dvec3& n : t.normals) facing = facing && glm::dot(n, to_o) >= 0.5;
                if (facing) rays.push_back({o, t.p - o, 0.0f, infinity});
            }
        }
    }
    // the sanitizer build checks every kind of ray, fewer of each
    if (sanitized) {
        std::vector<Ray> few;
        for (size_t i = 0; i < rays.size(); i += 25) few.push_back(rays[i]);
        rays = std::move(few);
    }
    return rays;
}

struct MeshCase {
    const char* name;
    MeshData mesh;
    vec3 center;
    float size;
    int per_edge;  ///< random targets per edge
};

std::vector<MeshCase> closed_meshes() {
    const vec3 far(1e4f, 7e3f, -3e3f);
    return {{"icosphere", make_icosphere(3, vec3(0.0f), 1.0f), vec3(0.0f), 1.0f, 4},
            {"icosphere at (1e4, 7e3, -3e3)", make_icosphere(3, far, 1.0f), far, 1.0f, 4},
            {"cube", make_cube_mesh(vec3(-1.0f), vec3(1.0f)), vec3(0.0f), 1.0f, 300},
            {"cube at (1e4, 7e3, -3e3)", make_cube_mesh(far - 1.0f, far + 1.0f), far, 1.0f, 300}};
}

/// A mesh case with its rays and their brute-force answers, computed once for the tests below.
struct EdgeCase {
    MeshCase mc;
    std::vector<Ray> rays;
    SceneData scene;
    std::vector<Hit> brute;
};

const std::vector<EdgeCase>& edge_cases() {
    static const std::vector<EdgeCase> cases = [] {
        std::vector<EdgeCase> out;
        for (MeshCase& mc : closed_meshes()) {
            EdgeCase ec{mc,
                        edge_rays(mc.mesh, mc.center, mc.size, mc.per_edge),
                        make_mesh_scene({mc.mesh}),
                        {}};
            ec.brute.resize(ec.rays.size());
            tbb::parallel_for(size_t(0), ec.rays.size(), [&](size_t i) {
                ec.brute[i] = brute_force_closest(ec.scene, ec.rays[i]);
            });
            out.push_back(std::move(ec));
        }
        return out;
    }();
    return cases;
}

/// numerics.md §0.2: with FMA contraction a b - c d of four equal inputs 1 + 2^-12 is 2^-24,
/// without it 0. Contraction breaks the exact antisymmetry of shared edge functions (§1).
TEST(TriangleEdges, BuildDoesNotContractMultiplyAddIntoFma) {
    volatile float va = 1.0f + 0x1.0p-12f, vb = va, vc = va, vd = va;
    const float a = va, b = vb, c = vc, d = vd;
    EXPECT_EQ(a * b - c * d, 0.0f) << "FMA contraction is on: build with -ffp-contract=off";
}

TEST(TriangleEdges, ClosedMeshesHaveNoCracksAtEdgesAndVertices) {
    for (const EdgeCase& ec : edge_cases()) {
        SCOPED_TRACE(ec.mc.name);
        const std::vector<Ray>& rays = ec.rays;
        size_t misses = 0, non_positive = 0, nan_t = 0;
        for (const Hit& h : ec.brute) {
            misses += !h.hit();
            non_positive += h.hit() && !(h.t > 0.0f);
            nan_t += is_nan_bits(h.t);
        }
        EXPECT_GT(rays.size(), sanitized ? 500u : 20000u);
        EXPECT_EQ(misses, 0u) << "of " << rays.size() << " rays at edges and vertices";
        std::printf("[ measured ] %s: %zu misses of %zu edge and vertex rays\n", ec.mc.name, misses,
                    rays.size());
        EXPECT_EQ(non_positive, 0u);
        EXPECT_EQ(nan_t, 0u);
    }
}

/// The closest t over every triangle by the double instantiation of the watertight test.
double double_closest_t(const MeshData& m, const Ray& r) {
    const RayOf<double> rd = ray_of<double>(r);
    const WatertightRayOf<double> wr = make_watertight_ray(rd);
    double best = infinity_of<double>;
    for (uvec3 k : m.tris) {
        double t, u, v;
        if (intersect_triangle(wr, glm::dvec3(m.positions[k.x]), glm::dvec3(m.positions[k.y]),
                               glm::dvec3(m.positions[k.z]), rd.t_min, best, t, u, v))
            best = t;
    }
    return best;
}

/// The double instantiation of the same test is the oracle for t: the float closest t is within
/// a few ulps of the double closest t (the float test's rounding; both see the same float ray).
/// Rays the double test lets pass beside the mesh (from 1e5 away the float ray passes within
/// float rounding of the edge it aims at) are counted, not compared: there the float test's
/// answer is the watertight one.
TEST(TriangleEdges, FloatDistancesAgreeWithTheDoubleOracle) {
    int64_t worst_ulps = 0;
    size_t compared = 0, grazing = 0;
    for (const EdgeCase& ec : edge_cases()) {
        SCOPED_TRACE(ec.mc.name);
        size_t far_off = 0;
        for (size_t i = 0; i < ec.rays.size(); i += 3) {  // a third of them, for time
            const Hit& h = ec.brute[i];
            if (!h.hit()) continue;
            const double t = double_closest_t(ec.mc.mesh, ec.rays[i]);
            if (!(t < infinity_of<double>)) {
                ++grazing;
                continue;
            }
            ++compared;
            const int64_t ulps = ulp_distance(h.t, static_cast<float>(t));
            worst_ulps = std::max(worst_ulps, ulps);
            far_off += ulps > 8;
        }
        EXPECT_EQ(far_off, 0u) << "hits whose t is more than 8 ulps from the double oracle";
    }
    EXPECT_GT(compared, 100 * grazing);
    std::printf(
        "[ measured ] triangle: worst float t vs double oracle %lld ulps over %zu hits "
        "(%zu grazing rays the double test lets pass)\n",
        static_cast<long long>(worst_ulps), compared, grazing);
}

/// Through the BVH (scalar), the answer equals brute force, tie-break included (smallest t, then
/// primitive); through the packet path at every width, the same decisions (row P).
TEST(TriangleEdges, BvhAndPacketPathsAgreeWithBruteForce) {
    for (const EdgeCase& ec : edge_cases()) {
        SCOPED_TRACE(ec.mc.name);
        const std::vector<Ray>& rays = ec.rays;
        const SceneData& scene = ec.scene;
        const Accel accel = build_accel(scene, BuildParams{});
        std::vector<Hit> scalar(rays.size());
        size_t bvh_mismatch = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            scalar[i] = intersect_closest(scene, accel, rays[i]);
            const Hit& b = ec.brute[i];
            bvh_mismatch += scalar[i].prim != b.prim || scalar[i].t != b.t;
        }
        EXPECT_EQ(bvh_mismatch, 0u) << "of " << rays.size() << " rays";
        for_each_width([&](auto w) {
            constexpr int W = decltype(w)::value;
            SCOPED_TRACE("W = " + std::to_string(W));
            EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(scene, accel, rays)), 0u);
            const std::vector<uint8_t> got = packet_any<W>(scene, accel, rays);
            EXPECT_EQ(std::count(got.begin(), got.end(), uint8_t{0}), 0) << "any-hit misses";
        });
    }
}

/// A ray through a vertex meets up to six triangles at the same t: the one reported is the
/// smallest primitive id among them, in every run and in both paths.
TEST(TriangleEdges, RaysThroughAVertexReportTheSmallestPrimitive) {
    const MeshData m = make_icosphere(3, vec3(0.0f), 1.0f);
    const SceneData scene = make_mesh_scene({m});
    const Accel accel = build_accel(scene, BuildParams{});
    std::vector<Ray> rays;
    for (vec3 p : m.positions) rays.push_back({vec3(0.0f), p, 0.0f, infinity});
    size_t wrong = 0, ties = 0;
    std::vector<Hit> scalar;
    for (const Ray& r : rays) {
        const WatertightRay wr = make_watertight_ray(r);
        float best_t = infinity;
        uint32_t best_prim = invalid_id;
        int at_best = 0;
        for (uint32_t k = 0; k < m.tris.size(); ++k) {
            float t, u, v;
            const uvec3 tri = m.tris[k];
            if (!intersect_triangle(wr, m.positions[tri.x], m.positions[tri.y], m.positions[tri.z],
                                    r.t_min, r.t_max, t, u, v))
                continue;
            if (t < best_t) {
                best_t = t, best_prim = k, at_best = 1;
            } else if (t == best_t) {
                ++at_best;
                best_prim = std::min(best_prim, k);
            }
        }
        ties += at_best > 1;
        const Hit h = intersect_closest(scene, accel, r);
        wrong += h.prim != best_prim || h.t != best_t;
        scalar.push_back(h);
    }
    EXPECT_GT(ties, m.positions.size() / 2) << "vertex rays should meet several triangles";
    EXPECT_EQ(wrong, 0u);
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        SCOPED_TRACE("W = " + std::to_string(W));
        EXPECT_EQ(hit_disagreements(scalar, packet_closest<W>(scene, accel, rays), 0), 0u);
    });
}

}  // namespace
}  // namespace raylane
