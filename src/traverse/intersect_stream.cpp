// traverse: stream traversal (intersect_stream.h). The rays are stored once, as records of 32
// bytes read a list's W rays at a time (gather_records8); the lists of ray numbers are the only
// thing that moves between nodes. The node and triangle tests are the packet path's own
// (slab_packet.h, triangle_packet.h), so a ray's answer is the scalar path's.
#include "traverse/intersect_stream.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <new>

#include "traverse/hit_update_packet.h"
#include "traverse/intersect_packet.h"
#include "traverse/leaf_packet.h"
#include "traverse/slab_packet.h"
#include "traverse/triangle_packet.h"

namespace raylane::RAYLANE_ISA_NS {

namespace {

/// 64-byte aligned storage that only grows (the thread's buffers, reused stream after stream).
template <class T>
struct AlignedArray {
    T* data = nullptr;
    size_t size = 0;
    AlignedArray() = default;
    AlignedArray(const AlignedArray&) = delete;
    AlignedArray& operator=(const AlignedArray&) = delete;
    ~AlignedArray() { ::operator delete(data, std::align_val_t(64)); }
    void reserve(size_t n) {
        if (n <= size) return;
        ::operator delete(data, std::align_val_t(64));
        data = static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(64)));
        size = n;
    }
};

/// What a node test reads of a ray: 32 bytes, one gather_records8.
struct SlabRecord {
    float ox, oy, oz, t_min;
    float ix, iy, iz, limit;  ///< inv_dir, and the t_limit of the ray's closest hit so far
};
/// What a leaf reads besides the SlabRecord: the direction, t_max and the closest hit so far.
struct HitRecord {
    float dx, dy, dz, t_max;
    float t;
    int32_t prim, object;
    int32_t occluded;  ///< intersect_any_stream: 1 once the ray is known to be occluded
};
static_assert(sizeof(SlabRecord) == 32 && sizeof(HitRecord) == 32);

/// A stream's rays by ray number i = packet * W + lane, and room for the lists. One per thread.
struct Stream {
    AlignedArray<SlabRecord> slab;
    AlignedArray<HitRecord> hit;
    AlignedArray<float> u, v;
    AlignedArray<int32_t> ids;
    void reserve(size_t rays) {
        slab.reserve(rays), hit.reserve(rays), u.reserve(rays), v.reserve(rays);
        // the lists: the first one and the root's; per level of the top-level tree (at most
        // traversal_stack_size deep) at most two lists as long as their parent's; per level of
        // a mesh's wide tree (as deep) at most wide_arity, and room for one node's split
        // (traverse_stream_wide). Memory that is not written is not touched.
        ids.reserve(ids_needed(rays));
        ids_end = ids.data + ids_needed(rays);
    }
    static size_t ids_needed(size_t rays) {
        return rays * (2 * traversal_stack_size + wide_arity * (traversal_stack_size + 1) + 2) + 64;
    }
    const int32_t* ids_end = nullptr;  ///< end of the room the lists of this stream may use
};

thread_local Stream stream;

/// Lanes j .. j + W - 1 of a list of n ray numbers (ray 0 past the end) and the lanes in it.
template <int W>
void load_batch(const int32_t* list, int n, int j, vint<W>& idx, vmask<W>& lanes) {
    const int k = std::min(W, n - j);
    lanes = mask_from_bits<W>((1u << k) - 1u);
    if (k == W) {
        idx = load<W>(list + j);
    } else {
        alignas(64) int32_t tmp[W] = {};
        std::memcpy(tmp, list + j, sizeof(int32_t) * static_cast<size_t>(k));
        idx = load_aligned<W>(tmp);
    }
}

template <int W>
void gather_slab(const Stream& s, const vint<W>& idx, SlabPacket<W>& sr, vfloat<W>& t_min,
                 vfloat<W>& limit) {
    vfloat<W> f[8];
    gather_records8<W>(reinterpret_cast<const float*>(s.slab.data), idx, f);
    sr.org = {f[0], f[1], f[2]};
    sr.inv_dir = {f[4], f[5], f[6]};
    t_min = f[3];
    limit = f[7];
}

/// A list's W rays as a packet (t_max: -1 in lanes past the list's end) with their hits so far;
/// `open`: the lanes not known to be occluded (intersect_any_stream).
template <int W>
void gather_rays(const Stream& s, const vint<W>& idx, vmask<W> lanes, RayPacket<W>& r,
                 HitPacket<W>& h, vmask<W>& open) {
    vfloat<W> a[8], b[8];
    gather_records8<W>(reinterpret_cast<const float*>(s.slab.data), idx, a);
    gather_records8<W>(reinterpret_cast<const float*>(s.hit.data), idx, b);
    r.org = {a[0], a[1], a[2]};
    r.t_min = a[3];
    r.dir = {b[0], b[1], b[2]};
    r.t_max = select(lanes, b[3], vfloat<W>(-1.0f));
    h.t = b[4];
    h.prim = float_as_int(b[5]);
    h.object = float_as_int(b[6]);
    h.u = vfloat<W>(0.0f), h.v = vfloat<W>(0.0f);  // written back only where a hit wins
    open = mask_and(lanes, eq(float_as_int(b[7]), vint<W>(0)));
}

/// Writes back the hits of the lanes in `won` and the rays' new limits.
template <int W>
void scatter_hits(Stream& s, const vint<W>& idx, vmask<W> won, const RayPacket<W>& r,
                  const HitPacket<W>& h) {
    const vfloat<W> limit = t_limit(r, h);
    for_each_active(won, [&](int i) {
        const auto k = static_cast<size_t>(get(idx, i));
        s.slab.data[k].limit = get(limit, i);
        HitRecord& hr = s.hit.data[k];
        hr.t = get(h.t, i), hr.prim = get(h.prim, i), hr.object = get(h.object, i);
        s.u.data[k] = get(h.u, i), s.v.data[k] = get(h.v, i);
    });
}

/// The stream traversal of the top-level tree (binary) by the rays of `list` (n of them), with
/// free room for lists from `free_ids` on. The root's box is tested first. leaf(node, list, n,
/// free) gets the rays that touch a leaf. At an interior node the list is split into the rays
/// that touch each child; the child that more rays enter first goes first, the other waits on
/// the stack with its list. A ray whose limit has dropped since falls out at the next test.
template <int W, class Leaf>
void traverse_stream(const Bvh& bvh, const Stream& s, const int32_t* list, int n, int32_t* free_ids,
                     Leaf&& leaf) {
    if (bvh.nodes.empty() || n == 0) return;
    const BvhNode* nodes = bvh.nodes.data();
    auto box = [](const BvhNode& node, vec3& lo, vec3& hi) {
        lo = vec3(node.lo[0], node.lo[1], node.lo[2]);
        hi = vec3(node.hi[0], node.hi[1], node.hi[2]);
    };
    // the root
    int32_t* root = free_ids;
    assert(root + n <= s.ids_end);
    int n_root = 0;
    {
        vec3 lo, hi;
        box(nodes[0], lo, hi);
        for (int j = 0; j < n; j += W) {
            vint<W> idx;
            vmask<W> lanes;
            load_batch<W>(list, n, j, idx, lanes);
            SlabPacket<W> sr;
            vfloat<W> t_min, limit, t_near;
            gather_slab<W>(s, idx, sr, t_min, limit);
            n_root += compress_store(root + n_root, idx,
                                     intersect_slab(sr, lo, hi, t_min, limit, t_near, lanes));
        }
    }
    struct Entry {
        uint32_t node;
        int n;
        int32_t* list;
    };
    Entry stack[traversal_stack_size];
    int top = 0;
    Entry e{0, n_root, root};
    int32_t* free_top = root + n_root;
    while (e.n > 0) {
        const BvhNode& node = nodes[e.node];
        if (node.is_leaf()) {
            leaf(node, e.list, e.n, free_top);
        } else {
            // children: split the list
            const uint32_t first = e.node + 1, second = node.index;
            vec3 lo1, hi1, lo2, hi2;
            box(nodes[first], lo1, hi1);
            box(nodes[second], lo2, hi2);
            int32_t* list_first = free_top;
            int32_t* list_second = free_top + e.n;
            assert(list_second + e.n <= s.ids_end);
            int n_first = 0, n_second = 0, second_nearer = 0;
            for (int j = 0; j < e.n; j += W) {
                vint<W> idx;
                vmask<W> lanes;
                load_batch<W>(e.list, e.n, j, idx, lanes);
                SlabPacket<W> sr;
                vfloat<W> t_min, limit, near_first, near_second;
                gather_slab<W>(s, idx, sr, t_min, limit);
                const vmask<W> hit_first =
                    intersect_slab(sr, lo1, hi1, t_min, limit, near_first, lanes);
                const vmask<W> hit_second =
                    intersect_slab(sr, lo2, hi2, t_min, limit, near_second, lanes);
                n_first += compress_store(list_first + n_first, idx, hit_first);
                n_second += compress_store(list_second + n_second, idx, hit_second);
                const vmask<W> both = mask_and(hit_first, hit_second);
                second_nearer += count(mask_and(both, near_second < near_first)) -
                                 count(mask_and(both, near_first < near_second));
            }
            if (n_first > 0 && n_second > 0) {
                if (second_nearer > 0) {
                    stack[top++] = {first, n_first, list_first};
                    e = {second, n_second, list_second};
                } else {
                    stack[top++] = {second, n_second, list_second};
                    e = {first, n_first, list_first};
                }
                free_top = list_second + n_second;
                continue;
            }
            if (n_first > 0 || n_second > 0) {
                e = n_first > 0 ? Entry{first, n_first, list_first}
                                : Entry{second, n_second, list_second};
                free_top = e.list + e.n;
                continue;
            }
        }
        if (top == 0) break;
        // the lists above the popped one belong to finished subtrees
        e = stack[--top];
        free_top = e.list + e.n;
    }
}

/// The stream traversal of one mesh's wide tree by the rays of `list` (n of them, all of
/// which reach its root node), with free room for lists from `free_ids` on. At a wide node the
/// list is split into the rays that enter each slot (a ray may enter several): first into
/// regions of n each past the room the lists need, then moved below them in the order they
/// will be popped, so that the lists above a popped one always belong to finished slots. The
/// slot whose rays enter nearest on average goes first. leaf(ref, list, n) gets the rays of a
/// leaf slot; a list of at most W rays goes on as one packet: small(ref, list, n).
template <int W, class Leaf, class Small>
void traverse_stream_wide(const WideBvh& wide, const Stream& s, const int32_t* list, int n,
                          int32_t* free_ids, Leaf&& leaf, Small&& small) {
    if (wide.nodes.empty() || n == 0) return;
    struct Entry {
        WideRef ref;
        int n;
        const int32_t* list;
    };
    Entry stack[wide_stack_size];
    int top = 0;
    Entry e{WideRef{}, n, list};
    int32_t* free_top = free_ids;
    for (;;) {
        if (e.ref.count > 0) {
            leaf(e.ref, e.list, e.n);
        } else if (e.n <= W) {
            small(e.ref, e.list, e.n);
        } else {
            // the slots' lists, each in a region of e.n past the room the lists need
            const WideNode& node = wide.nodes[e.ref.child];
            const int slots = node.children;
            int32_t* region = free_top + slots * e.n;
            assert(region + slots * e.n <= s.ids_end);
            int count_of[wide_arity] = {};
            float near_sum[wide_arity] = {};
            for (int j = 0; j < e.n; j += W) {
                vint<W> idx;
                vmask<W> lanes;
                load_batch<W>(e.list, e.n, j, idx, lanes);
                SlabPacket<W> sr;
                vfloat<W> t_min, limit;
                gather_slab<W>(s, idx, sr, t_min, limit);
                for (int k = 0; k < slots; ++k) {
                    vfloat<W> near;
                    const vmask<W> h =
                        intersect_slab(sr, vec3(node.lo[0][k], node.lo[1][k], node.lo[2][k]),
                                       vec3(node.hi[0][k], node.hi[1][k], node.hi[2][k]), t_min,
                                       limit, near, lanes);
                    count_of[k] += compress_store(region + k * e.n + count_of[k], idx, h);
                    near_sum[k] += hsum(select(h, near, vfloat<W>(0.0f)));
                }
            }
            // the slots entered, nearest (by mean entry distance) first
            int order[wide_arity], entered = 0;
            float mean[wide_arity];
            for (int k = 0; k < slots; ++k) {
                if (count_of[k] == 0) continue;
                mean[k] = near_sum[k] / float(count_of[k]);
                int at = entered++;
                for (; at > 0 && mean[order[at - 1]] > mean[k]; --at) order[at] = order[at - 1];
                order[at] = k;
            }
            // the lists below the regions, farthest first: the nearest is on top
            int32_t* out = free_top;
            for (int i = entered - 1; i >= 0; --i) {
                const int k = order[i];
                std::memcpy(out, region + k * e.n, sizeof(int32_t) * size_t(count_of[k]));
                stack[top++] = {{node.child[k], node.count[k]}, count_of[k], out};
                out += count_of[k];
            }
        }
        if (top == 0) break;
        // the lists above the popped one (in the free room, as every pushed list) belong to
        // finished slots
        e = stack[--top];
        free_top = free_ids + (e.list + e.n - free_ids);
    }
}

/// Fills the stream from the packets and writes the active lanes' ray numbers to `list` (the
/// inactive lanes' records are filled too, with a limit of -infinity, but never listed);
/// returns how many there are.
template <int W>
int fill_stream(Stream& s, const RayPacket<W>* rays, const vmask<W>* active,
                const HitPacket<W>* hits, int count, int32_t* list) {
    int n = 0;
    for (int p = 0; p < count; ++p) {
        const RayPacket<W>& r = rays[p];
        const HitPacket<W> hit = hits ? hits[p] : HitPacket<W>{};
        const SlabPacket<W> sr = make_slab_ray(r);
        const vfloat<W> limit = select(active[p], t_limit(r, hit), vfloat<W>(-infinity));
        // the packet's fields as rows of W floats, then one record per lane
        const vfloat<W> slab_fields[8] = {r.org.x,      r.org.y,      r.org.z,      r.t_min,
                                          sr.inv_dir.x, sr.inv_dir.y, sr.inv_dir.z, limit};
        const vfloat<W> hit_fields[8] = {r.dir.x,
                                         r.dir.y,
                                         r.dir.z,
                                         r.t_max,
                                         hit.t,
                                         int_as_float(hit.prim),
                                         int_as_float(hit.object),
                                         vfloat<W>(0.0f)};
        alignas(64) float rows[16][W];
        for (int c = 0; c < 8; ++c) {
            store_aligned(rows[c], slab_fields[c]);
            store_aligned(rows[8 + c], hit_fields[c]);
        }
        for (int i = 0; i < W; ++i) {
            const auto k = static_cast<size_t>(p * W + i);
            float* slab_record = reinterpret_cast<float*>(&s.slab.data[k]);
            float* hit_record = reinterpret_cast<float*>(&s.hit.data[k]);
            for (int c = 0; c < 8; ++c) slab_record[c] = rows[c][i], hit_record[c] = rows[8 + c][i];
        }
        store(s.u.data + p * W, hit.u);
        store(s.v.data + p * W, hit.v);
        n += compress_store(list + n, vint<W>(p * W) + lane_index<W>(), active[p]);
    }
    return n;
}

/// A mesh's leaf for the rays of a list, W at a time.
template <int W>
void stream_leaf(Stream& s, const MeshAccel& mesh, uint32_t object, WideRef leaf,
                 const int32_t* list, int n) {
    for (int j = 0; j < n; j += W) {
        vint<W> idx;
        vmask<W> lanes;
        load_batch<W>(list, n, j, idx, lanes);
        RayPacket<W> r;
        HitPacket<W> h;
        vmask<W> open;  // (for occlusion queries)
        gather_rays<W>(s, idx, lanes, r, h, open);
        const WatertightPacket<W> wr = make_watertight_ray(r, lanes);
        vfloat<W> limit = t_limit(r, h);
        const vmask<W> won = leaf_closest(leaf_tris(mesh, leaf), object, wr, r, lanes, limit, h);
        if (any(won)) scatter_hits(s, idx, won, r, h);
    }
}

/// Any object for the rays of a list, W at a time, through intersect_object_closest_from (a
/// mesh from slot `start` of its wide tree, which the rays were listed for, or from its root).
template <int W>
void stream_object(Stream& s, const SceneData& scene, const Accel& accel, uint32_t object,
                   const int32_t* list, int n, WideRef start) {
    for (int j = 0; j < n; j += W) {
        vint<W> idx;
        vmask<W> lanes;
        load_batch<W>(list, n, j, idx, lanes);
        RayPacket<W> r;
        HitPacket<W> h;
        vmask<W> open;  // (for occlusion queries)
        gather_rays<W>(s, idx, lanes, r, h, open);
        const vfloat<W> t_before = h.t;
        const vint<W> prim_before = h.prim, object_before = h.object;
        intersect_object_closest_from(scene, accel, object, r, lanes, h, start);
        const vmask<W> same_id = mask_and(eq(h.prim, prim_before), eq(h.object, object_before));
        const vmask<W> won = mask_and(lanes, mask_or(ne(h.t, t_before), mask_not(same_id)));
        if (any(won)) scatter_hits(s, idx, won, r, h);
    }
}

/// Marks the lanes in `found` occluded: their limit drops to -infinity (no test passes them
/// any more) and their hit record says so.
template <int W>
void mark_occluded(Stream& s, const vint<W>& idx, vmask<W> found) {
    for_each_active(found, [&](int i) {
        const auto k = static_cast<size_t>(get(idx, i));
        s.slab.data[k].limit = -infinity;
        s.hit.data[k].occluded = 1;
    });
}

/// The any-hit leaf: the open rays of a list against a mesh leaf's triangles, W at a time.
template <int W>
void stream_leaf_any(Stream& s, const MeshAccel& mesh, WideRef leaf, const int32_t* list, int n) {
    for (int j = 0; j < n; j += W) {
        vint<W> idx;
        vmask<W> lanes;
        load_batch<W>(list, n, j, idx, lanes);
        RayPacket<W> r;
        HitPacket<W> h;
        vmask<W> open;
        gather_rays<W>(s, idx, lanes, r, h, open);
        if (none(open)) continue;
        const WatertightPacket<W> wr = make_watertight_ray(r, open);
        const vmask<W> found = leaf_any(leaf_tris(mesh, leaf), wr, r, open);
        if (any(found)) mark_occluded<W>(s, idx, found);
    }
}

/// Any object for the open rays of a list, W at a time (a mesh from slot `start`).
template <int W>
void stream_object_any(Stream& s, const SceneData& scene, const Accel& accel, uint32_t object,
                       const int32_t* list, int n, WideRef start) {
    for (int j = 0; j < n; j += W) {
        vint<W> idx;
        vmask<W> lanes;
        load_batch<W>(list, n, j, idx, lanes);
        RayPacket<W> r;
        HitPacket<W> h;
        vmask<W> open;
        gather_rays<W>(s, idx, lanes, r, h, open);
        if (none(open)) continue;
        const vmask<W> found = intersect_object_any_from(scene, accel, object, r, open, start);
        if (any(found)) mark_occluded<W>(s, idx, found);
    }
}

/// Both levels for the listed rays: the top-level BVH, then at each of its leaves every object
/// (a mesh by its own BVH), closest hits or occlusion (`any_hit`: shadow casters only).
template <bool any_hit, int W>
void traverse_scene(Stream& s, const SceneData& scene, const Accel& accel, int32_t* list, int n) {
    traverse_stream<W>(
        accel.top, s, list, n, list + n,
        [&](const BvhNode& top_leaf, const int32_t* tl, int tn, int32_t* free_ids) {
            for (uint32_t k = top_leaf.index; k < top_leaf.index + top_leaf.count; ++k) {
                const uint32_t object = accel.top.prim_ids[k];
                const Object& o = scene.objects[object];
                if (any_hit && !o.casts_shadows) continue;
                // the object for a list of rays, a mesh from slot `start`
                auto whole = [&](const int32_t* ll, int ln, WideRef start) {
                    if constexpr (any_hit)
                        stream_object_any<W>(s, scene, accel, object, ll, ln, start);
                    else
                        stream_object<W>(s, scene, accel, object, ll, ln, start);
                };
                if (o.kind != ShapeKind::mesh) {
                    whole(tl, tn, WideRef{});
                    continue;
                }
                const MeshAccel& mesh = accel.meshes[o.shape];
                traverse_stream_wide<W>(
                    mesh.wide, s, tl, tn, free_ids,
                    [&](WideRef leaf, const int32_t* ll, int ln) {
                        if constexpr (any_hit)
                            stream_leaf_any<W>(s, mesh, leaf, ll, ln);
                        else
                            stream_leaf<W>(s, mesh, object, leaf, ll, ln);
                    },
                    [&](WideRef start, const int32_t* ll, int ln) { whole(ll, ln, start); });
            }
        });
}

}  // namespace

template <int W>
void intersect_closest_stream(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                              const vmask<W>* active, HitPacket<W>* hits, int count) {
    for (int p = 0; p < count; ++p) hits[p] = HitPacket<W>{};
    if (count <= 0) return;
    assert(static_cast<int64_t>(count) * W <= max_stream_rays);
    for (uint32_t object : accel.unbounded)
        for (int p = 0; p < count; ++p)
            if (any(active[p]))
                intersect_object_closest_from(scene, accel, object, rays[p], active[p], hits[p]);
    if (accel.top.nodes.empty()) return;
    Stream& s = stream;
    const auto n_rays = static_cast<size_t>(count) * W;
    s.reserve(n_rays);
    int32_t* list = s.ids.data;
    const int n = fill_stream(s, rays, active, hits, count, list);
    traverse_scene<false, W>(s, scene, accel, list, n);
    // the hits back into the packets
    for (int p = 0; p < count; ++p) {
        alignas(64) float t[W];
        alignas(64) int32_t prim[W], object[W];
        for (int i = 0; i < W; ++i) {
            const HitRecord& hr = s.hit.data[p * W + i];
            t[i] = hr.t, prim[i] = hr.prim, object[i] = hr.object;
        }
        hits[p].t = load_aligned<W>(t);
        hits[p].prim = load_aligned<W>(prim);
        hits[p].object = load_aligned<W>(object);
        hits[p].u = load<W>(s.u.data + p * W);
        hits[p].v = load<W>(s.v.data + p * W);
    }
}

template <int W>
void intersect_any_stream(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                          const vmask<W>* active, vmask<W>* occluded, int count) {
    for (int p = 0; p < count; ++p) {
        occluded[p] = mask_and(active[p], mask_not(active[p]));
        for (uint32_t object : accel.unbounded) {
            const vmask<W> open = mask_andnot(active[p], occluded[p]);
            if (any(open))
                occluded[p] = mask_or(
                    occluded[p], intersect_object_any_from(scene, accel, object, rays[p], open));
        }
    }
    if (count <= 0 || accel.top.nodes.empty()) return;
    assert(static_cast<int64_t>(count) * W <= max_stream_rays);
    Stream& s = stream;
    s.reserve(static_cast<size_t>(count) * W);
    // occluded[p] holds the open lanes until the end (active, not occluded by an unbounded
    // object): they go into the stream, and no buffer is allocated for them
    for (int p = 0; p < count; ++p) occluded[p] = mask_andnot(active[p], occluded[p]);
    int32_t* list = s.ids.data;
    const int n = fill_stream<W>(s, rays, occluded, nullptr, count, list);
    traverse_scene<true, W>(s, scene, accel, list, n);
    // the occluded lanes: those an unbounded object occludes (active, not open) and those the
    // stream found (open, and marked)
    for (int p = 0; p < count; ++p) {
        uint32_t found = 0;
        for (int i = 0; i < W; ++i) found |= uint32_t(s.hit.data[p * W + i].occluded) << i;
        const vmask<W> open = occluded[p];
        occluded[p] =
            mask_or(mask_andnot(active[p], open), mask_and(open, mask_from_bits<W>(found)));
    }
}

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W)                                                                     \
    template void intersect_closest_stream<W>(const SceneData&, const Accel&, const RayPacket<W>*, \
                                              const vmask<W>*, HitPacket<W>*, int);                \
    template void intersect_any_stream<W>(const SceneData&, const Accel&, const RayPacket<W>*,     \
                                          const vmask<W>*, vmask<W>*, int);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE

}  // namespace raylane::RAYLANE_ISA_NS
