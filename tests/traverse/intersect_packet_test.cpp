// Equivalence of traverse/intersect_packet.cpp with traverse/intersect_scalar.cpp: the same
// closest hits (object, primitive, t) and the same any-hit answers, ray by ray, at every packet
// width this machine runs, on coherent camera rays, shadow rays and incoherent bounce rays.
#include "traverse/intersect_packet.h"

#include <gtest/gtest.h>
#include <immintrin.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>
#include <tuple>

#include "core/offset.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "scene/transform.h"
#include "support/adversarial_rays.h"
#include "support/geometry_support.h"
#include "support/models.h"
#include "support/ray_packets.h"
#include "support/widths.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_scalar.h"
#include "traverse/intersect_stream.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int ray_target = 20000;  // per set; the sanitizer build checks the same code paths
#else
constexpr int ray_target = 1000000;
#endif

struct Loaded {
    SceneData scene;
    Accel accel;
};

/// A scene of scenes/ (or the built-in one) with its BVHs built by `method`; nullptr when its
/// model is absent.
std::shared_ptr<Loaded> load(const std::string& name, BvhBuild method = BvhBuild::median) {
    static std::map<std::pair<std::string, BvhBuild>, std::shared_ptr<Loaded>> cache;
    const auto key = std::make_pair(name, method);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    std::shared_ptr<Loaded> l;
    try {
        l = std::make_shared<Loaded>();
        l->scene = name == "builtin"
                       ? make_builtin_scene()
                       : load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
        l->accel = build_accel(l->scene, BuildParams{.method = method});
    } catch (const std::exception&) {
        l = nullptr;
    }
    return cache[key] = l;
}

/// The three ray sets of a scene, with the scalar path's answers.
struct RaySets {
    std::vector<Ray> camera, shadow, bounce;
    std::vector<Hit> camera_hits, bounce_hits;
    std::vector<uint8_t> shadow_blocked;
};

RaySets make_ray_sets(const Loaded& l) {
    RaySets s;
    Camera cam = l.scene.camera;
    const double aspect = double(cam.width) / cam.height;
    cam.height = std::max(1, int(std::sqrt(ray_target / aspect)));
    cam.width = std::max(1, ray_target / cam.height);
    const CameraFrame frame = make_camera_frame(cam);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x)
            s.camera.push_back(camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f));
    s.camera_hits.resize(s.camera.size());
    tbb::parallel_for(size_t(0), s.camera.size(), [&](size_t i) {
        s.camera_hits[i] = intersect_closest(l.scene, l.accel, s.camera[i]);
    });
    // shadow rays to every light and one cosine-distributed bounce per hit
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (size_t i = 0; i < s.camera.size(); ++i) {
        const Hit& h = s.camera_hits[i];
        if (!h.hit()) continue;
        const SurfacePoint sp = surface_at(l.scene, s.camera[i], h);
        vec3 n = sp.geometric_normal;
        if (glm::dot(n, s.camera[i].dir) > 0.0f) n = -n;
        const vec3 o = offset_ray_origin(sp.position, n, ray_reach(s.camera[i], h.t));
        for (const Light& light : l.scene.lights) {
            Ray r;
            r.org = o;
            if (light.kind == LightKind::point) {
                r.dir = light.position - o;
                r.t_max = 1.0f;
            } else {
                r.dir = light.direction;
            }
            s.shadow.push_back(r);
        }
        const float u1 = uni(rng), u2 = uni(rng);
        const float rad = std::sqrt(u1), phi = 6.2831853f * u2;
        const vec3 t = glm::normalize(std::fabs(n.x) > 0.5f ? glm::cross(n, vec3(0, 1, 0))
                                                            : glm::cross(n, vec3(1, 0, 0)));
        const vec3 b = glm::cross(n, t);
        Ray r;
        r.org = o;
        r.dir = rad * std::cos(phi) * t + rad * std::sin(phi) * b +
                std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
        s.bounce.push_back(r);
    }
    s.shadow_blocked.resize(s.shadow.size());
    s.bounce_hits.resize(s.bounce.size());
    tbb::parallel_for(size_t(0), s.shadow.size(), [&](size_t i) {
        s.shadow_blocked[i] = intersect_any(l.scene, l.accel, s.shadow[i]);
    });
    tbb::parallel_for(size_t(0), s.bounce.size(), [&](size_t i) {
        s.bounce_hits[i] = intersect_closest(l.scene, l.accel, s.bounce[i]);
    });
    return s;
}

/// Counts lanes whose closest hit differs from the scalar answer (object, primitive or t).
template <int W>
size_t closest_mismatches(const Loaded& l, const std::vector<Ray>& rays,
                          const std::vector<Hit>& want) {
    std::atomic<size_t> bad{0};
    tbb::parallel_for(size_t(0), (rays.size() + W - 1) / W, [&](size_t k) {
        vmask<W> active;
        const RayPacket<W> p = make_packet<W>(rays, k * W, active);
        const HitPacket<W> got = intersect_closest(l.scene, l.accel, p, active);
        for (int i = 0; i < W && k * W + i < rays.size(); ++i) {
            const Hit g = get_hit(got, i), w = want[k * W + i];
            if (g.object != w.object || g.prim != w.prim || (w.hit() && g.t != w.t)) ++bad;
        }
    });
    return bad;
}

template <int W>
size_t any_mismatches(const Loaded& l, const std::vector<Ray>& rays,
                      const std::vector<uint8_t>& want) {
    std::atomic<size_t> bad{0};
    tbb::parallel_for(size_t(0), (rays.size() + W - 1) / W, [&](size_t k) {
        vmask<W> active;
        const RayPacket<W> p = make_packet<W>(rays, k * W, active);
        const uint32_t got = bits(intersect_any(l.scene, l.accel, p, active));
        for (int i = 0; i < W && k * W + i < rays.size(); ++i)
            if (((got >> i) & 1u) != want[k * W + i]) ++bad;
    });
    return bad;
}

/// The same through intersect_closest_block / intersect_any_block, max_block_rays rays a block.
template <int W>
size_t closest_block_mismatches(const Loaded& l, const std::vector<Ray>& rays,
                                const std::vector<Hit>& want) {
    constexpr int per_block = max_block_rays / W;
    std::atomic<size_t> bad{0};
    const size_t packets = (rays.size() + W - 1) / W;
    tbb::parallel_for(size_t(0), (packets + per_block - 1) / per_block, [&](size_t b) {
        RayPacket<W> p[per_block];
        vmask<W> active[per_block] = {};
        HitPacket<W> got[per_block];
        int count = 0;
        for (size_t k = b * per_block; k < std::min(packets, (b + 1) * per_block); ++k, ++count)
            p[count] = make_packet<W>(rays, k * W, active[count]);
        intersect_closest_block(l.scene, l.accel, p, active, got, count);
        for (int c = 0; c < count; ++c) {
            const size_t k = b * per_block + size_t(c);
            for (int i = 0; i < W && k * W + i < rays.size(); ++i) {
                const Hit g = get_hit(got[c], i), w = want[k * W + i];
                if (g.object != w.object || g.prim != w.prim || (w.hit() && g.t != w.t)) ++bad;
            }
        }
    });
    return bad;
}

template <int W>
size_t any_block_mismatches(const Loaded& l, const std::vector<Ray>& rays,
                            const std::vector<uint8_t>& want) {
    constexpr int per_block = max_block_rays / W;
    std::atomic<size_t> bad{0};
    const size_t packets = (rays.size() + W - 1) / W;
    tbb::parallel_for(size_t(0), (packets + per_block - 1) / per_block, [&](size_t b) {
        RayPacket<W> p[per_block];
        vmask<W> active[per_block] = {}, got[per_block] = {};
        int count = 0;
        for (size_t k = b * per_block; k < std::min(packets, (b + 1) * per_block); ++k, ++count)
            p[count] = make_packet<W>(rays, k * W, active[count]);
        intersect_any_block(l.scene, l.accel, p, active, got, count);
        for (int c = 0; c < count; ++c) {
            const size_t k = b * per_block + size_t(c);
            const uint32_t g = bits(got[c]);
            for (int i = 0; i < W && k * W + i < rays.size(); ++i)
                if (((g >> i) & 1u) != want[k * W + i]) ++bad;
        }
    });
    return bad;
}

/// Calls trace(packets, active, count, first) for the rays in streams of `stream_rays` rays (a
/// partial one at the end); `first` is the stream's first packet number.
template <int W, class Trace>
void for_each_stream(const std::vector<Ray>& rays, size_t stream_rays, Trace&& trace) {
    const size_t per_stream = stream_rays / W;
    const size_t packets = (rays.size() + W - 1) / W;
    tbb::parallel_for(size_t(0), (packets + per_stream - 1) / per_stream, [&](size_t b) {
        std::vector<RayPacket<W>> p(per_stream);
        const std::unique_ptr<vmask<W>[]> active(new vmask<W>[per_stream]);  // not vector<bool>
        int count = 0;
        for (size_t k = b * per_stream; k < std::min(packets, (b + 1) * per_stream); ++k, ++count)
            p[size_t(count)] = make_packet<W>(rays, k * W, active[size_t(count)]);
        trace(p.data(), active.get(), count, b * per_stream);
    });
}

/// The same through intersect_closest_stream / intersect_any_stream (uv compared too).
template <int W>
size_t closest_stream_mismatches(const Loaded& l, const std::vector<Ray>& rays,
                                 const std::vector<Hit>& want, size_t stream_rays = 4096) {
    std::atomic<size_t> bad{0};
    for_each_stream<W>(rays, stream_rays,
                       [&](const RayPacket<W>* p, const vmask<W>* active, int count, size_t first) {
                           std::vector<HitPacket<W>> got(static_cast<size_t>(count));
                           intersect_closest_stream(l.scene, l.accel, p, active, got.data(), count);
                           for (int c = 0; c < count; ++c) {
                               const size_t k = first + size_t(c);
                               for (int i = 0; i < W && k * W + i < rays.size(); ++i) {
                                   const Hit g = get_hit(got[size_t(c)], i), w = want[k * W + i];
                                   if (g.object != w.object || g.prim != w.prim ||
                                       (w.hit() && g.t != w.t) ||
                                       (w.hit() && (g.uv.x != w.uv.x || g.uv.y != w.uv.y)))
                                       ++bad;
                               }
                           }
                       });
    return bad;
}

template <int W>
size_t any_stream_mismatches(const Loaded& l, const std::vector<Ray>& rays,
                             const std::vector<uint8_t>& want, size_t stream_rays = 4096) {
    std::atomic<size_t> bad{0};
    for_each_stream<W>(
        rays, stream_rays,
        [&](const RayPacket<W>* p, const vmask<W>* active, int count, size_t first) {
            const std::unique_ptr<vmask<W>[]> got(new vmask<W>[static_cast<size_t>(count) + 1]);
            intersect_any_stream(l.scene, l.accel, p, active, got.get(), count);
            for (int c = 0; c < count; ++c) {
                const size_t k = first + size_t(c);
                const uint32_t g = bits(got[size_t(c)]);
                for (int i = 0; i < W && k * W + i < rays.size(); ++i)
                    if (((g >> i) & 1u) != want[k * W + i]) ++bad;
            }
        });
    return bad;
}

/// The scalar path's answers for a ray set (the reference every packet form is held to).
struct ScalarAnswers {
    std::vector<Hit> closest;
    std::vector<uint8_t> blocked;
    size_t hits = 0;
};
ScalarAnswers scalar_answers(const Loaded& l, const std::vector<Ray>& rays) {
    ScalarAnswers a{std::vector<Hit>(rays.size()), std::vector<uint8_t>(rays.size()), 0};
    for (size_t i = 0; i < rays.size(); ++i) {
        a.closest[i] = intersect_closest(l.scene, l.accel, rays[i]);
        a.blocked[i] = intersect_any(l.scene, l.accel, rays[i]);
        a.hits += a.closest[i].hit();
    }
    return a;
}

template <class T>
class IntersectPacket : public ::testing::Test {};
TYPED_TEST_SUITE(IntersectPacket, Widths, WidthName);

const RaySets& ray_sets(const std::string& name, BvhBuild method) {
    static std::map<std::pair<std::string, BvhBuild>, RaySets> cache;
    const auto key = std::make_pair(name, method);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    return cache[key] = make_ray_sets(*load(name, method));
}

// The allowance for rays within rounding of a shared edge: none. The packet triangle test does
// the scalar test's float operations in the same order, so every lane is bit-identical.
void check_scene(const std::string& name,
                 size_t (*closest)(const Loaded&, const std::vector<Ray>&, const std::vector<Hit>&),
                 size_t (*any_hit)(const Loaded&, const std::vector<Ray>&,
                                   const std::vector<uint8_t>&),
                 BvhBuild method = BvhBuild::median) {
    const std::shared_ptr<Loaded> l = load(name, method);
    if (!l) RAYLANE_MODEL_MISSING() << "scenes/" << name << ".json or its model is not available";
    const RaySets& s = ray_sets(name, method);
    size_t hits = 0;
    for (const Hit& h : s.camera_hits) hits += h.hit();
    EXPECT_GT(hits, s.camera.size() / 10) << "the camera rays must hit something";
    EXPECT_GT(s.shadow.size(), s.camera.size() / 10);
    EXPECT_EQ(closest(*l, s.camera, s.camera_hits), 0u) << "camera rays";
    EXPECT_EQ(any_hit(*l, s.shadow, s.shadow_blocked), 0u) << "shadow rays";
    EXPECT_EQ(closest(*l, s.bounce, s.bounce_hits), 0u) << "bounce rays";
}

TYPED_TEST(IntersectPacket, MatchesScalarOnTheDragon) {
    constexpr int W = TypeParam::value;
    check_scene("dragon", closest_mismatches<W>, any_mismatches<W>);
}

TYPED_TEST(IntersectPacket, MatchesScalarOnTheBunny) {
    constexpr int W = TypeParam::value;
    check_scene("bunny", closest_mismatches<W>, any_mismatches<W>);
}

TYPED_TEST(IntersectPacket, MatchesScalarOnEveryAnalyticShape) {
    constexpr int W = TypeParam::value;
    check_scene("builtin", closest_mismatches<W>, any_mismatches<W>);
}

TYPED_TEST(IntersectPacket, BlocksMatchScalarOnTheDragon) {
    constexpr int W = TypeParam::value;
    check_scene("dragon", closest_block_mismatches<W>, any_block_mismatches<W>);
}

TYPED_TEST(IntersectPacket, BlocksMatchScalarOnTheBunny) {
    constexpr int W = TypeParam::value;
    check_scene("bunny", closest_block_mismatches<W>, any_block_mismatches<W>);
}

TYPED_TEST(IntersectPacket, BlocksMatchScalarOnEveryAnalyticShape) {
    constexpr int W = TypeParam::value;
    check_scene("builtin", closest_block_mismatches<W>, any_block_mismatches<W>);
}

/// Streams on every ray set of a scene, also the bounce rays as occlusion queries (incoherent
/// shadow rays), in streams of 4096 rays and of 96 (lists shorter than a packet from the root
/// on).
template <int W>
void check_scene_streams(const std::string& name, BvhBuild method = BvhBuild::median) {
    const std::shared_ptr<Loaded> l = load(name, method);
    if (!l) RAYLANE_MODEL_MISSING() << "scenes/" << name << ".json or its model is not available";
    const RaySets& s = ray_sets(name, method);
    std::vector<uint8_t> bounce_blocked(s.bounce.size());
    tbb::parallel_for(size_t(0), s.bounce.size(), [&](size_t i) {
        bounce_blocked[i] = intersect_any(l->scene, l->accel, s.bounce[i]);
    });
    size_t hits = 0, blocked = 0;
    for (const Hit& h : s.bounce_hits) hits += h.hit();
    for (uint8_t b : s.shadow_blocked) blocked += b;
    EXPECT_GT(hits, s.bounce.size() / 20) << "the bounce rays must hit something";
    EXPECT_GT(blocked, s.shadow.size() / 100) << "some shadow rays must be blocked";
    for (size_t stream_rays : {4096, 96}) {
        EXPECT_EQ(closest_stream_mismatches<W>(*l, s.camera, s.camera_hits, stream_rays), 0u)
            << "camera rays";
        EXPECT_EQ(closest_stream_mismatches<W>(*l, s.bounce, s.bounce_hits, stream_rays), 0u)
            << "bounce rays";
        EXPECT_EQ(any_stream_mismatches<W>(*l, s.shadow, s.shadow_blocked, stream_rays), 0u)
            << "shadow rays";
        EXPECT_EQ(any_stream_mismatches<W>(*l, s.bounce, bounce_blocked, stream_rays), 0u)
            << "bounce rays as occlusion queries";
    }
}

TYPED_TEST(IntersectPacket, StreamsMatchScalarOnTheDragon) {
    check_scene_streams<TypeParam::value>("dragon");
}

TYPED_TEST(IntersectPacket, StreamsMatchScalarOnTheBunny) {
    check_scene_streams<TypeParam::value>("bunny");
}

TYPED_TEST(IntersectPacket, StreamsMatchScalarOnEveryAnalyticShape) {
    check_scene_streams<TypeParam::value>("builtin");
}

/// The traversals make no assumption about the tree beyond its layout: through the SAH build
/// (a comparison option) packets and blocks still give the scalar answers, and the scalar
/// answers are the median tree's (the closest hit does not depend on the tree).
TYPED_TEST(IntersectPacket, PacketsAndBlocksMatchScalarThroughTheSahBuild) {
    constexpr int W = TypeParam::value;
    check_scene("dragon", closest_mismatches<W>, any_mismatches<W>, BvhBuild::sah);
    check_scene("dragon", closest_block_mismatches<W>, any_block_mismatches<W>, BvhBuild::sah);
    check_scene("builtin", closest_block_mismatches<W>, any_block_mismatches<W>, BvhBuild::sah);
    check_scene_streams<W>("dragon", BvhBuild::sah);
    const std::shared_ptr<Loaded> median = load("dragon");
    if (!median) return;
    const RaySets &a = ray_sets("dragon", BvhBuild::median), &b = ray_sets("dragon", BvhBuild::sah);
    ASSERT_EQ(a.camera.size(), b.camera.size());
    size_t differ = 0;
    for (size_t i = 0; i < a.camera_hits.size(); ++i)
        differ += a.camera_hits[i].prim != b.camera_hits[i].prim ||
                  a.camera_hits[i].t != b.camera_hits[i].t;
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(a.shadow_blocked, b.shadow_blocked);
}

TYPED_TEST(IntersectPacket, MatchesScalarOnAwkwardRays) {
    constexpr int W = TypeParam::value;
    const std::shared_ptr<Loaded> l = load("builtin");
    std::vector<Ray> rays;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const vec3 dirs[] = {{1, 0, 0},           {0, -1, 0},      {-0.0f, 0, 1}, {0, 0, -1},
                         {0.0f, -0.0f, 1.0f}, {1e-30f, -1, 0}, {1, 1, 0},     {0, -1, 1},
                         {nan, 0.2f, 1}};  // a NaN lane: no hit, and no effect on its block
    const vec3 origins[] = {{0, 0, -5},    {0, 3, 0},  {0, 0, 0},
                            {-1, 0.5f, 2}, {1, -1, 5}, {nan, 0, -5}};
    const float t_maxes[] = {infinity, 0.0f, 1.0f, 100.0f};
    for (vec3 o : origins)
        for (vec3 d : dirs)
            for (float t_max : t_maxes) rays.push_back({o, d, 0.0f, t_max});
    // origins on surfaces: the scalar hit points of a fan of rays, re-launched in both directions
    const std::vector<Ray> first = rays;
    for (const Ray& r : first) {
        const Hit h = intersect_closest(l->scene, l->accel, r);
        if (!h.hit()) continue;
        const vec3 p = r.org + h.t * r.dir;
        rays.push_back({p, r.dir, 0.0f, infinity});
        rays.push_back({p, -r.dir, 0.0f, infinity});
    }
    const ScalarAnswers want = scalar_answers(*l, rays);
    EXPECT_EQ(closest_mismatches<W>(*l, rays, want.closest), 0u);
    EXPECT_EQ(any_mismatches<W>(*l, rays, want.blocked), 0u);
    EXPECT_EQ(closest_block_mismatches<W>(*l, rays, want.closest), 0u);
    EXPECT_EQ(any_block_mismatches<W>(*l, rays, want.blocked), 0u);
    for (size_t stream_rays : {4096, 32}) {
        EXPECT_EQ(closest_stream_mismatches<W>(*l, rays, want.closest, stream_rays), 0u);
        EXPECT_EQ(any_stream_mismatches<W>(*l, rays, want.blocked, stream_rays), 0u);
    }
}

/// A UV sphere of triangles (rings x segments quads, two triangles each).
MeshData tessellated_sphere(vec3 centre, float radius, int rings, int segments) {
    MeshData m;
    m.name = "sphere";
    for (int i = 0; i <= rings; ++i) {
        const float theta = 3.14159265f * float(i) / float(rings);
        for (int j = 0; j < segments; ++j) {
            const float phi = 6.28318531f * float(j) / float(segments);
            m.positions.push_back(centre + radius * vec3(std::sin(theta) * std::cos(phi),
                                                         std::cos(theta),
                                                         std::sin(theta) * std::sin(phi)));
        }
    }
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const auto at = [&](int r, int c) { return uint32_t(r * segments + c % segments); };
            const uint32_t a = at(i, j), b = at(i, j + 1), c = at(i + 1, j), d = at(i + 1, j + 1);
            if (i > 0) m.tris.push_back({a, b, c});  // the poles' quads are triangles
            if (i + 1 < rings) m.tris.push_back({b, d, c});
        }
    }
    return m;
}

/// The built-in scene's analytic shapes with two meshes beside them: the stream traversal's
/// nested top-level and mesh traversals, its leaves and its hand-over of short lists to the
/// packet traversal, on the awkward rays of MatchesScalarOnAwkwardRays (zero and NaN
/// components, t_max 0 and infinity, origins on surfaces in both directions) and on random rays
/// through the meshes; every third lane inactive though it holds a ray that hits (inactive
/// lanes must come back as misses, and not occluded).
TYPED_TEST(IntersectPacket, StreamsMatchScalarOnAwkwardRaysThroughMeshes) {
    constexpr int W = TypeParam::value;
    Loaded l;
    l.scene = make_builtin_scene();
    for (const auto& [centre, radius, rings] : {std::tuple{vec3(0.0f, 0.5f, 0.0f), 0.8f, 40},
                                                std::tuple{vec3(-1.0f, 0.5f, 2.0f), 0.5f, 9}}) {
        Object o;
        o.kind = ShapeKind::mesh;
        o.shape = uint32_t(l.scene.meshes.size());
        l.scene.objects.push_back(o);
        l.scene.meshes.push_back(tessellated_sphere(centre, radius, rings, 2 * rings));
    }
    l.accel = build_accel(l.scene, BuildParams{});
    std::vector<Ray> rays;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const vec3 dirs[] = {{1, 0, 0},  {0, -1, 0},          {-0.0f, 0, 1},
                         {0, 0, -1}, {0.0f, -0.0f, 1.0f}, {1e-30f, -1, 0},
                         {1, 1, 0},  {0, -1, 1},          {nan, 0.2f, 1}};
    const vec3 origins[] = {{0, 0.5f, -5}, {0, 3, 0},     {0, 0.5f, 0}, {-1, 0.5f, 2},
                            {1, -1, 5},    {-4, 0.6f, 2}, {nan, 0, -5}};
    const float t_maxes[] = {infinity, 0.0f, 1.0f, 100.0f};
    for (vec3 o : origins)
        for (vec3 d : dirs)
            for (float t_max : t_maxes) rays.push_back({o, d, 0.0f, t_max});
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    for (int k = 0; k < 20000; ++k) {  // from all around, half of them at the meshes
        const vec3 o(4.0f * uni(rng), 0.5f + 2.0f * uni(rng), 4.0f * uni(rng));
        const vec3 aim =
            k % 4 == 0   ? vec3(0.0f, 0.5f, 0.0f) + 0.8f * vec3(uni(rng), uni(rng), uni(rng))
            : k % 4 == 1 ? vec3(-1.0f, 0.5f, 2.0f) + 0.5f * vec3(uni(rng), uni(rng), uni(rng))
                         : o + vec3(uni(rng), uni(rng), uni(rng));
        rays.push_back({o, aim - o, 0.0f, infinity});
    }
    const std::vector<Ray> first = rays;
    for (const Ray& r : first) {
        const Hit h = intersect_closest(l.scene, l.accel, r);
        if (!h.hit()) continue;
        const vec3 p = r.org + h.t * r.dir;
        rays.push_back({p, r.dir, 0.0f, infinity});
        rays.push_back({p, -r.dir, 0.0f, infinity});
    }
    ScalarAnswers want = scalar_answers(l, rays);
    size_t mesh_hits = 0;
    for (const Hit& h : want.closest)
        mesh_hits += h.hit() && l.scene.objects[h.object].kind == ShapeKind::mesh;
    EXPECT_GT(mesh_hits, rays.size() / 10);
    for (size_t stream_rays : {4096, 32}) {
        EXPECT_EQ(closest_stream_mismatches<W>(l, rays, want.closest, stream_rays), 0u);
        EXPECT_EQ(any_stream_mismatches<W>(l, rays, want.blocked, stream_rays), 0u);
    }
    // every third lane inactive, holding a ray that hits
    const size_t packets = (rays.size() + W - 1) / W;
    std::vector<RayPacket<W>> p(packets);
    const std::unique_ptr<vmask<W>[]> active(new vmask<W>[packets]),
        occluded(new vmask<W>[packets]);
    std::vector<HitPacket<W>> got(packets);
    size_t lane = 0;
    for (size_t k = 0; k < packets; ++k) {
        p[k] = make_packet<W>(rays, k * W, active[k]);
        uint32_t keep = 0;
        for (int i = 0; i < W; ++i, ++lane) keep |= uint32_t(lane % 3 != 0) << i;
        active[k] = mask_and(active[k], mask_from_bits<W>(keep));
    }
    intersect_closest_stream(l.scene, l.accel, p.data(), active.get(), got.data(), int(packets));
    intersect_any_stream(l.scene, l.accel, p.data(), active.get(), occluded.get(), int(packets));
    size_t bad = 0, off = 0;
    for (size_t k = 0; k < packets; ++k) {
        for (int i = 0; i < W && k * W + size_t(i) < rays.size(); ++i) {
            const size_t r = k * W + size_t(i);
            const bool on = (bits(active[k]) >> i) & 1u;
            const Hit g = get_hit(got[k], i);
            const Hit w = on ? want.closest[r] : Hit{};
            off += !on;
            bad += g.object != w.object || g.prim != w.prim || (w.hit() && g.t != w.t);
            bad += ((bits(occluded[k]) >> i) & 1u) != (on ? want.blocked[r] : 0u);
        }
    }
    EXPECT_GT(off, rays.size() / 4);
    EXPECT_EQ(bad, 0u);
    // no packets at all
    intersect_closest_stream(l.scene, l.accel, p.data(), active.get(), got.data(), 0);
    intersect_any_stream(l.scene, l.accel, p.data(), active.get(), occluded.get(), 0);
}

/// A closest-hit block culls a node that its first packet misses when the node lies beyond the
/// largest limit of the block's lanes (intersect_closest_block lowers the block's t bound as hits
/// are found). Parallel rays along (0.001, 0, 1) from a 16x16 grid: row 0 meets a triangle at
/// z = 5, rows 1 to 7 (y < 0) a triangle at z = 10, rows 8 to 15 (y > 0) a triangle at z = 9.995
/// before the one at 10. With leaves of one triangle the tree visits z = 5, then z = 10 (the
/// lower x, and the rays go to +x), then z = 9.995; there the range's first packet (row 1, or
/// its first W rays) misses the box and only the block's bound, the largest limit 10, keeps the
/// leaf: a bound 0.1 % too small (9.99), or the smallest limit (5) instead of the largest, culls
/// it and rows 8 to 15 would report z = 10.
TYPED_TEST(IntersectPacket, BlocksCullOnlyNodesBeyondEveryLanesLimit) {
    constexpr int W = TypeParam::value;
    Loaded l;
    l.scene.materials.resize(1);
    MeshData three;
    three.positions = {{-3.0f, -3.0f, 10.0f},   {2.0f, -3.0f, 10.0f},   {-0.5f, 6.0f, 10.0f},
                       {-0.5f, 0.0f, 9.995f},   {2.5f, 0.0f, 9.995f},   {1.0f, 3.0f, 9.995f},
                       {-1.0f, -0.0875f, 5.0f}, {1.0f, -0.0875f, 5.0f}, {0.0f, -1.0f, 5.0f}};
    three.tris = {uvec3(0, 1, 2), uvec3(3, 4, 5), uvec3(6, 7, 8)};
    l.scene.meshes.push_back(three);
    Object o;
    o.kind = ShapeKind::mesh;
    l.scene.objects.push_back(o);
    l.accel = build_accel(l.scene, BuildParams{1});
    // the leaves in visiting order: z = 5 (split on z), then z = 10 before z = 9.995 (split on x)
    const Bvh& bvh = l.accel.meshes[0].bvh;
    ASSERT_EQ(std::vector<uint32_t>(bvh.prim_ids.begin(), bvh.prim_ids.end()),
              (std::vector<uint32_t>{2, 0, 1}));
    ASSERT_EQ(bvh.nodes[0].axis, 2);
    std::vector<Ray> rays;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            rays.push_back({vec3(-0.1f + 0.0125f * (float(x) + 0.5f),
                                 -0.1f + 0.0125f * (float(y) + 0.5f), 0.0f),
                            vec3(0.001f, 0.0f, 1.0f), 0.0f, infinity});
    const ScalarAnswers want = scalar_answers(l, rays);
    size_t hits_of[3] = {0, 0, 0};
    for (size_t i = 0; i < rays.size(); ++i) {
        ASSERT_TRUE(want.closest[i].hit());
        ++hits_of[want.closest[i].prim];
    }
    EXPECT_EQ(hits_of[2], 16u) << "row 0 hits the triangle at z = 5";
    EXPECT_EQ(hits_of[0], 7u * 16u) << "rows 1 to 7 hit the triangle at z = 10";
    EXPECT_EQ(hits_of[1], 8u * 16u) << "rows 8 to 15 hit the triangle at z = 9.995";
    EXPECT_EQ(closest_block_mismatches<W>(l, rays, want.closest), 0u);
}

/// The oracle test's adversarial rays (origins on face planes; zero, -0, denormal and tiny
/// direction components; rays through corners and along edges), a million of them, at the cube
/// and its coplanar floor: blocks of consecutive rays and streams give the scalar answers.
TYPED_TEST(IntersectPacket, BlocksAndStreamsMatchScalarOnAdversarialRays) {
    constexpr int W = TypeParam::value;
    Loaded l;
    using namespace geometry_test;
    l.scene =
        make_mesh_scene({make_cube_mesh(vec3(0.0f), vec3(1.0f)), make_floor_mesh(0.0f, 2.0f)});
    l.accel = build_accel(l.scene, BuildParams{1});
    const std::vector<Ray> rays = adversarial_rays(ray_count(1000000));
    const ScalarAnswers want = scalar_answers(l, rays);
    EXPECT_GT(want.hits, rays.size() / 5);
    EXPECT_EQ(closest_block_mismatches<W>(l, rays, want.closest), 0u);
    EXPECT_EQ(any_block_mismatches<W>(l, rays, want.blocked), 0u);
    EXPECT_EQ(closest_stream_mismatches<W>(l, rays, want.closest), 0u);
    EXPECT_EQ(any_stream_mismatches<W>(l, rays, want.blocked), 0u);
}

/// Packets of one active lane each (the lane moving through 0 .. W - 1), alone and in blocks:
/// leaves test such a packet by ray (leaf_packet.h, leaf_lanes triangles at once), and the
/// answers are the scalar path's, on the dragon's and the bunny's camera, shadow and bounce rays.
TYPED_TEST(IntersectPacket, LoneLanesMatchScalar) {
    constexpr int W = TypeParam::value;
    constexpr int per_block = max_block_rays / W;
    for (const char* name : {"dragon", "bunny"}) {
        const std::shared_ptr<Loaded> l = load(name);
        if (!l)
            RAYLANE_MODEL_MISSING() << "scenes/" << name << ".json or its model is not available";
        const RaySets& s = ray_sets(name, BvhBuild::median);
        // blocks of packets with ray k alone in lane k % W, the other lanes inactive (benign:
        // t_max < t_min), for the first 200k rays; check(p, active, count, first ray) counts
        // the block's mismatches
        auto lone_blocks = [&](const std::vector<Ray>& rays, auto&& check) {
            std::atomic<size_t> bad{0};
            const size_t n = std::min<size_t>(rays.size(), 200000);
            tbb::parallel_for(size_t(0), (n + per_block - 1) / per_block, [&](size_t b) {
                RayPacket<W> p[per_block];
                vmask<W> active[per_block] = {};
                int count = 0;
                for (size_t k = b * per_block; k < std::min(n, (b + 1) * per_block); ++k, ++count) {
                    Ray off;
                    off.t_max = -1.0f;
                    for (int i = 0; i < W; ++i)
                        set_ray(p[count], i, i == int(k % W) ? rays[k] : off);
                    active[count] = mask_from_bits<W>(1u << (k % W));
                }
                bad += check(p, active, count, b * per_block);
            });
            return bad.load();
        };
        auto closest = [&](const std::vector<Ray>& rays, const std::vector<Hit>& want) {
            return lone_blocks(rays, [&](const RayPacket<W>* p, const vmask<W>* active, int count,
                                         size_t first) {
                HitPacket<W> got[per_block];
                intersect_closest_block(l->scene, l->accel, p, active, got, count);
                size_t bad = 0;
                for (int c = 0; c < count; ++c) {
                    const size_t k = first + size_t(c);
                    const HitPacket<W> alone =
                        intersect_closest(l->scene, l->accel, p[c], active[c]);
                    for (const HitPacket<W>& h : {got[c], alone}) {
                        const Hit g = get_hit(h, int(k % W)), w = want[k];
                        if (g.object != w.object || g.prim != w.prim || (w.hit() && g.t != w.t) ||
                            (w.hit() && (g.uv.x != w.uv.x || g.uv.y != w.uv.y)))
                            ++bad;
                    }
                }
                return bad;
            });
        };
        auto any_hit = [&](const std::vector<Ray>& rays, const std::vector<uint8_t>& want) {
            return lone_blocks(rays, [&](const RayPacket<W>* p, const vmask<W>* active, int count,
                                         size_t first) {
                vmask<W> got[per_block] = {};
                intersect_any_block(l->scene, l->accel, p, active, got, count);
                size_t bad = 0;
                for (int c = 0; c < count; ++c) {
                    const size_t k = first + size_t(c);
                    const uint32_t lane = 1u << (k % W);
                    const uint32_t alone = bits(intersect_any(l->scene, l->accel, p[c], active[c]));
                    bad += ((bits(got[c]) & lane) != 0) != (want[k] != 0);
                    bad += ((alone & lane) != 0) != (want[k] != 0);
                }
                return bad;
            });
        };
        EXPECT_EQ(closest(s.camera, s.camera_hits), 0u) << name << " camera rays";
        EXPECT_EQ(any_hit(s.shadow, s.shadow_blocked), 0u) << name << " shadow rays";
        EXPECT_EQ(closest(s.bounce, s.bounce_hits), 0u) << name << " bounce rays";
    }
}

/// The camera's rays reversed, searching behind their origin (t in (-1e4, 0)): block culling
/// must not assume t >= 0.
TYPED_TEST(IntersectPacket, BlocksHandleNegativeIntervals) {
    constexpr int W = TypeParam::value;
    for (const char* name : {"dragon", "builtin"}) {
        const std::shared_ptr<Loaded> l = load(name);
        if (!l) continue;
        Camera cam = l->scene.camera;
        cam.width = 160;
        cam.height = 90;
        const CameraFrame frame = make_camera_frame(cam);
        std::vector<Ray> rays;
        for (int y = 0; y < cam.height; ++y) {
            for (int x = 0; x < cam.width; ++x) {
                const Ray r = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
                rays.push_back({r.org, -r.dir, -1e4f, 0.0f});
            }
        }
        const ScalarAnswers want = scalar_answers(*l, rays);
        EXPECT_GT(want.hits, rays.size() / 4) << name;
        EXPECT_EQ(closest_block_mismatches<W>(*l, rays, want.closest), 0u) << name;
        EXPECT_EQ(any_block_mismatches<W>(*l, rays, want.blocked), 0u) << name;
        EXPECT_EQ(closest_stream_mismatches<W>(*l, rays, want.closest), 0u) << name;
        EXPECT_EQ(any_stream_mismatches<W>(*l, rays, want.blocked), 0u) << name;
    }
}

/// Blocks whose rays include infinite or huge direction components beside finite ones: the
/// reciprocal of -inf is -0, and of -1e38 a denormal that flush-to-zero (the render threads' mode)
/// makes -0, so the block's reciprocal bounds on that axis touch zero and the axis must not cull
/// (block_may_hit takes the axis's sign from them). A box at x in [-10, -5], y in [12, 100]: the
/// rays (-0.5, 1, 0) from the origin cross it for t in [12, 20]; each block mixes them with rays
/// of one other direction, with and without flush-to-zero, t_min 0 and 1.
TYPED_TEST(IntersectPacket, BlocksWithInfiniteOrHugeDirectionsMatchScalar) {
    constexpr int W = TypeParam::value;
    Loaded l;
    l.scene.materials.resize(1);
    l.scene.boxes = {Box{vec3(-10.0f, 12.0f, -1.0f), vec3(-5.0f, 100.0f, 1.0f)}};
    l.scene.objects.resize(1);
    l.scene.objects[0].kind = ShapeKind::box;
    l.accel = build_accel(l.scene, BuildParams{});
    const float inf = std::numeric_limits<float>::infinity();
    const vec3 dirs[] = {{-0.5f, 1.0f, 0.0f}, {-inf, 1.0f, 0.0f},  {-1e38f, 1.0f, 0.0f},
                         {-0.5f, inf, 0.0f},  {-0.5f, 1.0f, -inf}, {-0.5f, 1e38f, 0.0f}};
    // block j (of 10) alternates dirs[0] with dirs[1 + j / 2], at t_min 0 or 1
    std::vector<Ray> rays;
    for (int j = 0; j < 10; ++j)
        for (int i = 0; i < max_block_rays; ++i)
            rays.push_back({vec3(0.0f), dirs[i % 2 == 0 ? 0 : 1 + j / 2], float(j % 2), infinity});
    const unsigned saved = _mm_getcsr();
    for (bool ftz : {false, true}) {
        if (ftz) _mm_setcsr(saved | 0x8040u);  // FTZ | DAZ, as the render threads run
        const ScalarAnswers want = scalar_answers(l, rays);
        EXPECT_GE(want.hits, rays.size() / 2) << "ftz " << ftz;
        // the blocks on this thread, so that they run in the same floating-point mode
        constexpr int per_block = max_block_rays / W;
        size_t bad = 0;
        for (size_t b = 0; b < rays.size(); b += max_block_rays) {
            RayPacket<W> p[per_block];
            vmask<W> active[per_block] = {}, occluded[per_block] = {};
            HitPacket<W> got[per_block];
            for (int c = 0; c < per_block; ++c)
                p[c] = make_packet<W>(rays, b + size_t(c) * W, active[c]);
            HitPacket<W> streamed[per_block];
            vmask<W> stream_occluded[per_block] = {};
            intersect_closest_block(l.scene, l.accel, p, active, got, per_block);
            intersect_any_block(l.scene, l.accel, p, active, occluded, per_block);
            intersect_closest_stream(l.scene, l.accel, p, active, streamed, per_block);
            intersect_any_stream(l.scene, l.accel, p, active, stream_occluded, per_block);
            for (int c = 0; c < per_block; ++c) {
                for (int i = 0; i < W; ++i) {
                    const size_t k = b + size_t(c) * W + size_t(i);
                    const Hit w = want.closest[k];
                    for (const Hit& g : {get_hit(got[c], i), get_hit(streamed[c], i)})
                        bad += g.prim != w.prim || (w.hit() && g.t != w.t);
                    bad += ((bits(occluded[c]) >> i) & 1u) != want.blocked[k];
                    bad += ((bits(stream_occluded[c]) >> i) & 1u) != want.blocked[k];
                }
            }
        }
        EXPECT_EQ(bad, 0u) << "ftz " << ftz;
    }
    _mm_setcsr(saved);
}

/// Blocks of rays leaving a plane from points on it (offset as the renderer offsets them): a
/// tilted plane far from the origin and a rotated, scaled, translated one. Each block of 256 rays
/// shares an elevation above its plane, from steep to grazing to slightly below: blocks that all
/// leave are culled against the plane (block_may_hit_plane), the others tested; every answer must
/// be the scalar one.
TYPED_TEST(IntersectPacket, BlocksMatchScalarOnRaysLeavingPlanes) {
    constexpr int W = TypeParam::value;
    Loaded l;
    l.scene.materials.resize(1);
    l.scene.planes = {Plane{vec3(1000.0f, -3.0f, 2000.0f), glm::normalize(vec3(0.2f, 1.0f, -0.1f))},
                      Plane{vec3(0.5f, 0.25f, -1.0f), glm::normalize(vec3(0.3f, 0.9f, 0.2f))}};
    Transform t;
    t.translate = glm::dvec3(5.0, -2.0, 300.0);
    t.rotate = make_rotation_xyz(glm::dvec3(20.0, 35.0, -10.0));
    t.scale = glm::dvec3(2.0, 0.5, 3.0);
    l.scene.objects.resize(2);
    for (uint32_t i = 0; i < 2; ++i) {
        l.scene.objects[i].kind = ShapeKind::plane;
        l.scene.objects[i].shape = i;
    }
    set_transform(l.scene.objects[1], t);
    ASSERT_TRUE(l.scene.objects[1].has_transform);
    l.accel = build_accel(l.scene, BuildParams{});

    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
    const float elevations[] = {1.2f, 0.2f, 1e-2f, 1e-4f, 1e-6f, 0.0f, -1e-6f, -1e-3f};
    std::vector<Ray> rays;
    for (uint32_t i = 0; i < 2; ++i) {
        const Object& object = l.scene.objects[i];
        const Plane& plane = l.scene.planes[i];
        // a frame on the plane in world space
        const glm::mat3 normal_to_world = glm::transpose(glm::mat3(object.object_from_world));
        const vec3 n = glm::normalize(normal_to_world * plane.normal);
        const vec3 a = glm::normalize(glm::cross(n, vec3(0.0f, 0.0f, 1.0f)));
        const vec3 b = glm::cross(n, a);
        for (float elevation : elevations) {
            for (float spread : {0.01f, 10.0f}) {
                for (int block = 0; block < 4; ++block) {
                    const float azimuth = 3.14159f * uni(rng);
                    const vec3 d0 =
                        std::cos(elevation) * (std::cos(azimuth) * a + std::sin(azimuth) * b) +
                        std::sin(elevation) * n;
                    for (int k = 0; k < max_block_rays; ++k) {
                        const vec3 q = plane.point + spread * (uni(rng) * vec3(1, 0, 0) +
                                                               uni(rng) * vec3(0, 0, 1));
                        // onto the plane (object space), then to world space
                        const vec3 on = q - glm::dot(q - plane.point, plane.normal) /
                                                glm::dot(plane.normal, plane.normal) * plane.normal;
                        const vec3 p = vec3(object.world_from_object * glm::vec4(on, 1.0f));
                        const float reach =
                            std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
                        const vec3 o = offset_ray_origin(p, n, reach);
                        const vec3 d = d0 + 1e-3f * vec3(uni(rng), uni(rng), uni(rng));
                        rays.push_back({o, d, 0.0f, k % 2 ? infinity : 50.0f});
                    }
                }
            }
        }
    }
    const ScalarAnswers want = scalar_answers(l, rays);
    EXPECT_GT(want.hits, rays.size() / 20);
    EXPECT_LT(want.hits, rays.size() / 2);
    EXPECT_EQ(closest_block_mismatches<W>(l, rays, want.closest), 0u);
    EXPECT_EQ(any_block_mismatches<W>(l, rays, want.blocked), 0u);
}

TYPED_TEST(IntersectPacket, NoActiveLanesMeansNoHits) {
    constexpr int W = TypeParam::value;
    const std::shared_ptr<Loaded> l = load("builtin");
    RayPacket<W> p;  // all rays along +z from the origin: would hit the scene if active
    const vmask<W> none_active = mask_from_bits<W>(0u);
    const HitPacket<W> h = intersect_closest(l->scene, l->accel, p, none_active);
    EXPECT_EQ(bits(h.t < vfloat<W>(infinity)), 0u);
    EXPECT_EQ(bits(intersect_any(l->scene, l->accel, p, none_active)), 0u);
}

}  // namespace
}  // namespace raylane
