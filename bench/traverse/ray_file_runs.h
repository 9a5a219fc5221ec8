// bench: `bench_intersect --rays FILE.npy [--mesh MODEL]`: a user's rays (an (N, 6) float32
// .npy file) against one mesh, through every contender in one run: Raylane's scalar path and,
// on every instruction set raced (support/isa_sets.h), its packet path (query/intersect_batch.h,
// the code behind the Python module's Mesh.intersect: Packet picks blocks or streams per 256
// rays, Block and Stream force one) and Embree 3 restricted to the same set (rtcIntersect1 / 16 /
// 1M, rtcOccluded1 / 16 / 1M) when it is installed; every contender writes
// the answers the Python module returns (t, primitive, u, v, unit normal; occluded flags). Closest
// hits and any-hit queries (t_max = inf), on 1 thread and on all. The mesh is the model file as it
// is (load_mesh, as raylane.load_mesh reads it), not a scene's placement of it.
#pragma once

#include <benchmark/benchmark.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/load_mesh.h"
#include "io/model_path.h"
#include "query/intersect_batch.h"
#include "support/isa_sets.h"
#include "support/ray_file.h"
#include "support/summary.h"

#ifdef RAYLANE_HAVE_EMBREE
#include "traverse/embree_scene.h"
#endif

namespace raylane::bench {

struct RayFileWorkload {
    std::string rays_path, mesh_path;
    std::vector<float> rays;  ///< 6 floats per ray
    size_t count = 0;
    SceneData scene;  ///< the mesh as one object
    Accel accel;
    TriangleNormals normals;
#ifdef RAYLANE_HAVE_EMBREE
    std::map<Isa, RTCScene> rtc_scenes;  ///< the mesh in Embree, per set (embree_scene)
#endif
    RayArrays arrays() const {
        RayArrays a;
        a.org = rays.data(), a.dir = rays.data() + 3;
        a.org_stride = a.dir_stride = 6;
        a.count = count;
        return a;
    }
};

inline RayFileWorkload& ray_file_workload() {
    static RayFileWorkload w;
    return w;
}

/// Reads the rays and the model and builds the BVH; throws on bad input.
inline void load_ray_file_workload(const std::string& rays_path, const std::string& model) {
    RayFileWorkload& w = ray_file_workload();
    w.rays_path = rays_path;
    w.rays = read_ray_file(rays_path);
    w.count = w.rays.size() / 6;
    w.mesh_path = find_model(model, ".");
    MeshData mesh = load_mesh(w.mesh_path);
    w.scene.materials.push_back(Material{});
    if (!mesh.tris.empty()) {
        Object object;
        object.kind = ShapeKind::mesh;
        w.scene.objects.push_back(object);
    }
    w.scene.meshes.push_back(std::move(mesh));
    w.accel = build_accel(w.scene, BuildParams{});
    w.normals = make_triangle_normals(w.scene);
}

#ifdef RAYLANE_HAVE_EMBREE
/// The mesh in Embree on the set's device, built on first use.
inline RTCScene embree_scene(Isa isa) {
    RayFileWorkload& w = ray_file_workload();
    RTCScene& scene = w.rtc_scenes[isa];
    if (!scene) scene = make_embree_scene(isa, w.scene.meshes);
    return scene;
}
#endif

/// Counts rays per second over `threads` threads; body(first, last) traces a range of rays
/// (tasks of 256 rays) or, with whole = true, body(0, count) is called once per iteration.
template <class Body>
void run_ray_file(benchmark::State& state, int threads, bool whole, Body&& body) {
    const size_t n = ray_file_workload().count;
    tbb::task_arena arena(threads);
    for (auto _ : state) {
        if (whole) {
            body(size_t(0), n);
            continue;
        }
        arena.execute([&] {
            tbb::parallel_for(size_t(0), (n + 255) / 256,
                              [&](size_t c) { body(c * 256, std::min(n, (c + 1) * 256)); });
        });
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(n));
    state.counters["rays/s"] =
        benchmark::Counter(double(n) * double(state.iterations()), benchmark::Counter::kIsRate);
}

/// Scalar, Packet, Block and Stream: intersect_closest_batch / intersect_any_batch on the
/// whole file (they spread the rays over the threads themselves) with the set `isa` in use,
/// writing the arrays that MeshData.intersect and MeshData.occluded return.
inline void bench_ray_file_batch(benchmark::State& state, Isa isa, bool any_hit,
                                 BatchParams params) {
    use_isa(isa);
    const RayFileWorkload& w = ray_file_workload();
    const size_t n = w.count;
    std::vector<float> t(n), u(n), v(n), normal(3 * n);
    std::vector<int32_t> prim(n);
    std::vector<uint8_t> occluded(n);
    const HitBuffers hits{t.data(), prim.data(), nullptr, u.data(), v.data(), normal.data()};
    run_ray_file(state, params.threads, true, [&](size_t, size_t) {
        if (any_hit)
            intersect_any_batch(w.scene, w.accel, w.arrays(), occluded.data(), params);
        else
            intersect_closest_batch(w.scene, w.accel, w.arrays(), hits, params, &w.normals);
        benchmark::DoNotOptimize(prim.data());
        benchmark::DoNotOptimize(occluded.data());
    });
}

#ifdef RAYLANE_HAVE_EMBREE
inline RTCRayHit embree_ray(const float* r) {
    RTCRayHit rh{};
    rh.ray = {r[0], r[1], r[2], 0.0f, r[3], r[4], r[5], 0.0f, infinity, ~0u, 0u, 0u};
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

/// The arrays every contender writes, as MeshData.intersect and MeshData.occluded return them: t
/// (inf on a miss), primitive (-1), u, v, unit geometric normal (0 on a miss); occluded.
struct RayFileOutputs {
    std::vector<float> t, u, v, normal;
    std::vector<int32_t> prim;
    std::vector<uint8_t> occluded;
    explicit RayFileOutputs(size_t n) : t(n), u(n), v(n), normal(3 * n), prim(n), occluded(n) {}
    /// Ray i's answer from Embree's hit (Ng is Embree's unnormalised geometric normal).
    void set(size_t i, bool hit, float t_hit, unsigned id, float u_hit, float v_hit, float nx,
             float ny, float nz) {
        t[i] = hit ? t_hit : infinity;
        prim[i] = hit ? int32_t(id) : -1;
        u[i] = hit ? u_hit : 0.0f, v[i] = hit ? v_hit : 0.0f;
        const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
        const float s = hit && len > 0.0f ? 1.0f / len : 0.0f;
        normal[3 * i] = nx * s, normal[3 * i + 1] = ny * s, normal[3 * i + 2] = nz * s;
    }
};

/// Embree1 (one ray at a time), Embree16 (packets of 16 consecutive rays, `coherent` context
/// flag or not) and Embree1M (streams of 256 rays). Each writes the answers MeshData.intersect and
/// MeshData.occluded return (RayFileOutputs), as the Raylane contenders do.
inline void bench_ray_file_embree(benchmark::State& state, Isa isa, bool any_hit, int api,
                                  bool coherent, int threads) {
    const RayFileWorkload& w = ray_file_workload();
    const RTCScene rtc_scene = embree_scene(isa);
    RayFileOutputs out(w.count);
    run_ray_file(state, threads, false, [&](size_t first, size_t last) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags =
            coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
        if (api == 1) {
            for (size_t i = first; i < last; ++i) {
                RTCRayHit rh = embree_ray(&w.rays[6 * i]);
                if (any_hit) {
                    rtcOccluded1(rtc_scene, &ctx, &rh.ray);
                    out.occluded[i] = rh.ray.tfar < 0.0f;
                } else {
                    rtcIntersect1(rtc_scene, &ctx, &rh);
                    out.set(i, rh.hit.geomID != RTC_INVALID_GEOMETRY_ID, rh.ray.tfar, rh.hit.primID,
                            rh.hit.u, rh.hit.v, rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
                }
            }
        } else if (api == 16) {
            for (size_t i = first; i < last; i += 16) {
                alignas(64) RTCRayHit16 rh;
                alignas(64) int valid[16];
                for (int k = 0; k < 16; ++k) {
                    const bool on = i + size_t(k) < last;
                    const float* r = &w.rays[6 * (on ? i + size_t(k) : first)];
                    valid[k] = on ? -1 : 0;
                    rh.ray.org_x[k] = r[0], rh.ray.org_y[k] = r[1], rh.ray.org_z[k] = r[2];
                    rh.ray.dir_x[k] = r[3], rh.ray.dir_y[k] = r[4], rh.ray.dir_z[k] = r[5];
                    rh.ray.tnear[k] = 0.0f, rh.ray.tfar[k] = infinity, rh.ray.time[k] = 0.0f;
                    rh.ray.mask[k] = ~0u, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                }
                if (any_hit)
                    rtcOccluded16(valid, rtc_scene, &ctx, &rh.ray);
                else
                    rtcIntersect16(valid, rtc_scene, &ctx, &rh);
                for (size_t k = 0; k < 16 && i + k < last; ++k) {
                    if (any_hit) {
                        out.occluded[i + k] = rh.ray.tfar[k] < 0.0f;
                    } else {
                        out.set(i + k, rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID, rh.ray.tfar[k],
                                rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k], rh.hit.Ng_x[k],
                                rh.hit.Ng_y[k], rh.hit.Ng_z[k]);
                    }
                }
            }
        } else {
            alignas(64) RTCRayHit rh[256];
            const size_t n = last - first;
            for (size_t k = 0; k < n; ++k) rh[k] = embree_ray(&w.rays[6 * (first + k)]);
            if (any_hit) {
                alignas(64) RTCRay r[256];
                for (size_t k = 0; k < n; ++k) r[k] = rh[k].ray;
                rtcOccluded1M(rtc_scene, &ctx, r, unsigned(n), sizeof(RTCRay));
                for (size_t k = 0; k < n; ++k) out.occluded[first + k] = r[k].tfar < 0.0f;
            } else {
                rtcIntersect1M(rtc_scene, &ctx, rh, unsigned(n), sizeof(RTCRayHit));
                for (size_t k = 0; k < n; ++k)
                    out.set(first + k, rh[k].hit.geomID != RTC_INVALID_GEOMETRY_ID, rh[k].ray.tfar,
                            rh[k].hit.primID, rh[k].hit.u, rh[k].hit.v, rh[k].hit.Ng_x,
                            rh[k].hit.Ng_y, rh[k].hit.Ng_z);
            }
        }
    });
    benchmark::DoNotOptimize(out.prim.data());
    benchmark::DoNotOptimize(out.occluded.data());
}
#endif

/// `--embree-hits OUT.npy`: Embree's closest hit of every ray (rtcIntersect1, on the set in
/// use), as an (N, 4) float64 array of t (inf on a miss), primitive id (-1 on a miss) and
/// barycentrics u, v, for checks against Raylane's. Returns false when Embree is not built in.
inline bool write_embree_hits(const std::string& path) {
#ifdef RAYLANE_HAVE_EMBREE
    const RayFileWorkload& w = ray_file_workload();
    const RTCScene rtc_scene = embree_scene(isa_in_use());
    std::vector<double> out(4 * w.count);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (size_t i = 0; i < w.count; ++i) {
        RTCRayHit rh = embree_ray(&w.rays[6 * i]);
        rtcIntersect1(rtc_scene, &ctx, &rh);
        const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        out[4 * i] = hit ? double(rh.ray.tfar) : double(infinity);
        out[4 * i + 1] = hit ? double(rh.hit.primID) : -1.0;
        out[4 * i + 2] = hit ? double(rh.hit.u) : 0.0;
        out[4 * i + 3] = hit ? double(rh.hit.v) : 0.0;
    }
    write_npy(path, out, 4);
    return true;
#else
    (void)path;
    return false;
#endif
}

/// BM_RayFile_Build: what raylane.Mesh builds from its arrays (build_accel of the one-object
/// scene and the triangles' normals), from the loaded mesh, on the set in use.
inline void bench_ray_file_build(benchmark::State& state) {
    use_isa(isa_in_use());
    const RayFileWorkload& w = ray_file_workload();
    for (auto _ : state) {
        Accel accel = build_accel(w.scene, BuildParams{});
        TriangleNormals normals = make_triangle_normals(w.scene);
        benchmark::DoNotOptimize(accel.meshes.data());
        benchmark::DoNotOptimize(normals.meshes.data());
    }
}

/// The name of a contender on a set: "Packet_avx2", "Embree16_avx2".
inline std::string ray_file_name(const char* contender, Isa isa) {
    return std::string(contender) + "_" + isa_name(isa);
}

/// BM_RayFile_Closest_Scalar/threads:1 (on the set in use), BM_RayFile_Closest_Packet_avx2/
/// threads:1 and BM_RayFile_Closest_Embree16_avx2/threads:1 (per set raced), ...
inline void register_ray_file() {
    benchmark::RegisterBenchmark("BM_RayFile_Build", bench_ray_file_build)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    std::vector<int> thread_counts = {1};
    if (tbb::info::default_concurrency() > 1)
        thread_counts.push_back(tbb::info::default_concurrency());
    for (bool any_hit : {false, true}) {
        const std::string query = any_hit ? "BM_RayFile_Occluded_" : "BM_RayFile_Closest_";
        for (int threads : thread_counts) {
            const std::string suffix = "/threads:" + std::to_string(threads);
            auto add = [&](const std::string& name, auto&&... args) {
                benchmark::RegisterBenchmark((query + name + suffix).c_str(), args...)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
            };
            auto batch = [&](BatchPath path, Coherence coherence) {
                return BatchParams{path, coherence, threads};
            };
            add("Scalar", bench_ray_file_batch, isa_in_use(), any_hit,
                batch(BatchPath::scalar, Coherence::automatic));
            for (Isa isa : raced_isas()) {
                add(ray_file_name("Packet", isa), bench_ray_file_batch, isa, any_hit,
                    batch(BatchPath::packet, Coherence::automatic));
                add(ray_file_name("Block", isa), bench_ray_file_batch, isa, any_hit,
                    batch(BatchPath::packet, Coherence::coherent));
                add(ray_file_name("Stream", isa), bench_ray_file_batch, isa, any_hit,
                    batch(BatchPath::packet, Coherence::incoherent));
#ifdef RAYLANE_HAVE_EMBREE
                add(ray_file_name("Embree1", isa), bench_ray_file_embree, isa, any_hit, 1, false,
                    threads);
                add(ray_file_name("Embree16", isa), bench_ray_file_embree, isa, any_hit, 16, false,
                    threads);
                add(ray_file_name("Embree16Coherent", isa), bench_ray_file_embree, isa, any_hit, 16,
                    true, threads);
                add(ray_file_name("Embree1M", isa), bench_ray_file_embree, isa, any_hit, 256, false,
                    threads);
#endif
            }
        }
    }
}

/// `--summary` of a ray file: Mrays/s (median of the repetitions) per contender, query and
/// thread count, one table per instruction set (Scalar, the same in each), and the packet path
/// over Embree's best on the same set.
inline void print_ray_file_summary(const Measured& m, std::ostream& out) {
    const RayFileWorkload& w = ray_file_workload();
    const char* contenders[] = {"Scalar",  "Packet",   "Block",    "Stream",
                                "Embree1", "Embree16", "Embree1M", "Embree16Coherent"};
    out << "Mrays/s, median of the repetitions: " << w.count << " rays of " << w.rays_path << " at "
        << w.mesh_path << " (" << w.scene.meshes[0].tris.size()
        << " triangles); one table per instruction set, Embree restricted to the same set\n";
    for (Isa isa : raced_isas()) {
        auto rate = [&](const char* query, const char* c, int threads) {
            const std::string name = std::string(c) == "Scalar" ? c : ray_file_name(c, isa);
            const std::optional<double> r =
                m.median_counter(std::string("BM_RayFile_") + query + "_" + name +
                                     "/threads:" + std::to_string(threads) + "/real_time",
                                 "rays/s");
            return r ? std::optional<double>(*r * 1e-6) : std::nullopt;
        };
        bool table = false;
        for (const char* query : {"Closest", "Occluded"}) {
            for (int threads = 1; threads <= tbb::info::default_concurrency(); ++threads) {
                auto r = [&](const char* c) { return rate(query, c, threads); };
                bool ran = false;  // any of this set's contenders (all but Scalar)
                for (size_t i = 1; i < std::size(contenders); ++i) ran = ran || r(contenders[i]);
                if (!ran) continue;
                if (!table) {
                    out << "\n| " << isa_label(isa) << " |";
                    for (const char* c : contenders) out << " " << c << " |";
                    out << " Packet / Embree's best |\n|---|";
                    for (size_t i = 0; i < std::size(contenders) + 1; ++i) out << "---:|";
                    out << "\n";
                    table = true;
                }
                out << "| " << query << ", " << threads << (threads == 1 ? " thread" : " threads")
                    << " |";
                for (const char* c : contenders) out << " " << figure_text(r(c), "%.3g") << " |";
                const auto embree =
                    best_of({r("Embree1"), r("Embree16"), r("Embree1M"), r("Embree16Coherent")});
                out << " " << ratio_text(r("Packet"), embree) << " |\n";
            }
        }
    }
    print_isas_not_raced(out);
    out << "\nBVH build (BM_RayFile_Build): "
        << figure_text(m.median_ms("BM_RayFile_Build/real_time"), "%.1f ms") << ", on "
        << isa_name(isa_in_use()) << "\n";
}

}  // namespace raylane::bench
