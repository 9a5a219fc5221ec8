// Equivalence of traverse/intersect_packet.cpp with traverse/intersect_scalar.cpp on packets whose
// lanes share nothing: random origins and directions, rays leaving surfaces, finite and infinite
// intervals, shuffled together. This exercises the mesh traversals' ordering by entry distance
// and their pop test against each lane's own shrinking limit; hits must agree bit for bit
// (object, primitive, t, u, v).
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>

#include "io/load_scene.h"
#include "support/models.h"
#include "support/widths.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_scalar.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int rays_per_kind = 5000;
#else
constexpr int rays_per_kind = 100000;
#endif

struct Case {
    SceneData scene;
    Accel accel;
    std::vector<Ray> rays;
    std::vector<Hit> closest;
    std::vector<uint8_t> blocked;
};

/// Uniform on the unit sphere.
vec3 random_direction(std::mt19937& rng) {
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    for (;;) {
        const vec3 d(uni(rng), uni(rng), uni(rng));
        const float len2 = glm::dot(d, d);
        if (len2 > 1e-4f && len2 <= 1.0f) return d / std::sqrt(len2);
    }
}

/// Rays from random points of the scene's box, then from the points they hit (in random
/// directions, both sides of the surface), with a mix of intervals; shuffled; scalar answers.
std::shared_ptr<Case> make_case(const std::string& name) {
    static std::map<std::string, std::shared_ptr<Case>> cache;
    if (auto it = cache.find(name); it != cache.end()) return it->second;
    auto c = std::make_shared<Case>();
    try {
        c->scene = name == "builtin"
                       ? make_builtin_scene()
                       : load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
        c->accel = build_accel(c->scene, BuildParams{});
    } catch (const std::exception&) {
        return cache[name] = nullptr;
    }
    Aabb box;
    for (const Aabb& b : c->accel.object_bounds)
        if (!b.empty()) box.grow(b);
    if (box.empty()) box = {vec3(-1.0f), vec3(1.0f)};
    const vec3 lo = box.lo - 0.1f * box.extent(), hi = box.hi + 0.1f * box.extent();
    const float size = glm::length(box.extent());
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto interval = [&](Ray& r) {
        const float pick = unit(rng);
        if (pick < 0.25f) r.t_max = unit(rng) * 0.2f * size;  // short: shadow-like
        if (pick > 0.9f) r.t_min = -unit(rng) * 0.1f * size;  // behind the origin too
    };
    for (int i = 0; i < rays_per_kind; ++i) {
        Ray r;
        r.org = lo + vec3(unit(rng), unit(rng), unit(rng)) * (hi - lo);
        r.dir = random_direction(rng);
        interval(r);
        c->rays.push_back(r);
    }
    const std::vector<Ray> first = c->rays;
    for (const Ray& r : first) {
        const Hit h = intersect_closest(c->scene, c->accel, r);
        if (!h.hit()) continue;
        Ray s;
        s.org = r.org + h.t * r.dir;
        s.dir = random_direction(rng);
        interval(s);
        c->rays.push_back(s);
    }
    std::shuffle(c->rays.begin(), c->rays.end(), rng);
    c->closest.resize(c->rays.size());
    c->blocked.resize(c->rays.size());
    tbb::parallel_for(size_t(0), c->rays.size(), [&](size_t i) {
        c->closest[i] = intersect_closest(c->scene, c->accel, c->rays[i]);
        c->blocked[i] = intersect_any(c->scene, c->accel, c->rays[i]);
    });
    return cache[name] = c;
}

template <class T>
class IntersectPacketIncoherent : public ::testing::Test {};
TYPED_TEST_SUITE(IntersectPacketIncoherent, Widths, WidthName);

template <int W>
void check(const std::string& name) {
    const std::shared_ptr<Case> c = make_case(name);
    if (!c) RAYLANE_MODEL_MISSING() << "scenes/" << name << ".json or its model is not available";
    size_t hits = 0;
    for (const Hit& h : c->closest) hits += h.hit();
    EXPECT_GT(hits, c->rays.size() / 4) << "the rays must hit something";
    std::atomic<size_t> bad_closest{0}, bad_any{0};
    const size_t n = c->rays.size();
    tbb::parallel_for(size_t(0), (n + W - 1) / W, [&](size_t k) {
        RayPacket<W> p;
        uint32_t b = 0;
        for (int i = 0; i < W; ++i) {
            Ray r;
            r.t_max = -1.0f;  // benign inactive lane
            if (k * W + i < n) {
                r = c->rays[k * W + i];
                b |= 1u << i;
            }
            set_ray(p, i, r);
        }
        const vmask<W> active = mask_from_bits<W>(b);
        const HitPacket<W> got = intersect_closest(c->scene, c->accel, p, active);
        const uint32_t blocked = bits(intersect_any(c->scene, c->accel, p, active));
        for (int i = 0; i < W && k * W + i < n; ++i) {
            const Hit g = get_hit(got, i), w = c->closest[k * W + i];
            const bool same =
                g.object == w.object && g.prim == w.prim &&
                (!w.hit() || (std::bit_cast<uint32_t>(g.t) == std::bit_cast<uint32_t>(w.t) &&
                              std::bit_cast<uint32_t>(g.uv.x) == std::bit_cast<uint32_t>(w.uv.x) &&
                              std::bit_cast<uint32_t>(g.uv.y) == std::bit_cast<uint32_t>(w.uv.y)));
            if (!same) ++bad_closest;
            if (((blocked >> i) & 1u) != c->blocked[k * W + i]) ++bad_any;
        }
    });
    EXPECT_EQ(bad_closest.load(), 0u) << "closest hits differ";
    EXPECT_EQ(bad_any.load(), 0u) << "any-hit answers differ";
}

TYPED_TEST(IntersectPacketIncoherent, MatchesScalarOnTheDragon) {
    check<TypeParam::value>("dragon");
}

TYPED_TEST(IntersectPacketIncoherent, MatchesScalarOnTheBunny) { check<TypeParam::value>("bunny"); }

TYPED_TEST(IntersectPacketIncoherent, MatchesScalarOnEveryAnalyticShape) {
    check<TypeParam::value>("builtin");
}

}  // namespace
}  // namespace raylane
