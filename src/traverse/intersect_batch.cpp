// traverse: queries of a caller's ray arrays over threads (intersect_batch.h).
#include "traverse/intersect_batch.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/ray_packet.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_scalar.h"
#include "traverse/intersect_stream.h"
#include "traverse/triangle_scalar.h"

namespace raylane {
namespace {

/// Flush-to-zero and denormals-are-zero (numerics.md §0.2) for a task; the thread's own modes
/// come back afterwards (a task may run on the caller's thread).
struct FlushToZero {
    unsigned saved = _mm_getcsr();
    FlushToZero() { _mm_setcsr(saved | 0x8040u); }
    ~FlushToZero() { _mm_setcsr(saved); }
    FlushToZero(const FlushToZero&) = delete;
    FlushToZero& operator=(const FlushToZero&) = delete;
};

/// Ray i, and whether it is traced: finite origin and direction, a direction that is not zero,
/// and t_max > 0.
bool read_ray(const RayArrays& rays, size_t i, Ray& ray) {
    const float* o = rays.org + i * rays.org_stride;
    const float* d = rays.dir + i * rays.dir_stride;
    ray.org = vec3(o[0], o[1], o[2]);
    ray.dir = vec3(d[0], d[1], d[2]);
    ray.t_min = 0.0f;
    ray.t_max = rays.t_max ? rays.t_max[i] : rays.t_max_all;
    const bool finite = std::isfinite(o[0]) && std::isfinite(o[1]) && std::isfinite(o[2]) &&
                        std::isfinite(d[0]) && std::isfinite(d[1]) && std::isfinite(d[2]);
    return finite && ray.dir != vec3(0.0f) && ray.t_max > 0.0f;
}

/// The geometric normal surface_at gives, straight from the triangle's corners for a mesh.
vec3 geometric_normal(const Scene& scene, const Ray& ray, const Hit& hit) {
    if (!hit.hit()) return vec3(0.0f);
    const Object& object = scene.objects[hit.object];
    if (object.kind != ShapeKind::mesh) return surface_at(scene, ray, hit).geometric_normal;
    const Mesh& mesh = scene.meshes[object.shape];
    const glm::uvec3 tri = mesh.tris[hit.prim];
    return geometry_triangle<float>(mesh.positions[tri.x], mesh.positions[tri.y],
                                    mesh.positions[tri.z], hit.uv.x, hit.uv.y)
        .normal;
}

void write_hit(const Scene& scene, const Ray& ray, const Hit& hit, size_t i,
               const HitBuffers& out) {
    if (out.t) out.t[i] = hit.t;
    if (out.prim) out.prim[i] = static_cast<int32_t>(hit.prim);
    if (out.object) out.object[i] = static_cast<int32_t>(hit.object);
    if (out.u) out.u[i] = hit.uv.x;
    if (out.v) out.v[i] = hit.uv.y;
    if (out.normal) {
        const vec3 n = geometric_normal(scene, ray, hit);
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
            FlushToZero ftz;
            body(k * batch_task_rays, std::min(count, (k + 1) * batch_task_rays));
        });
    });
}

/// Packets of rays first .. first + n - 1 (n <= max_block_rays): ceil(n / W) packets, lanes of
/// rays that are not traced inactive with a benign ray. Returns the packet count.
template <int W>
int load_block(const RayArrays& rays, size_t first, size_t n, RayPacket<W>* packets,
               vmask<W>* active, uint32_t* lanes) {
    alignas(64) float c[7][max_block_rays];
    const int count = static_cast<int>((n + W - 1) / W);
    for (int p = 0; p < count; ++p) lanes[p] = 0;
    for (size_t k = 0; k < size_t(count) * W; ++k) {
        Ray ray;
        const bool traced = k < n && read_ray(rays, first + k, ray);
        if (!traced) ray = Ray{vec3(0.0f), vec3(0.0f, 0.0f, 1.0f), 0.0f, -1.0f};
        const float f[7] = {ray.org.x, ray.org.y, ray.org.z, ray.dir.x,
                            ray.dir.y, ray.dir.z, ray.t_max};
        for (int j = 0; j < 7; ++j) c[j][k] = f[j];
        if (traced) lanes[k / W] |= 1u << (k % W);
    }
    for (int p = 0; p < count; ++p) {
        const size_t o = size_t(p) * W;
        packets[p].org = load_vec3<W>(&c[0][o], &c[1][o], &c[2][o]);
        packets[p].dir = load_vec3<W>(&c[3][o], &c[4][o], &c[5][o]);
        packets[p].t_min = vfloat<W>(0.0f);
        packets[p].t_max = load<W>(&c[6][o]);
        active[p] = mask_from_bits<W>(lanes[p]);
    }
    return count;
}

/// Writes the hits of a block loaded by load_block.
template <int W>
void store_block(const Scene& scene, const RayArrays& rays, const HitPacket<W>* hits,
                 const uint32_t* lanes, size_t first, size_t n, const HitBuffers& out) {
    for (size_t k = 0; k < n; ++k) {
        const size_t p = k / W;
        const int lane = static_cast<int>(k % W);
        Ray ray;
        read_ray(rays, first + k, ray);
        Hit hit;
        if ((lanes[p] >> lane) & 1u) hit = get_hit(hits[p], lane);
        write_hit(scene, ray, hit, first + k, out);
    }
}

template <int W>
void store_occluded(const vmask<W>* occluded, const uint32_t* lanes, size_t first, size_t n,
                    uint8_t* out) {
    for (size_t k = 0; k < n; ++k) {
        const size_t p = k / W;
        const uint32_t lane = static_cast<uint32_t>(k % W);
        out[first + k] = static_cast<uint8_t>((bits(occluded[p]) & lanes[p]) >> lane & 1u);
    }
}

/// A task's stream: the packets of its incoherent blocks, and where each block's rays are.
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
    std::vector<Block> blocks;
    int count = 0;
    size_t capacity = 0;

    StreamPackets() {
        constexpr size_t packets = (batch_task_rays + W - 1) / W;
        rays.resize(packets), hits.resize(packets), lanes.resize(packets);
        active.reset(new vmask<W>[packets]);
        occluded.reset(new vmask<W>[packets]);
    }
    void add(const RayArrays& r, size_t first, size_t n) {
        blocks.push_back({first, n, count});
        count += load_block<W>(r, first, n, &rays[size_t(count)], &active[size_t(count)],
                               &lanes[size_t(count)]);
    }
    void clear() { count = 0, blocks.clear(); }
};

template <int W>
StreamPackets<W>& stream_packets() {
    thread_local StreamPackets<W> s;
    return s;
}

bool as_block(const RayArrays& rays, size_t first, size_t n, Coherence coherence) {
    return coherence == Coherence::coherent ||
           (coherence == Coherence::automatic && rays_coherent(rays, first, n));
}

template <int W>
void closest_packet_task(const Scene& scene, const Accel& accel, const RayArrays& rays,
                         const HitBuffers& out, Coherence coherence, size_t first, size_t last) {
    constexpr int per_block = max_block_rays / W;
    StreamPackets<W>& stream = stream_packets<W>();
    stream.clear();
    for (size_t b = first; b < last; b += max_block_rays) {
        const size_t n = std::min<size_t>(max_block_rays, last - b);
        if (!as_block(rays, b, n, coherence)) {
            stream.add(rays, b, n);
            continue;
        }
        RayPacket<W> packets[per_block];
        vmask<W> active[per_block];
        HitPacket<W> hits[per_block];
        uint32_t lanes[per_block];
        const int count = load_block<W>(rays, b, n, packets, active, lanes);
        intersect_closest_block(scene, accel, packets, active, hits, count);
        store_block<W>(scene, rays, hits, lanes, b, n, out);
    }
    if (stream.count == 0) return;
    intersect_closest_stream(scene, accel, stream.rays.data(), stream.active.get(),
                             stream.hits.data(), stream.count);
    for (const auto& block : stream.blocks)
        store_block<W>(scene, rays, &stream.hits[size_t(block.packet)],
                       &stream.lanes[size_t(block.packet)], block.first, block.n, out);
}

template <int W>
void any_packet_task(const Scene& scene, const Accel& accel, const RayArrays& rays, uint8_t* out,
                     Coherence coherence, size_t first, size_t last) {
    constexpr int per_block = max_block_rays / W;
    StreamPackets<W>& stream = stream_packets<W>();
    stream.clear();
    for (size_t b = first; b < last; b += max_block_rays) {
        const size_t n = std::min<size_t>(max_block_rays, last - b);
        if (!as_block(rays, b, n, coherence)) {
            stream.add(rays, b, n);
            continue;
        }
        RayPacket<W> packets[per_block];
        vmask<W> active[per_block], occluded[per_block];
        uint32_t lanes[per_block];
        const int count = load_block<W>(rays, b, n, packets, active, lanes);
        intersect_any_block(scene, accel, packets, active, occluded, count);
        store_occluded<W>(occluded, lanes, b, n, out);
    }
    if (stream.count == 0) return;
    intersect_any_stream(scene, accel, stream.rays.data(), stream.active.get(),
                         stream.occluded.get(), stream.count);
    for (const auto& block : stream.blocks)
        store_occluded<W>(&stream.occluded[size_t(block.packet)],
                          &stream.lanes[size_t(block.packet)], block.first, block.n, out);
}

}  // namespace

bool rays_coherent(const RayArrays& rays, size_t first, size_t count) {
    vec3 first_dir{0.0f};
    bool have_first = false;
    for (size_t i = first; i < first + count; ++i) {
        Ray ray;
        if (!read_ray(rays, i, ray)) continue;
        const vec3 d = glm::normalize(ray.dir);
        if (!have_first) {
            first_dir = d, have_first = true;
        } else if (!(glm::dot(d, first_dir) >= 0.9f)) {
            return false;
        }
    }
    return true;
}

void intersect_closest_batch(const Scene& scene, const Accel& accel, const RayArrays& rays,
                             const HitBuffers& hits, const BatchParams& params) {
    run_tasks(rays.count, params.threads, [&](size_t first, size_t last) {
        if (params.path == BatchPath::packet) {
            closest_packet_task<native_width>(scene, accel, rays, hits, params.coherence, first,
                                              last);
            return;
        }
        for (size_t i = first; i < last; ++i) {
            Ray ray;
            Hit hit;
            if (read_ray(rays, i, ray)) hit = intersect_closest(scene, accel, ray);
            write_hit(scene, ray, hit, i, hits);
        }
    });
}

void intersect_any_batch(const Scene& scene, const Accel& accel, const RayArrays& rays,
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

}  // namespace raylane
