// query: queries of a caller's ray arrays over threads (intersect_batch.h).
#include "query/intersect_batch.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <vector>

#include "core/float_modes.h"
#include "core/ray_packet.h"
#include "query/batch_rays.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_scalar.h"
#include "traverse/intersect_stream.h"
#include "traverse/surface_scalar.h"
#include "traverse/triangle_scalar.h"

namespace raylane::RAYLANE_ISA_NS {
namespace {

/// The geometric normal surface_at gives for ray i's hit: from the table when there is one,
/// straight from the triangle's corners for a mesh otherwise.
vec3 geometric_normal(const SceneData& scene, const TriangleNormals* normals, const RayArrays& rays,
                      size_t i, const Hit& hit) {
    if (!hit.hit()) return vec3(0.0f);
    const Object& object = scene.objects[hit.object];
    if (normals && object.kind == ShapeKind::mesh) return normals->meshes[object.shape][hit.prim];
    if (object.kind != ShapeKind::mesh) {
        Ray ray;
        read_ray(rays, i, ray);
        return surface_at(scene, ray, hit).geometric_normal;
    }
    const MeshData& mesh = scene.meshes[object.shape];
    const glm::uvec3 tri = mesh.tris[hit.prim];
    return geometry_triangle<float>(mesh.positions[tri.x], mesh.positions[tri.y],
                                    mesh.positions[tri.z], hit.uv.x, hit.uv.y)
        .normal;
}

/// The scene and what a batch writes.
struct Output {
    const SceneData& scene;
    const RayArrays& rays;
    const HitBuffers& hits;
    const TriangleNormals* normals;
};

void write_hit(const Output& o, const Hit& hit, size_t i) {
    const HitBuffers& out = o.hits;
    if (out.t) out.t[i] = hit.t;
    if (out.prim) out.prim[i] = static_cast<int32_t>(hit.prim);
    if (out.object) out.object[i] = static_cast<int32_t>(hit.object);
    if (out.u) out.u[i] = hit.uv.x;
    if (out.v) out.v[i] = hit.uv.y;
    if (out.normal) {
        const vec3 n = geometric_normal(o.scene, o.normals, o.rays, i, hit);
        out.normal[3 * i] = n.x, out.normal[3 * i + 1] = n.y, out.normal[3 * i + 2] = n.z;
    }
}

/// Runs body(first, last) over the rays in tasks of batch_task_rays on params.threads threads.
template <class Body>
void run_tasks(size_t count, int threads, Body&& body) {
    if (count == 0) return;
    const size_t tasks = (count + batch_task_rays - 1) / batch_task_rays;
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(size_t(0), tasks, [&](size_t k) {
            // flush-to-zero for the task; the thread's own modes come back afterwards (a task
            // may run on the caller's thread)
            const KeepFloatModes keep;
            enable_flush_to_zero();
            body(k * batch_task_rays, std::min(count, (k + 1) * batch_task_rays));
        });
    });
}

/// Packets of rays first .. first + n - 1 (n <= max_block_rays): ceil(n / W) packets, lanes of
/// rays that are not traced (read_ray's rule, tested a packet at a time) inactive with a benign
/// ray; lanes[p] holds packet p's active lanes. Returns the packet count; `coherent` tells
/// whether the traced rays pass the ConeTest.
template <int W>
int load_block(const RayArrays& rays, size_t first, size_t n, RayPacket<W>* packets,
               vmask<W>* active, uint32_t* lanes, bool& coherent) {
    alignas(64) float c[7][max_block_rays];
    const int count = static_cast<int>((n + W - 1) / W);
    const float* o = rays.org + first * rays.org_stride;
    const float* d = rays.dir + first * rays.dir_stride;
    for (size_t k = 0; k < n; ++k, o += rays.org_stride, d += rays.dir_stride) {
        c[0][k] = o[0], c[1][k] = o[1], c[2][k] = o[2];
        c[3][k] = d[0], c[4][k] = d[1], c[5][k] = d[2];
        c[6][k] = rays.t_max ? rays.t_max[first + k] : rays.t_max_all;
    }
    for (size_t k = n; k < size_t(count) * W; ++k) {  // padding: a benign inactive ray
        c[0][k] = c[1][k] = c[2][k] = c[3][k] = c[4][k] = 0.0f;
        c[5][k] = 1.0f, c[6][k] = -1.0f;
    }
    const vfloat<W> zero(0.0f);
    auto finite = [&](vfloat<W> x) { return (x - x) == zero; };  // false for inf and NaN
    int first_lane = -1;
    for (int p = 0; p < count; ++p) {
        const size_t at = size_t(p) * W;
        RayPacket<W> r;
        r.org = load_vec3<W>(&c[0][at], &c[1][at], &c[2][at]);
        r.dir = load_vec3<W>(&c[3][at], &c[4][at], &c[5][at]);
        r.t_max = load<W>(&c[6][at]);
        const vmask<W> on = mask_and(
            mask_and(mask_and(finite(r.org.x), finite(r.org.y)),
                     mask_and(finite(r.org.z), finite(r.dir.x))),
            mask_and(mask_and(finite(r.dir.y), finite(r.dir.z)),
                     mask_and(mask_or(mask_or(r.dir.x != zero, r.dir.y != zero), r.dir.z != zero),
                              r.t_max > zero)));
        packets[p].org = select(on, r.org, make_vec3<W>(0.0f, 0.0f, 0.0f));
        packets[p].dir = select(on, r.dir, make_vec3<W>(0.0f, 0.0f, 1.0f));
        packets[p].t_min = zero;
        packets[p].t_max = select(on, r.t_max, vfloat<W>(-1.0f));
        active[p] = on;
        lanes[p] = bits(on);
        if (first_lane < 0 && lanes[p] != 0) first_lane = p * W + std::countr_zero(lanes[p]);
    }
    // the ConeTest against the first traced ray's direction, a packet at a time
    coherent = true;
    if (first_lane < 0) return count;
    const size_t f = size_t(first_lane);
    const vec3 d0(c[3][f], c[4][f], c[5][f]);
    const vfloat<W> len0(glm::dot(d0, d0));
    for (int p = 0; p < count && coherent; ++p) {
        const Vec3<W>& dir = packets[p].dir;
        const vfloat<W> dot =
            dir.x * vfloat<W>(d0.x) + dir.y * vfloat<W>(d0.y) + dir.z * vfloat<W>(d0.z);
        const vfloat<W> len2 = dir.x * dir.x + dir.y * dir.y + dir.z * dir.z;
        const vmask<W> inside = mask_and(dot > zero, dot * dot >= vfloat<W>(0.81f) * len2 * len0);
        coherent = none(mask_andnot(active[p], inside));
    }
    return count;
}

/// Writes the hits of a block loaded by load_block: array by array, then the normals.
template <int W>
void store_block(const Output& out, const HitPacket<W>* hits, const vmask<W>* active, size_t first,
                 size_t n) {
    alignas(64) float t[max_block_rays], u[max_block_rays], v[max_block_rays];
    alignas(64) int32_t prim[max_block_rays], object[max_block_rays];
    const size_t count = (n + W - 1) / W;
    const vfloat<W> zero(0.0f);
    for (size_t p = 0; p < count; ++p) {  // inactive lanes: a miss
        const vmask<W> a = active[p];
        store(&t[p * W], select(a, hits[p].t, vfloat<W>(infinity)));
        store(&u[p * W], select(a, hits[p].u, zero)), store(&v[p * W], select(a, hits[p].v, zero));
        store(&prim[p * W], select(a, hits[p].prim, vint<W>(-1)));
        store(&object[p * W], select(a, hits[p].object, vint<W>(-1)));
    }
    const HitBuffers& h = out.hits;
    if (h.t) std::copy_n(t, n, h.t + first);
    if (h.u) std::copy_n(u, n, h.u + first);
    if (h.v) std::copy_n(v, n, h.v + first);
    if (h.prim) std::copy_n(prim, n, h.prim + first);
    if (h.object) std::copy_n(object, n, h.object + first);
    if (!h.normal) return;
    for (size_t k = 0; k < n; ++k) {
        Hit hit;
        hit.t = t[k], hit.uv = vec2(u[k], v[k]);
        hit.prim = static_cast<uint32_t>(prim[k]), hit.object = static_cast<uint32_t>(object[k]);
        const vec3 nrm = geometric_normal(out.scene, out.normals, out.rays, first + k, hit);
        float* dst = h.normal + 3 * (first + k);
        dst[0] = nrm.x, dst[1] = nrm.y, dst[2] = nrm.z;
    }
}

template <int W>
void store_occluded(const vmask<W>* occluded, const uint32_t* lanes, size_t first, size_t n,
                    uint8_t* out) {
    for (size_t p = 0; p * W < n; ++p) {
        const uint32_t hit = bits(occluded[p]) & lanes[p];
        for (size_t k = p * W; k < std::min(n, (p + 1) * W); ++k)
            out[first + k] = static_cast<uint8_t>(hit >> (k - p * W) & 1u);
    }
}

/// A task's packets: each block is loaded at the end of the task's stream; a block traced on
/// its own (coherent) gives its place back, the others stay and are traced together as one
/// stream when the task's blocks are all loaded.
template <int W>
struct StreamPackets {
    struct Block {
        size_t first, n;
        int packet;
    };
    std::vector<RayPacket<W>> rays;
    std::vector<HitPacket<W>> hits;
    std::unique_ptr<vmask<W>[]> active, occluded;  // (vector<bool> at W = 1)
    std::vector<uint32_t> lanes;
    std::vector<Block> blocks;  ///< the blocks in the stream
    int count = 0;              ///< packets in the stream

    StreamPackets() {
        constexpr size_t packets = (batch_task_rays + W - 1) / W;
        rays.resize(packets), hits.resize(packets), lanes.resize(packets);
        active.reset(new vmask<W>[packets]);
        occluded.reset(new vmask<W>[packets]);
    }
    void clear() { count = 0, blocks.clear(); }
};

template <int W>
StreamPackets<W>& stream_packets() {
    thread_local StreamPackets<W> s;
    return s;
}

/// Loads rays first .. last - 1 block by block into the task's stream; traced_alone(at, count,
/// first, n) traces a block that goes on its own (coherent) and writes its answers; then
/// traced_together() traces the rest as one stream.
template <int W, class Alone, class Together>
void packet_task(const RayArrays& rays, Coherence coherence, size_t first, size_t last,
                 StreamPackets<W>& s, Alone&& traced_alone, Together&& traced_together) {
    s.clear();
    for (size_t b = first; b < last; b += max_block_rays) {
        const size_t n = std::min<size_t>(max_block_rays, last - b);
        const int at = s.count;
        bool coherent = false;
        const int count = load_block<W>(rays, b, n, &s.rays[size_t(at)], &s.active[size_t(at)],
                                        &s.lanes[size_t(at)], coherent);
        if (coherence == Coherence::coherent || (coherence == Coherence::automatic && coherent)) {
            traced_alone(at, count, b, n);
        } else {
            s.blocks.push_back({b, n, at});
            s.count += count;
        }
    }
    if (s.count > 0) traced_together();
}

template <int W>
void closest_packet_task(const SceneData& scene, const Accel& accel, const Output& out,
                         Coherence coherence, size_t first, size_t last) {
    const RayArrays& rays = out.rays;
    StreamPackets<W>& s = stream_packets<W>();
    packet_task<W>(
        rays, coherence, first, last, s,
        [&](int at, int count, size_t b, size_t n) {
            const size_t a = size_t(at);
            intersect_closest_block(scene, accel, &s.rays[a], &s.active[a], &s.hits[a], count);
            store_block<W>(out, &s.hits[a], &s.active[a], b, n);
        },
        [&] {
            intersect_closest_stream(scene, accel, s.rays.data(), s.active.get(), s.hits.data(),
                                     s.count);
            for (const auto& block : s.blocks)
                store_block<W>(out, &s.hits[size_t(block.packet)], &s.active[size_t(block.packet)],
                               block.first, block.n);
        });
}

template <int W>
void any_packet_task(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                     uint8_t* out, Coherence coherence, size_t first, size_t last) {
    StreamPackets<W>& s = stream_packets<W>();
    packet_task<W>(
        rays, coherence, first, last, s,
        [&](int at, int count, size_t b, size_t n) {
            const size_t a = size_t(at);
            intersect_any_block(scene, accel, &s.rays[a], &s.active[a], &s.occluded[a], count);
            store_occluded<W>(&s.occluded[a], &s.lanes[a], b, n, out);
        },
        [&] {
            intersect_any_stream(scene, accel, s.rays.data(), s.active.get(), s.occluded.get(),
                                 s.count);
            for (const auto& block : s.blocks)
                store_occluded<W>(&s.occluded[size_t(block.packet)], &s.lanes[size_t(block.packet)],
                                  block.first, block.n, out);
        });
}

}  // namespace

void intersect_closest_batch_isa(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                                 const HitBuffers& hits, const BatchParams& params,
                                 const TriangleNormals* normals) {
    const Output out{scene, rays, hits, normals};
    run_tasks(rays.count, params.threads, [&](size_t first, size_t last) {
        if (params.path == BatchPath::packet) {
            closest_packet_task<native_width>(scene, accel, out, params.coherence, first, last);
            return;
        }
        for (size_t i = first; i < last; ++i) {
            Ray ray;
            Hit hit;
            if (read_ray(rays, i, ray)) hit = intersect_closest(scene, accel, ray);
            write_hit(out, hit, i);
        }
    });
}

void intersect_any_batch_isa(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                             uint8_t* occluded, const BatchParams& params) {
    run_tasks(rays.count, params.threads, [&](size_t first, size_t last) {
        if (params.path == BatchPath::packet) {
            any_packet_task<native_width>(scene, accel, rays, occluded, params.coherence, first,
                                          last);
            return;
        }
        for (size_t i = first; i < last; ++i) {
            Ray ray;
            occluded[i] = read_ray(rays, i, ray) && intersect_any(scene, accel, ray);
        }
    });
}

}  // namespace raylane::RAYLANE_ISA_NS
