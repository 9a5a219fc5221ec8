// render: the packet renderer's shading of a tile's samples (render_packet.cpp, the tile loop):
// the wavefront of scenes with secondary rays (shade_tile_samples: ray queues, passes, sort by
// material) and the one pass of the others (shade_camera_block). Templates on the packet width
// and the kernel's feature set, instantiated by the tile loop's kernels. No scalar twin: the
// scalar renderer recurses (shade_scalar.cpp).
#pragma once

#include <algorithm>
#include <cstring>
#include <memory>
#include <vector>

#include "core/rng.h"
#include "scene/features.h"
#include "shade/optics_scalar.h"
#include "shade/path_queue.h"
#include "shade/shade_io_packet.h"
#include "shade/shade_packet.h"
#include "simd/hash.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_stream.h"

namespace raylane::RAYLANE_ISA_NS {

/// Samples of a tile's pixels traced together in one wavefront: its camera rays go in camera
/// packet by camera packet (a packet's samples one after the other), so the secondary rays of a
/// packet come from a few neighbouring pixels rather than from sixteen, and stay together longer.
constexpr int max_wavefront_samples = 16;

/// Samples per wavefront times the rays a camera ray may spawn (an estimate, below): kept under
/// this, a wavefront's queues stay about as large as one sample's of a scene with a few shadow
/// rays per hit, which fit the cache.
constexpr int64_t wavefront_ray_budget = 96;

/// The samples per wavefront: up to max_wavefront_samples, fewer when hits spawn many rays (shadow
/// rays to every light sample, times the glossy rays and their own shadow rays). It depends on
/// the scene and the sample-count options only, never on threads or timing: the summation order
/// of a pixel's contributions, and so the image's last bits, depend on it.
inline int samples_per_wavefront(const SceneData& scene, const ShadeParams& params) {
    int64_t shadow = 0, glossy = 0;  // 64 bits: any number of lights of 4096 samples
    for (const Light& light : scene.lights)
        if (light.shadows) shadow += light_sample_count(light, params);
    for (const Material& m : scene.materials)
        if (m.model == SpecularModel::glossy_phong)
            glossy = std::max<int64_t>(glossy, glossy_sample_count(m, params));
    const int64_t rays = std::max<int64_t>(shadow, 1) * (1 + glossy);
    return static_cast<int>(
        std::clamp<int64_t>(wavefront_ray_budget / rays, 1, max_wavefront_samples));
}

/// A wavefront's slots (shade_io_packet.h, SlotMap): sample j of the wavefront at tile slot i is
/// slot j * max_block_rays + i.
constexpr int max_slots = max_wavefront_samples * max_block_rays;

/// A thread's buffers for shading tiles; grown on the first tiles, then reused.
struct TileBuffers {
    PathQueue paths, next, next_inside;
    HitArrays hits;
    std::vector<ShadowQueue> shadows;  ///< one per light
    std::vector<int32_t> order, material_count;
    int32_t pixel[max_block_rays];  ///< each tile slot's image pixel
    float acc_r[max_slots], acc_g[max_slots], acc_b[max_slots];
    /// The radiance of each path of a pass (index = its entry in `paths`), added to its slot
    /// after the pass in queue order.
    std::vector<float> path_r, path_g, path_b;
};

/// Packets for a whole queue (the stream traversals take every ray of a pass at once): a
/// thread's, grown on the first tiles, then reused.
template <int W>
struct QueuePackets {
    std::vector<RayPacket<W>> rays;
    std::vector<HitPacket<W>> hits;
    std::unique_ptr<vmask<W>[]> active, occluded;  // (vector<bool> at W = 1)
    size_t capacity = 0;
    void reserve(size_t packets) {
        if (packets <= capacity) return;
        rays.resize(packets), hits.resize(packets);
        active.reset(new vmask<W>[packets]);
        occluded.reset(new vmask<W>[packets]);
        capacity = packets;
    }
};
template <int W>
QueuePackets<W>& queue_packets() {
    thread_local QueuePackets<W> q;
    return q;
}

/// Packet p of a queue's first n rays from `base` on (t_min 0; inactive lanes past the end).
template <int W, class Queue>
RayPacket<W> queue_packet(const Queue& q, int base, int n, int p, const float* t_max,
                          vmask<W>& active) {
    const size_t i = static_cast<size_t>(base + p * W);
    const int lanes = std::min(W, n - p * W);
    active = mask_from_bits<W>(lanes >= 32 ? ~0u : (1u << lanes) - 1u);
    RayPacket<W> r;
    r.org = load_vec3<W>(&q.ox[i], &q.oy[i], &q.oz[i]);
    r.dir = load_vec3<W>(&q.dx[i], &q.dy[i], &q.dz[i]);
    r.t_min = vfloat<W>(0.0f);
    r.t_max = select(active, t_max ? load<W>(t_max + i) : vfloat<W>(infinity), vfloat<W>(-1.0f));
    return r;
}

/// Whether a pass of scattered rays goes as one stream (intersect_stream.h) rather than packet
/// by packet: when the scene has meshes, whose deep trees part a packet's lanes. Over a few
/// analytic shapes the stream's bookkeeping costs more than it saves (the glossy sphere of
/// Figure 1b took 1.6x as long as a stream, the other figures without meshes 1.02x-1.15x).
inline bool trace_as_stream(const Accel& accel, bool coherent) {
    return !coherent && !accel.meshes.empty();
}

/// Traces every ray of `q` to its closest hit: the first pass (camera rays, coherent) as blocks,
/// later passes (scattered rays) as one stream, or packet by packet (trace_as_stream).
template <int W>
void trace_queue(const SceneData& scene, const Accel& accel, const PathQueue& q, bool coherent,
                 HitArrays& h) {
    h.resize(q.ox.size());
    auto store_hits = [&](int base, int count, const HitPacket<W>* hits) {
        for (int p = 0; p < count; ++p) {
            const size_t i = static_cast<size_t>(base + p * W);
            store(&h.t[i], hits[p].t), store(&h.u[i], hits[p].u), store(&h.v[i], hits[p].v);
            store(&h.prim[i], hits[p].prim), store(&h.object[i], hits[p].object);
        }
    };
    if (trace_as_stream(accel, coherent)) {
        const int count = (q.size + W - 1) / W;
        QueuePackets<W>& qp = queue_packets<W>();
        qp.reserve(static_cast<size_t>(count));
        for (int p = 0; p < count; ++p)
            qp.rays[p] = queue_packet<W>(q, 0, q.size, p, nullptr, qp.active[p]);
        intersect_closest_stream(scene, accel, qp.rays.data(), qp.active.get(), qp.hits.data(),
                                 count);
        store_hits(0, count, qp.hits.data());
        return;
    }
    constexpr int max_packets = max_block_rays / W;
    RayPacket<W> rays[max_packets];
    HitPacket<W> hits[max_packets];
    vmask<W> active[max_packets];
    for (int base = 0; base < q.size; base += max_block_rays) {
        const int n = std::min(max_block_rays, q.size - base);
        const int count = (n + W - 1) / W;
        for (int p = 0; p < count; ++p)
            rays[p] = queue_packet<W>(q, base, n, p, nullptr, active[p]);
        if (coherent) {
            intersect_closest_block(scene, accel, rays, active, hits, count);
        } else {
            for (int p = 0; p < count; ++p)
                hits[p] = intersect_closest(scene, accel, rays[p], active[p]);
        }
        store_hits(base, count, hits);
    }
}

/// Traces the shadow queue of one light and adds the contributions of free segments: as blocks
/// after the camera pass (coherent); after later passes (scattered hit points) as one stream or
/// packet by packet (trace_as_stream).
template <int W>
void trace_shadows(const SceneData& scene, const Accel& accel, const ShadowQueue& q, bool coherent,
                   TileBuffers& b) {
    auto add_free = [&](int base, int count, const vmask<W>* active, const vmask<W>* occluded) {
        for (int p = 0; p < count; ++p) {
            for_each_active(mask_andnot(active[p], occluded[p]), [&](int l) {
                const size_t i = static_cast<size_t>(base + p * W + l);
                const size_t path = static_cast<size_t>(q.path[i]);
                b.path_r[path] += q.cr[i];
                b.path_g[path] += q.cg[i];
                b.path_b[path] += q.cb[i];
            });
        }
    };
    if (trace_as_stream(accel, coherent)) {
        const int count = (q.size + W - 1) / W;
        QueuePackets<W>& qp = queue_packets<W>();
        qp.reserve(static_cast<size_t>(count));
        for (int p = 0; p < count; ++p)
            qp.rays[p] = queue_packet<W>(q, 0, q.size, p, q.t_max.data(), qp.active[p]);
        intersect_any_stream(scene, accel, qp.rays.data(), qp.active.get(), qp.occluded.get(),
                             count);
        add_free(0, count, qp.active.get(), qp.occluded.get());
        return;
    }
    constexpr int max_packets = max_block_rays / W;
    RayPacket<W> rays[max_packets];
    vmask<W> active[max_packets], occluded[max_packets];
    for (int base = 0; base < q.size; base += max_block_rays) {
        const int n = std::min(max_block_rays, q.size - base);
        const int count = (n + W - 1) / W;
        for (int p = 0; p < count; ++p)
            rays[p] = queue_packet<W>(q, base, n, p, q.t_max.data(), active[p]);
        if (coherent) {
            intersect_any_block(scene, accel, rays, active, occluded, count);
        } else {
            for (int p = 0; p < count; ++p)
                occluded[p] = intersect_any(scene, accel, rays[p], active[p]);
        }
        add_free(base, count, active, occluded);
    }
}

/// The colour of every slot (a sample of a pixel) whose camera ray is in b.paths: passes of
/// trace, Beer's law, misses, sort by material, shade, shadows - until no rays are left. A pass
/// sums each path's terms apart (in the order the scalar path adds them), then adds the paths to
/// their slots in queue order; the queue's order is the same at every W (sort_by_parent), so the
/// image is the same bits at every W.
template <int W, uint32_t F>
void shade_tile_samples(const SceneData& scene, const Accel& accel, const ShadeParams& params,
                        int32_t first_sample, uint32_t seed, TileBuffers& b, ShadeCounts& counts) {
    const size_t materials = scene.materials.size();
    if (b.shadows.size() < scene.lights.size()) b.shadows.resize(scene.lights.size());
    b.material_count.resize(materials + 1);
    bool first = true;
    while (b.paths.size > 0) {
        PathQueue& q = b.paths;
        const bool camera_pass = first;
        trace_queue<W>(scene, accel, q, first, b.hits);
        first = false;
        for (auto* v : {&b.path_r, &b.path_g, &b.path_b}) v->assign(q.ox.size(), 0.0f);
        if (b.order.size() < static_cast<size_t>(q.size + W)) b.order.resize(q.ox.size());
        // Beer's law over the distance travelled, misses, and the count of hits per material
        std::fill(b.material_count.begin(), b.material_count.end(), 0);
        for (int i = 0; i < q.size; ++i) {
            const size_t r = static_cast<size_t>(i);
            if constexpr ((F & feature_refraction) != 0) {
                if (q.fr[r] != 1.0f || q.fg[r] != 1.0f || q.fb[r] != 1.0f) {
                    const vec3 f =
                        raylane::beer_transmittance(vec3(q.fr[r], q.fg[r], q.fb[r]), b.hits.t[r]);
                    q.wr[r] *= f.x, q.wg[r] *= f.y, q.wb[r] *= f.z;
                }
            }
            if (b.hits.prim[r] < 0) continue;
            ++b.material_count[scene.objects[size_t(b.hits.object[r])].material + 1];
        }
        // misses: the environment (or background) W rays at a time
        for (int base = 0; base < q.size; base += W) {
            const size_t i = static_cast<size_t>(base);
            const int lanes = std::min(W, q.size - base);
            const vmask<W> live = mask_from_bits<W>(lanes >= 32 ? ~0u : (1u << lanes) - 1u);
            const vmask<W> miss = mask_and(live, lt(load<W>(&b.hits.prim[i]), vint<W>(0)));
            if (none(miss)) continue;
            const Vec3<W> dir = load_vec3<W>(&q.dx[i], &q.dy[i], &q.dz[i]);
            const Vec3<W> w = load_vec3<W>(&q.wr[i], &q.wg[i], &q.wb[i]);
            const Vec3<W> l = miss_radiance<W>(scene, load<W>(&q.env_map[i]), dir, miss);
            const Vec3<W> add = w * l;
            store(&b.path_r[i], select(miss, add.x, vfloat<W>(0.0f)));
            store(&b.path_g[i], select(miss, add.y, vfloat<W>(0.0f)));
            store(&b.path_b[i], select(miss, add.z, vfloat<W>(0.0f)));
        }
        // counting sort of the hits by material (stable: tile order within a material)
        for (size_t m = 1; m <= materials; ++m) b.material_count[m] += b.material_count[m - 1];
        for (int i = 0; i < q.size; ++i) {
            const size_t r = static_cast<size_t>(i);
            if (b.hits.prim[r] < 0) continue;
            const uint32_t m = scene.objects[size_t(b.hits.object[r])].material;
            b.order[size_t(b.material_count[m]++)] = i;
        }
        // shade each material's hits W at a time (material_count[m] is now the end of m)
        const ShadeTarget target{.path_r = b.path_r.data(),
                                 .path_g = b.path_g.data(),
                                 .path_b = b.path_b.data(),
                                 .shadows = b.shadows.data(),
                                 .next = &b.next,
                                 .next_inside = &b.next_inside,
                                 .counts = &counts};
        const SlotMap slots{.pixel = b.pixel, .first_sample = first_sample};
        int begin = 0;
        for (size_t m = 0; m < materials; ++m) {
            const int end = b.material_count[m];
            for (int i = begin; i < end; i += W) {
                const int next = b.next.size, next_inside = b.next_inside.size;
                shade_packet<W, F>(scene, scene.materials[m], params, seed, slots, q, b.hits,
                                   &b.order[size_t(i)], std::min(W, end - i), target);
                b.next.sort_by_parent(next), b.next_inside.sort_by_parent(next_inside);
            }
            begin = end;
        }
        for (size_t j = 0; j < scene.lights.size(); ++j) {
            trace_shadows<W>(scene, accel, b.shadows[j], camera_pass, b);
            b.shadows[j].clear();
        }
        for (int i = 0; i < q.size; ++i) {
            const size_t path = static_cast<size_t>(i), s = static_cast<size_t>(q.slot[path]);
            b.acc_r[s] += b.path_r[path], b.acc_g[s] += b.path_g[path];
            b.acc_b[s] += b.path_b[path];
        }
        b.next.append(b.next_inside);  // rays inside a medium after the others
        b.next_inside.clear();
        std::swap(b.paths, b.next);
        b.next.clear();
    }
}

/// The kernel features that spawn secondary rays (mirrors, glass, glossy lobes): one group.
constexpr uint32_t group_secondary = feature_reflection | feature_refraction | feature_glossy;

/// Whether kernels of feature set F spawn secondary rays (and so need the wavefront).
template <uint32_t F>
constexpr bool has_secondary_rays = (F & group_secondary) != 0;

/// shade_tile_samples for scenes without secondary rays: one pass, so the camera block is traced
/// and each packet shaded where it stands, its lanes grouped by the object they hit (one
/// material each), into value[] in registers; the shadow rays of each light sample stay in
/// their packets and are traced as a block. No queue, sort by material, gathers or scatters;
/// the same arithmetic per ray, in the same order, so the same image.
template <int W, uint32_t F>
void shade_camera_block(const SceneData& scene, const Accel& accel, const ShadeParams& params,
                        int32_t sample, uint32_t seed, const RayPacket<W>* rays,
                        const vmask<W>* active, const vint<W>* slot, const vint<W>* pixel,
                        int count, Vec3<W>* value, ShadeCounts& counts) {
    static_assert(!has_secondary_rays<F>);
    constexpr int max_packets = max_block_rays / W;
    // one block of shadow rays per light sample, light j's from first[j] on (kept per thread)
    thread_local std::vector<ShadowBlock<W>> shadows;
    thread_local std::vector<int> first;
    first.resize(scene.lights.size() + 1);
    first[0] = 0;
    for (size_t j = 0; j < scene.lights.size(); ++j)
        first[j + 1] =
            first[j] + (scene.lights[j].shadows ? light_sample_count(scene.lights[j], params) : 0);
    if (shadows.size() < size_t(first.back())) shadows.resize(size_t(first.back()));
    for (int k = 0; k < first.back(); ++k)
        for (int p = 0; p < count; ++p) shadows[size_t(k)].lanes[p] = vmask<W>(false);

    HitPacket<W> hits[max_packets];
    intersect_closest_block(scene, accel, rays, active, hits, count);
    const Vec3<W> one = make_vec3<W>(1.0f, 1.0f, 1.0f);
    for (int p = 0; p < count; ++p) {
        value[p] = make_vec3<W>(0.0f, 0.0f, 0.0f);
        const PacketTarget<W> target{.value = &value[p],
                                     .shadows = shadows.data(),
                                     .shadow_first = first.data(),
                                     .packet = p,
                                     .counts = &counts};
        const vmask<W> hit = mask_andnot(active[p], lt(hits[p].prim, vint<W>(0)));
        const vmask<W> miss = mask_andnot(active[p], hit);
        if (any(miss)) {
            const Vec3<W> l = miss_radiance<W>(scene, vint<W>(-1), rays[p].dir, miss);
            shade_detail::accumulate<W>(target, slot[p], one * l, miss);
        }
        const ShadeInput<W> in{.rays = rays[p],
                               .hits = hits[p],
                               .weight = one,
                               .slot = slot[p],
                               .path = slot[p],  // (unused: PacketTarget adds to value[p])
                               .key = vint<W>(0),
                               .refl_depth = vint<W>(0),
                               .refr_depth = vint<W>(0),
                               .env = vint<W>(-1),
                               .pixel = pixel[p],
                               .sample = vint<W>(sample),
                               .local_only = mask_andnot(hit, hit)};
        for (vmask<W> todo = hit; any(todo);) {
            const int32_t object = get(hits[p].object, first_active(todo));
            const vmask<W> same = mask_and(todo, eq(hits[p].object, vint<W>(object)));
            const Material& m = scene.materials[scene.objects[size_t(object)].material];
            shade_hits<W, F>(scene, m, params, seed, in, same, target);
            todo = mask_andnot(todo, same);
        }
    }
    // each light sample's shadow rays as a block; free segments add their contribution, in the
    // order of the wavefront's shadow queues (light by light, sample by sample)
    vmask<W> occluded[max_packets];
    for (int k = 0; k < first.back(); ++k) {
        ShadowBlock<W>& b = shadows[size_t(k)];
        bool some = false;  // a block of sky or unlit points has no shadow ray at all
        for (int p = 0; p < count; ++p) {
            if (none(b.lanes[p])) b.rays[p].t_max = vfloat<W>(-1.0f);  // never written
            some = some || any(b.lanes[p]);
        }
        if (!some) continue;
        intersect_any_block(scene, accel, b.rays, b.lanes, occluded, count);
        for (int p = 0; p < count; ++p) {
            const vmask<W> free = mask_andnot(b.lanes[p], occluded[p]);
            value[p] = select(free, value[p] + b.contribution[p], value[p]);
        }
    }
}

}  // namespace raylane::RAYLANE_ISA_NS
