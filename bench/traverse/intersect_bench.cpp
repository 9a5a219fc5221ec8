// Benchmarks of traverse/: the same rays through every contender, rays per second.
// Scenes: the meshes of scenes/dragon.json and scenes/bunny.json (the mesh alone, so every
// contender traces the same triangles). Ray sets: primary rays at 1920x1080 (1 sample at pixel
// centres, in 16x16 tiles of 4x4 blocks), shadow rays from the primary hits to the scene's
// lights in the renderer's order (per tile and light, one packet per 4x4 pixels, inactive slots
// where the primary ray missed or the point faces away from the light), and one
// cosine-distributed bounce ray per hit (incoherent).
// Contenders: Raylane scalar; for every instruction set raced (bench/support/isa_sets.h),
// Raylane's packet contenders at the set's width (intersect_bench_packet.cpp: Packet4, Block8,
// Stream16, ...) and Embree 3 restricted to the same set (rtcNewDevice "isa=avx2"; rtcIntersect1
// / 1M / 16, rtcOccluded1 / 16; Embree16_avx2, ...) when it is installed. 1 and 2 threads
// (oneTBB; chunks of 256 rays).
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

#include "core/float_modes.h"
#include "core/offset.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "support/isa_sets.h"
#include "support/summary.h"
#include "traverse/intersect_contenders.h"
#include "traverse/intersect_scalar.h"
#include "traverse/ray_file_runs.h"

#ifdef RAYLANE_HAVE_EMBREE
#include "traverse/embree_scene.h"
#include "traverse/surface_scalar.h"
#endif

// each set's packet contenders (intersect_bench_packet.cpp)
#define RAYLANE_DECLARE(ns)                                            \
    namespace raylane {                                                \
    inline namespace ns {                                              \
    std::vector<bench::PacketContender> intersect_packet_contenders(); \
    }                                                                  \
    }
RAYLANE_FOR_EACH_ISA(RAYLANE_DECLARE)
#undef RAYLANE_DECLARE

namespace raylane::bench {
namespace {

/// The packet contenders of a set, at its width.
std::vector<PacketContender> packet_contenders(Isa isa) {
    switch (isa) {
        RAYLANE_IF_SSE42(case Isa::sse42 : return isa_sse42::intersect_packet_contenders();)
        RAYLANE_IF_AVX2(case Isa::avx2 : return isa_avx2::intersect_packet_contenders();)
        RAYLANE_IF_AVX512(case Isa::avx512 : return isa_avx512::intersect_packet_contenders();)
        default:
            break;
    }
    return {};
}

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
    SceneData scene;
    Accel accel;      ///< the median split (the report's build; the rays' reference)
    Accel accel_sah;  ///< the binned SAH build, for the Sah contenders
    std::vector<Ray> primary, shadow, bounce;
    RaySoa primary_soa, shadow_soa, bounce_soa;
#ifdef RAYLANE_HAVE_EMBREE
    std::map<Isa, RTCScene> rtc_scenes;  ///< the meshes in Embree, per set (embree_scene)
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
/// The workload's meshes in Embree on the set's device, built on first use.
RTCScene embree_scene(Workload& w, Isa isa) {
    RTCScene& scene = w.rtc_scenes[isa];
    if (!scene) scene = make_embree_scene(isa, w.scene.meshes);
    return scene;
}
#endif

/// The mesh objects of a scene file with its camera at 1920x1080 and its lights, and the ray sets.
Workload* workload(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Workload>> cache;
    if (auto it = cache.find(name); it != cache.end()) return it->second.get();
    std::unique_ptr<Workload> w;
    try {
        SceneData full = load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
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
    static_assert(chunk % tile_rays == 0);
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
    return (cache[name] = std::move(w)).get();
}

const std::vector<Ray>& rays_of(const Workload& w, const std::string& set) {
    return set == "primary" ? w.primary : set == "shadow" ? w.shadow : w.bounce;
}
const RaySoa& soa_of(const Workload& w, const std::string& set) {
    return set == "primary" ? w.primary_soa : set == "shadow" ? w.shadow_soa : w.bounce_soa;
}

/// Whether a ray is a real one (a shadow packet's slots where the primary ray missed are not).
bool active_ray(const Ray& r) { return r.t_max >= r.t_min; }

/// Runs body(first, last) over the rays in tasks of `rays_per_task` on `threads` threads; counts
/// the real rays per second. Tasks cover the padded SoA arrays; the scalar and AoS contenders
/// stop at the last ray and skip inactive slots.
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

/// A set's packet contender (its code calls the set's functions directly).
void bench_packet(benchmark::State& state, PacketContender c, std::string scene, std::string set,
                  int threads) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const Accel& accel = c.build == BvhBuild::sah ? w->accel_sah : w->accel;
    const RaySoa& soa = soa_of(*w, set);
    const bool any_hit = set == "shadow";
    run(
        state, rays_of(*w, set), threads,
        [&](size_t first, size_t last) { c.trace(w->scene, accel, soa, any_hit, first, last); },
        c.rays_per_task);
}

#ifdef RAYLANE_HAVE_EMBREE
void bench_embree1(benchmark::State& state, Isa isa, std::string scene, std::string set,
                   int threads) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const RTCScene rtc_scene = embree_scene(*w, isa);
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
                rtcOccluded1(rtc_scene, &ctx, &rh.ray);
                sum += rh.ray.tfar < 0.0f;
            } else {
                rtcIntersect1(rtc_scene, &ctx, &rh);
                sum += rh.hit.primID;
            }
        }
        benchmark::DoNotOptimize(sum);
    });
}

/// Embree16 (rtcIntersect16 / rtcOccluded16), or with `stream` Embree1M (rtcIntersect1M).
void bench_embree16(benchmark::State& state, Isa isa, bool stream, std::string scene,
                    std::string set, int threads) {
    Workload* w = workload(scene);
    if (!w) return state.SkipWithError("scene or model not found");
    const RTCScene rtc_scene = embree_scene(*w, isa);
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
            rtcIntersect1M(rtc_scene, &ctx, rh, unsigned(n), sizeof(RTCRayHit));
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
                rtcOccluded16(valid, rtc_scene, &ctx, &rh.ray);
            else
                rtcIntersect16(valid, rtc_scene, &ctx, &rh);
            benchmark::DoNotOptimize(rh.hit.primID[0]);
        }
    });
}
#endif

/// The name of an Embree contender on a set: "Embree16_avx2".
std::string embree_name(const char* api, Isa isa) {
    return std::string("Embree") + api + "_" + isa_name(isa);
}

void register_all() {
    for (std::string scene : {"dragon", "bunny"}) {
        for (std::string set : {"primary", "shadow", "bounce"}) {
            for (int threads : {1, 2}) {
                const std::string suffix =
                    "/" + scene + "/" + set + "/threads:" + std::to_string(threads);
                auto add = [&](const std::string& contender, auto&&... args) {
                    benchmark::RegisterBenchmark(("BM_Intersect_" + contender + suffix).c_str(),
                                                 args..., scene, set, threads)
                        ->Unit(benchmark::kMillisecond)
                        ->UseRealTime();
                };
                add("Scalar", bench_scalar);
                for (Isa isa : raced_isas()) {
                    for (const PacketContender& c : packet_contenders(isa))
                        add(c.name, bench_packet, c);
#ifdef RAYLANE_HAVE_EMBREE
                    add(embree_name("1", isa), bench_embree1, isa);
                    add(embree_name("16", isa), bench_embree16, isa, false);
                    if (set != "shadow") add(embree_name("1M", isa), bench_embree16, isa, true);
#endif
                }
            }
        }
    }
}

/// `--summary`: Mrays/s (median of the repetitions) of every contender, one table per model and
/// instruction set, by ray kind and thread count, and the ratios: the best of the set's packet
/// contenders (Packet<W>, Block<W>, Stream<W>: the median-split tree) over the scalar path and
/// over Embree's best API on the same set; the SAH contenders over Embree's best.
void print_summary(const Measured& m, std::ostream& out) {
    const char* kinds[3] = {"primary", "shadow", "bounce"};
    auto rate = [&](const std::string& c, const char* model, const char* kind, int threads) {
        const std::optional<double> r =
            m.median_counter("BM_Intersect_" + c + "/" + model + "/" + kind +
                                 "/threads:" + std::to_string(threads) + "/real_time",
                             "rays/s");
        return r ? std::optional<double>(*r * 1e-6) : std::nullopt;
    };
    out << "Mrays/s, median of the repetitions; one table per model and instruction set: packet "
           "= the best of Packet<W>, Block<W> and Stream<W> at the set's width W, SAH = the best "
           "of Packet<W>Sah and Block<W>Sah, Embree restricted to the same set "
           "(rtcNewDevice \"isa=<set>\")\n";
    for (const char* model : {"dragon", "bunny"}) {
        for (Isa isa : raced_isas()) {
            // the columns: Scalar, the set's contenders and Embree's APIs on the set, those run
            std::vector<std::string> names, packet_names, sah_names;
            for (const PacketContender& c : packet_contenders(isa)) {
                names.push_back(c.name);
                (c.build == BvhBuild::sah ? sah_names : packet_names).push_back(c.name);
            }
            const std::string embree1 = embree_name("1", isa), embree16 = embree_name("16", isa),
                              embree1m = embree_name("1M", isa);
            names.insert(names.end(), {embree1, embree16, embree1m});
            auto ran = [&](const std::string& c) {
                for (const char* kind : kinds)
                    for (int threads : {1, 2})
                        if (rate(c, model, kind, threads)) return true;
                return false;
            };
            std::vector<std::string> shown;
            for (const std::string& c : names)
                if (ran(c)) shown.push_back(c);
            if (shown.empty()) continue;  // none of this set's contenders ran on the model
            if (ran("Scalar")) shown.insert(shown.begin(), "Scalar");
            out << "\n| " << model << ", " << isa_label(isa) << " |";
            for (const std::string& c : shown) out << " " << c.substr(0, c.find('_')) << " |";
            out << " packet / scalar | packet / Embree's best | SAH / Embree's best |\n|---|";
            for (size_t i = 0; i < shown.size() + 3; ++i) out << "---:|";
            out << "\n";
            for (int k = 0; k < 3; ++k) {
                for (int threads : {1, 2}) {
                    auto r = [&](const std::string& c) {
                        return rate(c, model, kinds[k], threads);
                    };
                    auto best = [&](const std::vector<std::string>& cs) {
                        std::vector<std::optional<double>> rates;
                        for (const std::string& c : cs) rates.push_back(r(c));
                        return best_of(rates);
                    };
                    bool row_ran = false;
                    for (const std::string& c : shown) row_ran = row_ran || r(c);
                    if (!row_ran) continue;
                    out << "| " << kinds[k] << ", " << threads
                        << (threads == 1 ? " thread" : " threads") << " |";
                    for (const std::string& c : shown) {
                        const std::optional<double> v = r(c);
                        out << " " << figure_text(v, v && *v >= 100.0 ? "%.0f" : "%.3g") << " |";
                    }
                    const auto packet = best(packet_names), sah = best(sah_names);
                    const auto embree = best({embree1, embree16, embree1m});
                    out << " " << ratio_text(packet, r("Scalar")) << " | "
                        << ratio_text(packet, embree) << " | " << ratio_text(sah, embree) << " |\n";
                }
            }
        }
    }
    print_isas_not_raced(out);
    out << "\nThe packet figure is the best of the set's packet contenders that ran.\n";
}

}  // namespace
}  // namespace raylane::bench

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
    if (!raylane::bench::choose_isas(argv[0])) return 2;
    if (rays.empty()) {
        raylane::bench::register_all();
        return raylane::bench::run_benchmarks(argc, argv, raylane::bench::print_summary);
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
