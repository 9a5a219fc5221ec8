// Benchmarks of traverse/: the same rays through every contender, rays per second.
// Scenes: the meshes of scenes/dragon.json and scenes/bunny.json (the mesh alone, so every
// contender traces the same triangles). Ray sets: primary rays at 1920x1080 (1 sample at pixel
// centres, in 16x16 tiles of 4x4 blocks), shadow rays from the primary hits to the scene's
// lights in the renderer's order (per tile and light, one packet per 4x4 pixels, inactive slots
// where the primary ray missed or the point faces away from the light), and one
// cosine-distributed bounce ray per hit (incoherent).
// Contenders: Raylane scalar, Raylane packet at every width, and Embree 3 (rtcIntersect1 / 1M / 16,
// rtcOccluded1 / 16) when it is installed. 1 and 2 threads (oneTBB; chunks of 256 rays).
// With `--rays FILE.npy [--mesh MODEL] [--embree-hits OUT.npy]`: a ray file instead
// (traverse/ray_file_runs.h).
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <random>

#include "core/offset.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "render/tiles.h"
#include "support/summary.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_scalar.h"
#include "traverse/intersect_stream.h"
#include "traverse/ray_file_runs.h"

#ifdef RAYLANE_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace raylane {
namespace {

constexpr size_t chunk = 256;          // rays per task
constexpr size_t stream_rays = 16384;  // rays per task and stream of the Stream contender
constexpr size_t tile_rays = 256;      // primary rays per 16x16 tile

/// A ray set in SoA form, padded with inactive rays (t_max = -1) to a multiple of `chunk`, so
/// every contender reads its rays without repacking (as a renderer generating them would).
struct RaySoa {
    size_t size = 0;          ///< real rays; the padding follows
    std::vector<float> c[8];  ///< org x y z, dir x y z, t_min, t_max
    const float* at(int k, size_t i) const { return c[k].data() + i; }
};

RaySoa make_soa(const std::vector<Ray>& rays) {
    RaySoa s;
    s.size = rays.size();
    const size_t padded = (rays.size() + chunk - 1) / chunk * chunk;
    for (auto& v : s.c) v.resize(padded);
    for (size_t i = 0; i < padded; ++i) {
        Ray r = rays[std::min(i, rays.size() - 1)];
        if (i >= rays.size()) r.t_max = -1.0f;
        const float f[8] = {r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y, r.dir.z, r.t_min, r.t_max};
        for (int k = 0; k < 8; ++k) s.c[k][i] = f[k];
    }
    return s;
}

struct Workload {
    Scene scene;
    Accel accel;      ///< the median split (the report's build; the rays' reference)
    Accel accel_sah;  ///< the binned SAH build, for the Sah contenders
    std::vector<Ray> primary, shadow, bounce;
    RaySoa primary_soa, shadow_soa, bounce_soa;
#ifdef RAYLANE_HAVE_EMBREE
    RTCDevice device = nullptr;
    RTCScene rtc_scene = nullptr;
#endif
};

/// Primary rays in 16x16 tiles, 4x4 blocks inside a tile, row-major inside a block.
std::vector<Ray> primary_rays(const Camera& cam) {
    const CameraFrame frame = make_camera_frame(cam);
    std::vector<Ray> rays;
    rays.reserve(size_t(cam.width) * cam.height);
    for (int ty = 0; ty < cam.height; ty += 16)
        for (int tx = 0; tx < cam.width; tx += 16)
            for (int by = ty; by < ty + 16; by += 4)
                for (int bx = tx; bx < tx + 16; bx += 4)
                    for (int y = by; y < by + 4; ++y)
                        for (int x = bx; x < bx + 4; ++x)
                            if (x < cam.width && y < cam.height)
                                rays.push_back(camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f));
    return rays;
}

#ifdef RAYLANE_HAVE_EMBREE
void build_embree(Workload& w) {
    w.device = rtcNewDevice(nullptr);
    w.rtc_scene = rtcNewScene(w.device);
    for (const Mesh& mesh : w.scene.meshes) {
        RTCGeometry g = rtcNewGeometry(w.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              mesh.positions.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) v[3 * i + k] = mesh.positions[i][k];
        auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.tris.size()));
        for (size_t i = 0; i < mesh.tris.size(); ++i)
            for (int k = 0; k < 3; ++k) idx[3 * i + k] = mesh.tris[i][k];
        rtcCommitGeometry(g);
        rtcAttachGeometry(w.rtc_scene, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(w.rtc_scene);
}
#endif

/// The mesh objects of a scene file with its camera at 1920x1080 and its lights, and the ray sets.
Workload* workload(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Workload>> cache;
    if (auto it = cache.find(name); it != cache.end()) return it->second.get();
    std::unique_ptr<Workload> w;
    try {
        Scene full = load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
        w = std::make_unique<Workload>();
        w->scene = full;
        w->scene.objects.clear();
        for (const Object& o : full.objects)
            if (o.kind == ShapeKind::mesh) w->scene.objects.push_back(o);
        w->scene.camera.width = 1920;
        w->scene.camera.height = 1080;
        w->accel = build_accel(w->scene, BuildParams{});
        w->accel_sah = build_accel(w->scene, BuildParams{.method = BvhBuild::sah});
    } catch (const std::exception&) {
        return (cache[name] = nullptr).get();
    }
    w->primary = primary_rays(w->scene.camera);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    // shadow rays as the renderer's camera pass traces them: for each 16x16 tile and each light
    // that lights a point of it, a block of 16 packets, one per 4x4-pixel packet of primary rays,
    // a ray where the primary ray hit a point facing the light and an inactive slot (t_max = -1)
    // elsewhere (the bottom row's tiles are 16x8: two of them make a block)
    static_assert(tile_rays == size_t(max_block_rays) && chunk % tile_rays == 0);
    for (size_t tile = 0; tile < w->primary.size(); tile += tile_rays) {
        const size_t n = std::min(tile_rays, w->primary.size() - tile);
        std::vector<vec3> from(tile_rays), normal(tile_rays);
        std::vector<bool> hit(tile_rays, false);
        for (size_t i = 0; i < n; ++i) {
            const Ray& r = w->primary[tile + i];
            const Hit h = intersect_closest(w->scene, w->accel, r);
            if (!h.hit()) continue;
            const SurfacePoint sp = surface_at(w->scene, r, h);
            vec3 n_g = sp.geometric_normal;
            if (glm::dot(n_g, r.dir) > 0.0f) n_g = -n_g;
            const vec3 o = offset_ray_origin(sp.position, n_g, ray_reach(r, h.t));
            hit[i] = true;
            from[i] = o;
            normal[i] = n_g;
            const float u1 = uni(rng), u2 = uni(rng), rad = std::sqrt(u1), phi = 6.2831853f * u2;
            const vec3 t = glm::normalize(std::fabs(n_g.x) > 0.5f ? glm::cross(n_g, vec3(0, 1, 0))
                                                                  : glm::cross(n_g, vec3(1, 0, 0)));
            const vec3 b = glm::cross(n_g, t);
            w->bounce.push_back({o,
                                 rad * std::cos(phi) * t + rad * std::sin(phi) * b +
                                     std::sqrt(std::max(0.0f, 1.0f - u1)) * n_g,
                                 0.0f, infinity});
        }
        const auto any = std::find(hit.begin(), hit.end(), true);
        if (any == hit.end()) continue;
        const vec3 spare = from[size_t(any - hit.begin())];  // finite data for inactive slots
        for (const Light& light : w->scene.lights) {
            std::vector<Ray> block;
            bool lit_any = false;
            for (size_t k = 0; k < tile_rays; ++k) {
                const vec3 o = hit[k] ? from[k] : spare;
                Ray r = light.kind == LightKind::point ? Ray{o, light.position - o, 0.0f, 1.0f}
                                                       : Ray{o, light.direction, 0.0f, infinity};
                const bool lit = hit[k] && glm::dot(normal[k], r.dir) > 0.0f;
                if (!lit) r.t_max = -1.0f;
                lit_any = lit_any || lit;
                block.push_back(r);
            }
            if (lit_any) w->shadow.insert(w->shadow.end(), block.begin(), block.end());
        }
    }
    w->primary_soa = make_soa(w->primary);
    w->shadow_soa = make_soa(w->shadow);
    w->bounce_soa = make_soa(w->bounce);
#ifdef RAYLANE_HAVE_EMBREE
    build_embree(*w);
#endif
    return (cache[name] = std::move(w)).get();
}

const std::vector<Ray>& rays_of(const Workload& w, const std::string& set) {
    return set == "primary" ? w.primary : set == "shadow" ? w.shadow : w.bounce;
}
const RaySoa& soa_of(const Workload& w, const std::string& set) {
    return set == "primary" ? w.primary_soa : set == "shadow" ? w.shadow_soa : w.bounce_soa;
}

/// Packet of rays i .. i + W - 1 straight from the SoA arrays; padding lanes are inactive.
template <int W>
RayPacket<W> load_packet(const RaySoa& s, size_t i, vmask<W>& active) {
    RayPacket<W> p;
    p.org = load_vec3<W>(s.at(0, i), s.at(1, i), s.at(2, i));
    p.dir = load_vec3<W>(s.at(3, i), s.at(4, i), s.at(5, i));
    p.t_min = load<W>(s.at(6, i));
    p.t_max = load<W>(s.at(7, i));
    active = p.t_max >= p.t_min;
    return p;
}

/// Whether a ray is a real one (a shadow packet's slots where the primary ray missed are not).
bool active_ray(const Ray& r) { return r.t_max >= r.t_min; }

/// Runs body(first, last) over the rays in chunks on `threads` threads; counts the real rays per
/// second. Chunks cover the padded SoA arrays; the scalar and AoS contenders stop at the last ray
/// and skip inactive slots.
template <class Body>
void run(benchmark::State& state, const std::vector<Ray>& rays, int threads, Body&& body,
         size_t rays_per_task = chunk) {
    const size_t real = size_t(std::count_if(rays.begin(), rays.end(), active_ray));
    const size_t padded = (rays.size() + chunk - 1) / chunk * chunk;
    tbb::task_arena arena(threads);
    for (auto _ : state) {
        arena.execute([&] {
            const size_t tasks = (rays.size() + rays_per_task - 1) / rays_per_task;
            tbb::parallel_for(size_t(0), tasks, [&](size_t c) {
                enable_flush_to_zero();
                body(c * rays_per_task, std::min((c + 1) * rays_per_task, padded));
            });
        });
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(real));
    state.counters["rays/s"] =
        benchmark::Counter(double(real) * double(state.iterations()), benchmark::Counter::kIsRate);
}

void bench_scalar(benchmark::State& state, std::string scene, std::string set, int threads) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const std::vector<Ray>& rays = rays_of(*w, set);
    const bool any_hit = set == "shadow";
    run(state, rays, threads, [&](size_t first, size_t last) {
        uint32_t sum = 0;
        for (size_t i = first; i < std::min(last, rays.size()); ++i)
            if (active_ray(rays[i]))
                sum += any_hit ? intersect_any(w->scene, w->accel, rays[i])
                               : intersect_closest(w->scene, w->accel, rays[i]).prim;
        benchmark::DoNotOptimize(sum);
    });
}

template <int W>
void bench_packet(benchmark::State& state, std::string scene, std::string set, int threads,
                  BvhBuild build) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const Accel& accel = build == BvhBuild::sah ? w->accel_sah : w->accel;
    const std::vector<Ray>& rays = rays_of(*w, set);
    const bool any_hit = set == "shadow";
    const RaySoa& soa = soa_of(*w, set);
    run(state, rays, threads, [&](size_t first, size_t last) {
        for (size_t i = first; i < last; i += W) {
            vmask<W> active;
            const RayPacket<W> p = load_packet<W>(soa, i, active);
            if (none(active)) continue;  // a shadow packet whose primary rays all missed
            if (any_hit) {
                benchmark::DoNotOptimize(intersect_any(w->scene, accel, p, active));
            } else {
                HitPacket<W> h = intersect_closest(w->scene, accel, p, active);
                benchmark::DoNotOptimize(h);
            }
        }
    });
}

/// Blocks of max_block_rays consecutive rays (a 16x16 tile for the primary rays).
template <int W>
void bench_block(benchmark::State& state, std::string scene, std::string set, int threads,
                 BvhBuild build) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const Accel& accel = build == BvhBuild::sah ? w->accel_sah : w->accel;
    const std::vector<Ray>& rays = rays_of(*w, set);
    const bool any_hit = set == "shadow";
    static_assert(chunk % max_block_rays == 0);
    const RaySoa& soa = soa_of(*w, set);
    run(state, rays, threads, [&](size_t first, size_t last) {
        constexpr int per_block = max_block_rays / W;
        RayPacket<W> p[per_block];
        vmask<W> active[per_block], occluded[per_block];
        HitPacket<W> hits[per_block];
        for (size_t b = first; b < last; b += max_block_rays) {  // chunks hold whole blocks
            int count = 0;
            for (size_t i = b; i < b + max_block_rays; i += W, ++count)
                p[count] = load_packet<W>(soa, i, active[count]);
            if (any_hit) {
                intersect_any_block(w->scene, accel, p, active, occluded, count);
                benchmark::DoNotOptimize(occluded[0]);
            } else {
                intersect_closest_block(w->scene, accel, p, active, hits, count);
                benchmark::DoNotOptimize(hits[0]);
            }
        }
    });
}

/// Streams of stream_rays consecutive rays through intersect_closest_stream /
/// intersect_any_stream.
template <int W>
void bench_stream(benchmark::State& state, std::string scene, std::string set, int threads) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const std::vector<Ray>& rays = rays_of(*w, set);
    const RaySoa& soa = soa_of(*w, set);
    const bool any_hit = set == "shadow";
    run(
        state, rays, threads,
        [&](size_t first, size_t last) {
            thread_local std::vector<RayPacket<W>> p;
            thread_local std::vector<vmask<W>> active, occluded;
            thread_local std::vector<HitPacket<W>> hits;
            const size_t count = (last - first) / W;
            p.resize(count), active.resize(count), occluded.resize(count), hits.resize(count);
            for (size_t k = 0; k < count; ++k) p[k] = load_packet<W>(soa, first + k * W, active[k]);
            if (any_hit) {
                intersect_any_stream(w->scene, w->accel, p.data(), active.data(), occluded.data(),
                                     int(count));
                benchmark::DoNotOptimize(occluded[0]);
            } else {
                intersect_closest_stream(w->scene, w->accel, p.data(), active.data(), hits.data(),
                                         int(count));
                benchmark::DoNotOptimize(hits[0]);
            }
        },
        stream_rays);
}

#ifdef RAYLANE_HAVE_EMBREE
void bench_embree1(benchmark::State& state, std::string scene, std::string set, int threads) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const std::vector<Ray>& rays = rays_of(*w, set);
    const bool any_hit = set == "shadow";
    run(state, rays, threads, [&](size_t first, size_t last) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        unsigned sum = 0;
        for (size_t i = first; i < std::min(last, rays.size()); ++i) {
            const Ray& r = rays[i];
            if (!active_ray(r)) continue;
            RTCRayHit rh{};
            rh.ray = {r.org.x, r.org.y, r.org.z, r.t_min, r.dir.x, r.dir.y,
                      r.dir.z, 0.0f,    r.t_max, ~0u,     0u,      0u};
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            if (any_hit) {
                rtcOccluded1(w->rtc_scene, &ctx, &rh.ray);
                sum += rh.ray.tfar < 0.0f;
            } else {
                rtcIntersect1(w->rtc_scene, &ctx, &rh);
                sum += rh.hit.primID;
            }
        }
        benchmark::DoNotOptimize(sum);
    });
}

void bench_embree16(benchmark::State& state, std::string scene, std::string set, int threads,
                    bool stream) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const std::vector<Ray>& rays = rays_of(*w, set);
    const bool any_hit = set == "shadow";
    run(state, rays, threads, [&](size_t first, size_t last) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        // coherent: camera rays, and shadow rays in 4x4-pixel packets per light
        if (set != "bounce") ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        if (stream) {
            alignas(64) RTCRayHit rh[chunk];
            const size_t n = std::min(last, rays.size()) - first;
            for (size_t k = 0; k < n; ++k) {
                const Ray& r = rays[first + k];
                rh[k].ray = {r.org.x, r.org.y, r.org.z, r.t_min, r.dir.x, r.dir.y,
                             r.dir.z, 0.0f,    r.t_max, ~0u,     0u,      0u};
                rh[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect1M(w->rtc_scene, &ctx, rh, unsigned(n), sizeof(RTCRayHit));
            benchmark::DoNotOptimize(rh[0].hit.primID);
            return;
        }
        const RaySoa& soa = soa_of(*w, set);
        for (size_t i = first; i < last; i += 16) {
            alignas(64) RTCRayHit16 rh;
            alignas(64) int valid[16];
            std::memcpy(rh.ray.org_x, soa.at(0, i), sizeof rh.ray.org_x);
            std::memcpy(rh.ray.org_y, soa.at(1, i), sizeof rh.ray.org_y);
            std::memcpy(rh.ray.org_z, soa.at(2, i), sizeof rh.ray.org_z);
            std::memcpy(rh.ray.dir_x, soa.at(3, i), sizeof rh.ray.dir_x);
            std::memcpy(rh.ray.dir_y, soa.at(4, i), sizeof rh.ray.dir_y);
            std::memcpy(rh.ray.dir_z, soa.at(5, i), sizeof rh.ray.dir_z);
            std::memcpy(rh.ray.tnear, soa.at(6, i), sizeof rh.ray.tnear);
            std::memcpy(rh.ray.tfar, soa.at(7, i), sizeof rh.ray.tfar);
            bool any_valid = false;
            for (int k = 0; k < 16; ++k) {
                valid[k] = rh.ray.tfar[k] >= rh.ray.tnear[k] ? -1 : 0;
                any_valid = any_valid || valid[k] != 0;
                rh.ray.time[k] = 0.0f, rh.ray.mask[k] = ~0u, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
                rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            }
            if (!any_valid) continue;  // a shadow packet whose primary rays all missed
            if (any_hit)
                rtcOccluded16(valid, w->rtc_scene, &ctx, &rh.ray);
            else
                rtcIntersect16(valid, w->rtc_scene, &ctx, &rh);
            benchmark::DoNotOptimize(rh.hit.primID[0]);
        }
    });
}
#endif

/// Packet<W>, or Packet<W>Sah through the binned SAH build.
template <int W>
void register_packet(const std::string& scene, const std::string& set, int threads,
                     BvhBuild build = BvhBuild::median) {
    const std::string suffix = (build == BvhBuild::sah ? "Sah/" : "/") + scene + "/" + set +
                               "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(("BM_Intersect_Packet" + std::to_string(W) + suffix).c_str(),
                                 bench_packet<W>, scene, set, threads, build)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

/// Block<W>, or Block<W>Sah through the binned SAH build.
template <int W>
void register_block(const std::string& scene, const std::string& set, int threads,
                    BvhBuild build = BvhBuild::median) {
    const std::string suffix = (build == BvhBuild::sah ? "Sah/" : "/") + scene + "/" + set +
                               "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(("BM_Intersect_Block" + std::to_string(W) + suffix).c_str(),
                                 bench_block<W>, scene, set, threads, build)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

/// Stream<W>: intersect_closest_stream, or intersect_any_stream for shadow rays, on stream_rays
/// rays at a time (one task each: 15 tasks for the dragon's bounce rays, 2 threads).
template <int W>
void register_stream(const std::string& scene, const std::string& set, int threads) {
    const std::string suffix = "/" + scene + "/" + set + "/threads:" + std::to_string(threads);
    benchmark::RegisterBenchmark(("BM_Intersect_Stream" + std::to_string(W) + suffix).c_str(),
                                 bench_stream<W>, scene, set, threads)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

void register_all() {
    for (std::string scene : {"dragon", "bunny"}) {
        for (std::string set : {"primary", "shadow", "bounce"}) {
            for (int threads : {1, 2}) {
                const std::string suffix =
                    "/" + scene + "/" + set + "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(("BM_Intersect_Scalar" + suffix).c_str(), bench_scalar,
                                             scene, set, threads)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
                register_packet<1>(scene, set, threads);
                if constexpr (width_supported<4>) register_packet<4>(scene, set, threads);
                if constexpr (width_supported<8>) register_packet<8>(scene, set, threads);
                if constexpr (width_supported<16>) register_packet<16>(scene, set, threads);
                if constexpr (width_supported<8>) register_block<8>(scene, set, threads);
                if constexpr (width_supported<16>) register_block<16>(scene, set, threads);
                // streams at the widest width
                if constexpr (width_supported<16>)
                    register_stream<16>(scene, set, threads);
                else if constexpr (width_supported<8>)
                    register_stream<8>(scene, set, threads);
                // the widest packets and blocks again through the SAH build (a comparison
                // option: the rays are the same, the tree is not the report's)
                if constexpr (width_supported<16>) {
                    register_packet<16>(scene, set, threads, BvhBuild::sah);
                    register_block<16>(scene, set, threads, BvhBuild::sah);
                } else if constexpr (width_supported<8>) {
                    register_packet<8>(scene, set, threads, BvhBuild::sah);
                    register_block<8>(scene, set, threads, BvhBuild::sah);
                }
#ifdef RAYLANE_HAVE_EMBREE
                benchmark::RegisterBenchmark(("BM_Intersect_Embree1" + suffix).c_str(),
                                             bench_embree1, scene, set, threads)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
                benchmark::RegisterBenchmark(("BM_Intersect_Embree16" + suffix).c_str(),
                                             bench_embree16, scene, set, threads, false)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
                if (set != "shadow")
                    benchmark::RegisterBenchmark(("BM_Intersect_Embree1M" + suffix).c_str(),
                                                 bench_embree16, scene, set, threads, true)
                        ->Unit(benchmark::kMillisecond)
                        ->UseRealTime();
#endif
            }
        }
    }
}

/// `--summary`: Mrays/s (median of the repetitions) of every contender per model, ray kind and
/// thread count, as a Markdown table, and the ratios the targets are set on: the best Raylane
/// packet contender (Packet4/8/16, Block8/16, Stream8/16: the median-split tree) over the scalar
/// path and over Embree's best API; the SAH contenders over Embree's best. The target against
/// Embree is judged only when every Embree API of that ray kind was run.
void print_summary(const bench::Measured& m, std::ostream& out) {
    const char* contenders[] = {"Scalar",      "Packet4",    "Packet8",  "Packet16",   "Block8",
                                "Block16",     "Stream8",    "Stream16", "Packet8Sah", "Block8Sah",
                                "Packet16Sah", "Block16Sah", "Embree1",  "Embree16",   "Embree1M"};
    const char* kinds[3] = {"primary", "shadow", "bounce"};
    const double over_embree[3] = {1.6, 1.2, 1.3};  // targets, by kind
    const double over_scalar[3] = {4.0, 0.0, 1.0};  // (none for shadow rays)
    auto rate = [&](const char* c, const char* model, const char* kind, int threads) {
        const std::optional<double> r =
            m.median_counter(std::string("BM_Intersect_") + c + "/" + model + "/" + kind +
                                 "/threads:" + std::to_string(threads) + "/real_time",
                             "rays/s");
        return r ? std::optional<double>(*r * 1e-6) : std::nullopt;
    };
    out << "Mrays/s, median of the repetitions; packet = the best of Packet4/8/16, Block8/16 and "
           "Stream8/16\n";
    for (const char* model : {"dragon", "bunny"}) {
        std::vector<const char*> shown;
        for (const char* c : contenders) {
            bool ran = false;
            for (const char* kind : kinds)
                for (int threads : {1, 2}) ran = ran || rate(c, model, kind, threads);
            if (ran) shown.push_back(c);
        }
        if (shown.empty()) continue;
        out << "\n| " << model << " |";
        for (const char* c : shown) out << " " << c << " |";
        out << " packet / scalar | packet / Embree's best | SAH / Embree's best | targets |\n|---|";
        for (size_t i = 0; i < shown.size() + 4; ++i) out << "---:|";
        out << "\n";
        for (int k = 0; k < 3; ++k) {
            for (int threads : {1, 2}) {
                auto r = [&](const char* c) { return rate(c, model, kinds[k], threads); };
                bool ran = false;
                for (const char* c : shown) ran = ran || r(c);
                if (!ran) continue;
                out << "| " << kinds[k] << ", " << threads
                    << (threads == 1 ? " thread" : " threads") << " |";
                for (const char* c : shown) {
                    const std::optional<double> v = r(c);
                    out << " " << bench::figure_text(v, v && *v >= 100.0 ? "%.0f" : "%.3g") << " |";
                }
                const auto packet =
                    bench::best_of({r("Packet4"), r("Packet8"), r("Packet16"), r("Block8"),
                                    r("Block16"), r("Stream8"), r("Stream16")});
                const auto sah = bench::best_of(
                    {r("Packet8Sah"), r("Block8Sah"), r("Packet16Sah"), r("Block16Sah")});
                const bool every_embree =
                    r("Embree1") && r("Embree16") && (k == 1 || r("Embree1M"));  // no 1M shadow
                const auto embree = bench::best_of({r("Embree1"), r("Embree16"), r("Embree1M")});
                out << " " << bench::ratio_text(packet, r("Scalar")) << " | "
                    << bench::ratio_text(packet, embree) << " | " << bench::ratio_text(sah, embree)
                    << " | " << bench::figure_text(over_embree[k], "%.1fx") << " Embree's best: "
                    << bench::verdict(every_embree ? bench::divide(packet, embree) : std::nullopt,
                                      over_embree[k]);
                if (over_scalar[k] > 0.0)
                    out << "; " << bench::figure_text(over_scalar[k], "%.0fx") << " scalar: "
                        << bench::verdict(bench::divide(packet, r("Scalar")), over_scalar[k]);
                out << " |\n";
            }
        }
    }
    out << "\nTargets (each row's last column says whether the row meets them):\n";
    for (int k = 0; k < 3; ++k) {
        out << "- " << kinds[k]
            << " rays: packet / Embree's best >= " << bench::figure_text(over_embree[k], "%.1fx")
            << "\n";
        if (over_scalar[k] > 0.0)
            out << "- " << kinds[k]
                << " rays: packet / scalar >= " << bench::figure_text(over_scalar[k], "%.0fx")
                << "\n";
    }
    out << "\nThe packet figure is the best of the packet contenders that ran.\n";
}

}  // namespace
}  // namespace raylane

int main(int argc, char** argv) {
    // --rays FILE.npy [--mesh MODEL] [--embree-hits OUT.npy], taken out of argv
    std::string rays, mesh = "dragon.ply", embree_hits;
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        std::string* value = a == "--rays"          ? &rays
                             : a == "--mesh"        ? &mesh
                             : a == "--embree-hits" ? &embree_hits
                                                    : nullptr;
        if (!value) {
            argv[kept++] = argv[i];
            continue;
        }
        if (i + 1 == argc) {
            std::fprintf(stderr, "%s: %s needs a value\n", argv[0], a.c_str());
            return 2;
        }
        *value = argv[++i];
    }
    argc = kept;
    argv[argc] = nullptr;
    if (rays.empty()) {
        raylane::register_all();
        return raylane::bench::run_benchmarks(argc, argv, raylane::print_summary);
    }
    try {
        raylane::bench::load_ray_file_workload(rays, mesh);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 2;
    }
    if (!embree_hits.empty()) {
        if (raylane::bench::write_embree_hits(embree_hits)) return 0;
        std::fprintf(stderr, "%s: --embree-hits: built without Embree\n", argv[0]);
        return 2;
    }
    raylane::bench::register_ray_file();
    return raylane::bench::run_benchmarks(argc, argv, raylane::bench::print_ray_file_summary);
}
