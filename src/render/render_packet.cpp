// render: the packet renderer. Mirrors render_scalar.cpp.
#include "render/render_packet.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cstring>
#include <memory>
#include <vector>

#include "core/rng.h"
#include "render/camera_rays_packet.h"
#include "render/sample_sum_packet.h"
#include "render/tiles.h"
#include "scene/features.h"
#include "shade/optics_scalar.h"
#include "shade/path_queue.h"
#include "shade/shade_io_packet.h"
#include "shade/shade_packet.h"
#include "simd/hash.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_stream.h"
#include "traverse/surface_packet.h"

namespace raylane::RAYLANE_ISA_NS {
namespace {

/// A camera packet covers packet_cols x packet_rows pixels of its tile: 4x4 at W = 16, 4x2 at 8,
/// 2x2 at 4. A square's rays stay closer together through the BVH than a row's.
template <int W>
constexpr int packet_cols = W >= 8 ? 4 : (W >= 2 ? 2 : 1);
template <int W>
constexpr int packet_rows = W / packet_cols<W>;

/// One sample's values of a non-colour AOV, for a block of packets (a tile).
template <int W>
void aov_values(const Scene& scene, const Accel& accel, const RayPacket<W>* rays,
                const vmask<W>* active, int count, Aov aov, Vec3<W>* value) {
    constexpr int max_packets = max_block_rays / W;
    HitPacket<W> hits[max_packets];
    vmask<W> hit[max_packets];
    vint<W> nodes[max_packets];
    if (aov == Aov::bvh_cost) {
        // the cost of each ray on its own (a packet's traversal would give every lane the
        // packet's count): single-lane traversals, the scalar path's node counts
        for (int p = 0; p < count; ++p) {
            nodes[p] = vint<W>(0);
            hits[p] = HitPacket<W>{};
            for_each_active(active[p], [&](int i) {
                RayPacket<1> one;
                one.org = make_vec3<1>(get(rays[p].org.x, i), get(rays[p].org.y, i),
                                       get(rays[p].org.z, i));
                one.dir = make_vec3<1>(get(rays[p].dir.x, i), get(rays[p].dir.y, i),
                                       get(rays[p].dir.z, i));
                one.t_min = get(rays[p].t_min, i);
                one.t_max = get(rays[p].t_max, i);
                int32_t n = 0;
                const HitPacket<1> h = intersect_closest<1>(scene, accel, one, true, &n);
                set(nodes[p], i, n);
                set(hits[p].t, i, h.t);
            });
        }
    } else {
        intersect_closest_block(scene, accel, rays, active, hits, count);
    }
    for (int p = 0; p < count; ++p) hit[p] = mask_and(active[p], hits[p].t < vfloat<W>(infinity));
    const Vec3<W> black = make_vec3<W>(0.0f, 0.0f, 0.0f);
    for (int p = 0; p < count; ++p) {
        switch (aov) {
            case Aov::color:
                value[p] = black;
                break;
            case Aov::normal:
                value[p] =
                    any(hit[p])
                        ? select(hit[p], surface_at(scene, rays[p], hits[p], hit[p]).shading_normal,
                                 black)
                        : black;
                break;
            case Aov::depth: {
                const vfloat<W> t = select(hit[p], hits[p].t, vfloat<W>(0.0f));
                value[p] = {t, t, t};
                break;
            }
            case Aov::bvh_cost: {
                const vfloat<W> n = to_float(nodes[p]);
                value[p] = {n, n, n};
                break;
            }
        }
    }
}

/// Samples of a tile's pixels traced together in one wavefront: its camera rays go in camera
/// packet by camera packet (a packet's samples one after the other), so the secondary rays of a
/// packet come from a few neighbouring pixels rather than from sixteen, and stay together longer.
constexpr int max_batch_samples = 16;

/// Samples per wavefront times the rays a camera ray may spawn (an estimate, below): kept under
/// this, a wavefront's queues stay about as large as one sample's of a scene with a few shadow
/// rays per hit, which fit the cache.
constexpr int64_t wavefront_ray_budget = 96;

/// The samples per wavefront: up to max_batch_samples, fewer when hits spawn many rays (shadow
/// rays to every light sample, times the glossy rays and their own shadow rays). It depends on
/// the scene and the sample-count options only, never on threads or timing: the summation order
/// of a pixel's contributions, and so the image's last bits, depend on it.
int samples_per_wavefront(const Scene& scene, const ShadeParams& params) {
    int64_t shadow = 0, glossy = 0;  // 64 bits: any number of lights of 4096 samples
    for (const Light& light : scene.lights)
        if (light.shadows) shadow += light_sample_count(light, params);
    for (const Material& m : scene.materials)
        if (m.model == SpecularModel::glossy_phong)
            glossy = std::max<int64_t>(glossy, glossy_sample_count(m, params));
    const int64_t rays = std::max<int64_t>(shadow, 1) * (1 + glossy);
    return static_cast<int>(std::clamp<int64_t>(wavefront_ray_budget / rays, 1, max_batch_samples));
}

/// A wavefront's slots (shade_io_packet.h, SlotMap): sample j of the batch at tile slot i is slot
/// j * max_block_rays + i.
constexpr int max_slots = max_batch_samples * max_block_rays;

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
bool trace_as_stream(const Accel& accel, bool coherent) {
    return !coherent && !accel.meshes.empty();
}

/// Traces every ray of `q` to its closest hit: the first pass (camera rays, coherent) as blocks,
/// later passes (scattered rays) as one stream, or packet by packet (trace_as_stream).
template <int W>
void trace_queue(const Scene& scene, const Accel& accel, const PathQueue& q, bool coherent,
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
void trace_shadows(const Scene& scene, const Accel& accel, const ShadowQueue& q, bool coherent,
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
void shade_tile_samples(const Scene& scene, const Accel& accel, const ShadeParams& params,
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
                shade_batch<W, F>(scene, scene.materials[m], params, seed, slots, q, b.hits,
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
void shade_camera_block(const Scene& scene, const Accel& accel, const ShadeParams& params,
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

/// A camera packet's lanes in its packet_cols x packet_rows block of pixels: column
/// lane % packet_cols, row lane / packet_cols.
template <int W>
struct PacketLanes {
    alignas(64) int32_t cols[W], rows[W];
    vint<W> col, row;
    vint<W> pixel_offset;  ///< each lane's pixel from the packet's first in the image
};

/// Offset of each lane's pixel from the packet's first in an array `stride` pixels wide.
template <int W>
vint<W> lane_offset(const PacketLanes<W>& lanes, int stride) {
    alignas(64) int32_t offset[W];
    for (int i = 0; i < W; ++i) offset[i] = lanes.rows[i] * stride + lanes.cols[i];
    return load<W>(offset);
}

template <int W>
PacketLanes<W> make_packet_lanes(int image_width) {
    PacketLanes<W> lanes;
    for (int i = 0; i < W; ++i)
        lanes.cols[i] = i % packet_cols<W>, lanes.rows[i] = i / packet_cols<W>;
    lanes.col = load<W>(lanes.cols);
    lanes.row = load<W>(lanes.rows);
    lanes.pixel_offset = lane_offset(lanes, image_width);
    return lanes;
}

/// A tile as camera packets of packet_cols x packet_rows pixels (4x4 at W = 16: compact ray
/// bundles); lanes past the tile's edges are inactive.
template <int W>
struct TilePackets {
    static constexpr int max_packets = max_block_rays / W;
    int count = 0;   ///< packets in use
    int tile_w = 0;  ///< the tile's width in pixels
    vmask<W> active[max_packets];
    vint<W> xi[max_packets], yi[max_packets];  ///< each lane's pixel in the image
    vint<W> pixel[max_packets];                ///< the same as an index, row by row
    vint<W> slot[max_packets];                 ///< its index in the tile, row by row
};

/// The tile's packets; with secondary rays also the wavefront's slot -> pixel map (b.pixel).
template <int W, uint32_t F>
TilePackets<W> tile_packets(const Tile& tile, int image_width, const PacketLanes<W>& lanes,
                            TileBuffers& b) {
    TilePackets<W> tp;
    tp.tile_w = tile.x1 - tile.x0;
    const vint<W> slot_offset = lane_offset(lanes, tp.tile_w);
    int count = 0;
    for (int y0 = tile.y0; y0 < tile.y1; y0 += packet_rows<W>) {
        for (int x0 = tile.x0; x0 < tile.x1; x0 += packet_cols<W>, ++count) {
            tp.xi[count] = vint<W>(x0) + lanes.col;
            tp.yi[count] = vint<W>(y0) + lanes.row;
            tp.active[count] =
                mask_and(lt(tp.xi[count], vint<W>(tile.x1)), lt(tp.yi[count], vint<W>(tile.y1)));
            tp.pixel[count] = vint<W>(y0 * image_width + x0) + lanes.pixel_offset;
            tp.slot[count] = vint<W>((y0 - tile.y0) * tp.tile_w + (x0 - tile.x0)) + slot_offset;
            if constexpr (has_secondary_rays<F>) {  // the wavefront's slot -> pixel map
                for_each_active(tp.active[count], [&](int i) {
                    b.pixel[get(tp.slot[count], i)] = get(tp.pixel[count], i);
                });
            }
        }
    }
    assert(count <= TilePackets<W>::max_packets);  // tiles are at most 16x16 pixels
    tp.count = count;
    return tp;
}

/// Camera packet p's rays for sample s; inactive lanes get t_max = -1.
template <int W, uint32_t F>
RayPacket<W> camera_packet(const CameraFrame& frame, int spp, uint32_t seed,
                           const TilePackets<W>& tp, int p, int s) {
    const vint<W> si(s), seeds(static_cast<int32_t>(seed));
    // sample position: the pixel centre, or stratified in the pixel
    vfloat<W> jx(0.5f), jy(0.5f);
    if (spp > 1) {
        stratified_square<W>(s, spp, random_float<W>(tp.pixel[p], si, vint<W>(dim_pixel_x), seeds),
                             random_float<W>(tp.pixel[p], si, vint<W>(dim_pixel_y), seeds), jx, jy);
    }
    vfloat<W> lu(0.5f), lv(0.5f);
    if constexpr ((F & feature_lens) != 0) {
        if (frame.lens_radius > 0.0f) {
            lu = random_float<W>(tp.pixel[p], si, vint<W>(dim_lens_u), seeds);
            lv = random_float<W>(tp.pixel[p], si, vint<W>(dim_lens_v), seeds);
        }
    }
    RayPacket<W> r = camera_ray<W>(frame, to_float(tp.xi[p]) + jx, to_float(tp.yi[p]) + jy, lu, lv);
    r.t_max = select(tp.active[p], r.t_max, vfloat<W>(-1.0f));
    return r;
}

/// The tile's sums of samples per pixel, and its counts of NaN and infinite samples.
template <int W>
struct TileSums {
    PixelSumPacket<W> sum[max_block_rays / W];
    uint64_t nans = 0, infs = 0;
};

/// Adds one sample's values to the pixels' sums (samples in order, so the same sums).
template <int W>
void add_values(const TilePackets<W>& tp, const Vec3<W>* value, TileSums<W>& sums) {
    for (int p = 0; p < tp.count; ++p) {
        vmask<W> nan, inf;
        sample_kinds<W>(value[p], nan, inf);
        add_sample<W>(sums.sum[p], value[p], mask_andnot(tp.active[p], mask_or(nan, inf)));
        sums.nans += static_cast<uint64_t>(count(mask_and(tp.active[p], nan)));
        sums.infs += static_cast<uint64_t>(count(mask_and(tp.active[p], inf)));
    }
}

/// Sample s of the tile's pixels without a wavefront: an AOV, or the colour of a scene without
/// secondary rays (shade_camera_block).
template <int W, uint32_t F>
void sample_values(const Scene& scene, const Accel& accel, const RenderParams& params,
                   const ShadeParams& shade, const CameraFrame& frame, int spp,
                   const TilePackets<W>& tp, int s, Vec3<W>* value, ShadeCounts& counts) {
    RayPacket<W> rays[TilePackets<W>::max_packets];
    for (int p = 0; p < tp.count; ++p)
        rays[p] = camera_packet<W, F>(frame, spp, params.seed, tp, p, s);
    if (params.aov != Aov::color) {
        aov_values<W>(scene, accel, rays, tp.active, tp.count, params.aov, value);
    } else if constexpr (!has_secondary_rays<F>) {
        shade_camera_block<W, F>(scene, accel, shade, s, params.seed, rays, tp.active, tp.slot,
                                 tp.pixel, tp.count, value, counts);
    } else {
        assert(false);  // colour with secondary rays is always batched (wavefront_values)
    }
}

/// Samples s0 .. s0 + n - 1 of the tile's pixels in one wavefront (colour with secondary rays):
/// the camera rays into the queue, a packet's n samples one after the other; then passes until
/// every path has ended; then each sample's values into the sums.
template <int W, uint32_t F>
void wavefront_values(const Scene& scene, const Accel& accel, const RenderParams& params,
                      const ShadeParams& shade, const CameraFrame& frame, int spp,
                      const TilePackets<W>& tp, int s0, int n, TileBuffers& b, TileSums<W>& sums,
                      ShadeCounts& counts) {
    b.paths.clear();
    std::fill(b.acc_r, b.acc_r + n * max_block_rays, 0.0f);
    std::fill(b.acc_g, b.acc_g + n * max_block_rays, 0.0f);
    std::fill(b.acc_b, b.acc_b + n * max_block_rays, 0.0f);
    const Vec3<W> one = make_vec3<W>(1.0f, 1.0f, 1.0f);
    const vint<W> zero(0), none(-1);
    for (int p = 0; p < tp.count; ++p) {
        for (int j = 0; j < n; ++j) {
            const RayPacket<W> r = camera_packet<W, F>(frame, spp, params.seed, tp, p, s0 + j);
            push_packet<W>(b.paths, r.org, r.dir, one, one,
                           tp.slot[p] + vint<W>(j * max_block_rays), none, zero, zero, zero, none,
                           zero, tp.active[p]);
        }
    }
    shade_tile_samples<W, F>(scene, accel, shade, s0, params.seed, b, counts);
    Vec3<W> value[TilePackets<W>::max_packets];
    for (int j = 0; j < n; ++j) {
        for (int p = 0; p < tp.count; ++p) {
            const vint<W> at = tp.slot[p] + vint<W>(j * max_block_rays);
            value[p].x = gather(b.acc_r, at, tp.active[p]);
            value[p].y = gather(b.acc_g, at, tp.active[p]);
            value[p].z = gather(b.acc_b, at, tp.active[p]);
        }
        add_values<W>(tp, value, sums);
    }
}

/// The tile's pixel means into the film: into a buffer in film order (slot[p] holds each lane's
/// index in it), then into the film a row at a time: a few wide stores per row instead of three
/// per pixel.
template <int W>
void write_tile(const Tile& tile, const TilePackets<W>& tp, const TileSums<W>& sums,
                const PixelRect& region, Film& film) {
    static_assert(sizeof(vec3) == 3 * sizeof(float));  // runs of floats copied as pixels
    alignas(64) vec3 tile_rgb[max_block_rays];
    for (int p = 0; p < tp.count; ++p) {
        const Vec3<W> mean = pixel_mean<W>(sums.sum[p]);
        alignas(64) float rgb[3 * W];
        store_vec3_aos(rgb, mean);
        if (all(tp.active[p])) {  // inside the tile: a row of the packet is a run of the buffer
            const int at = get(tp.slot[p], 0);
            for (int r = 0; r < packet_rows<W>; ++r)
                std::memcpy(&tile_rgb[at + r * tp.tile_w], &rgb[3 * r * packet_cols<W>],
                            3 * packet_cols<W> * sizeof(float));
        } else {
            alignas(64) int32_t at[W];
            store_aligned(at, tp.slot[p]);
            for_each_active(tp.active[p], [&](int i) {
                tile_rgb[at[i]] = vec3(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
            });
        }
    }
    // the film holds the region: the tile's rows and columns inside it
    const int x0 = std::max(tile.x0, region.x0), x1 = std::min(tile.x1, region.x1);
    for (int y = std::max(tile.y0, region.y0); y < std::min(tile.y1, region.y1); ++y) {
        vec3* row = &film.at(x0 - region.x0, y - region.y0);
        const vec3* from = &tile_rgb[(y - tile.y0) * tp.tile_w + (x0 - tile.x0)];
        if (x1 - x0 == 16)  // the common case: a copy of constant size, inlined
            std::memcpy(row, from, 16 * sizeof(vec3));
        else
            std::memcpy(row, from, static_cast<size_t>(x1 - x0) * sizeof(vec3));
    }
}

template <int W, uint32_t F>
RenderResult render_packet_features(const Scene& scene, const Accel& accel,
                                    const RenderParams& params) {
    const auto start = std::chrono::steady_clock::now();
    const Camera& cam = scene.camera;
    const CameraFrame frame = make_camera_frame(cam);
    RenderResult result;
    const PixelRect region = render_region(params, cam.width, cam.height);
    result.film = make_film_for_overwrite(region.width(), region.height());
    const int spp = params.spp > 0 ? params.spp : 1;
    // a tile is a block: at most max_block_rays pixels, rows a multiple of W wide
    const int tile_size = std::min(params.tile_size, 16);
    const std::vector<Tile> tiles = make_tiles(cam.width, cam.height, tile_size, region);
    PerThreadStats per_thread;
    Progress progress{params.progress_label, tiles.size(), params.progress && stderr_is_terminal()};
    const PacketLanes<W> lanes = make_packet_lanes<W>(cam.width);
    const ShadeParams shade{params.light_samples, params.glossy_samples};
    const int wavefront_samples = samples_per_wavefront(scene, shade);

    for_each_tile(tiles, params.threads, progress, [&](const Tile& tile) {
        thread_local TileBuffers b;
        const TilePackets<W> tp = tile_packets<W, F>(tile, cam.width, lanes, b);
        TileSums<W> sums;
        ShadeCounts counts;
        // colour with secondary rays: batches of samples, one wavefront each; else one sample at
        // a time
        const bool batched = has_secondary_rays<F> && params.aov == Aov::color;
        const int batch = batched ? wavefront_samples : 1;
        for (int s0 = 0; s0 < spp; s0 += batch) {
            if (batched) {
                wavefront_values<W, F>(scene, accel, params, shade, frame, spp, tp, s0,
                                       std::min(batch, spp - s0), b, sums, counts);
            } else {
                Vec3<W> value[TilePackets<W>::max_packets];
                sample_values<W, F>(scene, accel, params, shade, frame, spp, tp, s0, value, counts);
                add_values<W>(tp, value, sums);
            }
        }
        write_tile<W>(tile, tp, sums, region, result.film);
        per_thread.local().add_tile(counts, sums.nans, sums.infs);
    });

    result.stats.primary_rays = static_cast<uint64_t>(region.width()) *
                                static_cast<uint64_t>(region.height()) * static_cast<uint64_t>(spp);
    for (const RenderStats& sums : per_thread) result.stats.add_counts(sums);
    result.stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

/// The kernel feature set for a scene: groups of features, so 16 kernels cover every scene.
uint32_t kernel_features(uint32_t scene) {
    uint32_t f = 0;
    if (scene & feature_textures) f |= feature_textures;
    if (scene & feature_area_lights) f |= feature_area_lights;
    if (scene & group_secondary) f |= group_secondary;
    if (scene & (feature_environment | feature_lens)) f |= feature_environment | feature_lens;
    return f;
}

#ifndef RAYLANE_SANITIZED
constexpr uint32_t group_camera = feature_environment | feature_lens;

/// Calls the kernel compiled for exactly the feature groups in f.
template <int W>
RenderResult dispatch(uint32_t f, const Scene& scene, const Accel& accel,
                      const RenderParams& params) {
    constexpr uint32_t T = feature_textures, A = feature_area_lights, S = group_secondary,
                       C = group_camera;
    switch (f) {
#define RAYLANE_KERNEL(bits) \
    case (bits):             \
        return render_packet_features<W, (bits)>(scene, accel, params);
        RAYLANE_KERNEL(0)
        RAYLANE_KERNEL(T)
        RAYLANE_KERNEL(A)
        RAYLANE_KERNEL(T | A)
        RAYLANE_KERNEL(S)
        RAYLANE_KERNEL(S | T)
        RAYLANE_KERNEL(S | A)
        RAYLANE_KERNEL(S | T | A)
        RAYLANE_KERNEL(C)
        RAYLANE_KERNEL(C | T)
        RAYLANE_KERNEL(C | A)
        RAYLANE_KERNEL(C | T | A)
        RAYLANE_KERNEL(C | S)
        RAYLANE_KERNEL(C | S | T)
        RAYLANE_KERNEL(C | S | A)
#undef RAYLANE_KERNEL
        default:
            return render_packet_features<W, kernel_features_all>(scene, accel, params);
    }
}

#endif

}  // namespace

template <int W>
RenderResult render_packet_width(const Scene& scene, const Accel& accel,
                                 const RenderParams& params) {
#ifdef RAYLANE_SANITIZED
    // sanitizer builds compile two kernels, 16 take too long to build there: the generic one and
    // the one for scenes that use no kernel feature, so that the one-pass shading
    // (shade_camera_block) runs under the sanitizers too; the release tests check that every
    // specialised kernel gives the generic kernel's image
    if constexpr (W == native_width) {
        if (!params.generic_kernel && kernel_features(scene_features(scene)) == 0)
            return render_packet_features<W, 0>(scene, accel, params);
    }
    return render_packet_features<W, kernel_features_all>(scene, accel, params);
#else
    if (params.generic_kernel || W != native_width)
        return render_packet_features<W, kernel_features_all>(scene, accel, params);
    return dispatch<W>(kernel_features(scene_features(scene)), scene, accel, params);
#endif
}

RenderResult render_packet_isa(const Scene& scene, const Accel& accel, const RenderParams& params) {
    return render_packet_width<native_width>(scene, accel, params);
}

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W) \
    template RenderResult render_packet_width<W>(const Scene&, const Accel&, const RenderParams&);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE

}  // namespace raylane::RAYLANE_ISA_NS
