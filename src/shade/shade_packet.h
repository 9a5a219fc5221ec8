// shade: the packet path's shading kernels. shade_hits shades W hits of one material at a time
// (grouped by a counting sort in the wavefront, by object in a camera packet when the scene has
// no secondary rays; docs/architecture.md): the terms of shade_scalar.cpp (local
// lights and lobes, glossy, mirror, glass with Beer's law), but instead of recursing, new rays go
// to queues - shadow rays per light, secondary rays to the next pass - carrying the weight their
// radiance gets in the pixel. Compiled per feature set F (features.h): a scene pays only for
// the features it uses. Header-only: instantiated by render/render_packet.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh.h"
#include "core/offset_packet.h"
#include "core/ray_packet.h"
#include "render/path_queue.h"
#include "scene/features.h"
#include "scene/mesh_normals.h"
#include "scene/scene.h"
#include "shade/brdf_packet.h"
#include "shade/lights_packet.h"
#include "shade/shade_scalar.h"
#include "shade/texture_packet.h"
#include "simd/hash.h"
#include "simd/lanes.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"

namespace raylane {

/// Closest hits of a PathQueue's rays, one array per field (index = ray).
struct HitArrays {
    std::vector<float> t, u, v;
    std::vector<int32_t> prim, object;
    void resize(size_t n) {
        if (t.size() >= n) return;
        for (auto* a : {&t, &u, &v}) a->resize(n);
        prim.resize(n), object.resize(n);
    }
};

/// What a batch writes to: the radiance per wavefront slot (one sample of one pixel), the shadow
/// queues (one per light) and the next pass's queue.
struct ShadeTarget {
    float* acc_r = nullptr;
    float* acc_g = nullptr;
    float* acc_b = nullptr;
    ShadowQueue* shadows = nullptr;
    PathQueue* next = nullptr;
    /// Rays that travel inside a refractive medium (refracted in, reflected inside): kept apart
    /// from `next` and traced after it, so that a packet holds rays of one kind (a refracted ray
    /// crosses the mesh, a reflected one leaves it: mixed in a packet, their lanes part at once).
    PathQueue* next_inside = nullptr;
    ShadeCounts* counts = nullptr;
};

/// One light sample's shadow rays of a block of camera packets, kept in their packets (the
/// one-pass kernels): ray, contribution if unoccluded, and the lanes that have one.
template <int W>
struct ShadowBlock {
    RayPacket<W> rays[max_block_rays / W];
    Vec3<W> contribution[max_block_rays / W];
    vmask<W> lanes[max_block_rays / W];
};

/// What a batch writes to in the one-pass kernels (no secondary rays): the radiance of camera
/// packet `packet` in registers and its shadow rays in place, one ShadowBlock per light sample
/// (light j's samples from shadow_first[j] on).
template <int W>
struct PacketTarget {
    Vec3<W>* value = nullptr;
    ShadowBlock<W>* shadows = nullptr;
    const int* shadow_first = nullptr;
    int packet = 0;
    ShadeCounts* counts = nullptr;
};

namespace shade_detail {

/// v[idx[i]] for the first k lanes (the others get `fill`); idx has room for W entries.
template <int W>
inline vfloat<W> gather_lanes(const std::vector<float>& v, const vint<W>& idx, vmask<W> m,
                              float fill) {
    return select(m, gather(v.data(), idx, m), vfloat<W>(fill));
}
template <int W>
inline vint<W> gather_lanes(const std::vector<int32_t>& v, const vint<W>& idx, vmask<W> m,
                            int32_t fill) {
    const vfloat<W> bits = gather(reinterpret_cast<const float*>(v.data()), idx, m);
    return select(m, float_as_int(bits), vint<W>(fill));
}

template <int W>
inline Vec3<W> bc(vec3 v) {
    return make_vec3<W>(v.x, v.y, v.z);
}

/// Adds value * weight to the lanes' pixel slots (lanes may share a slot: one at a time).
template <int W>
inline void accumulate(const ShadeTarget& out, const vint<W>& slot, const Vec3<W>& value,
                       vmask<W> m) {
    for_each_active(m, [&](int i) {
        const size_t s = static_cast<size_t>(get(slot, i));
        out.acc_r[s] += get(value.x, i);
        out.acc_g[s] += get(value.y, i);
        out.acc_b[s] += get(value.z, i);
    });
}

/// The same for one camera packet's registers: its lanes are distinct pixels.
template <int W>
inline void accumulate(const PacketTarget<W>& out, const vint<W>&, const Vec3<W>& value,
                       vmask<W> m) {
    *out.value = select(m, *out.value + value, *out.value);
}

/// Queues the `lit` lanes' shadow rays towards sample i of light j (contribution added if the
/// segment is free).
template <int W>
inline void add_shadow_rays(const ShadeTarget& out, size_t j, int, const Vec3<W>& origin,
                            const Vec3<W>& dir, const vfloat<W>& distance,
                            const Vec3<W>& contribution, const vint<W>& slot, vmask<W> lit) {
    push_packet<W>(out.shadows[j], origin, dir, distance, contribution, slot, lit);
}
template <int W>
inline void add_shadow_rays(const PacketTarget<W>& out, size_t j, int i, const Vec3<W>& origin,
                            const Vec3<W>& dir, const vfloat<W>& distance,
                            const Vec3<W>& contribution, const vint<W>&, vmask<W> lit) {
    ShadowBlock<W>& b = out.shadows[out.shadow_first[j] + i];
    const int p = out.packet;
    const RayPacket<W> r{origin, dir, vfloat<W>(0.0f), distance};
    if (none(b.lanes[p])) {  // the packet's first batch for this sample: every lane written
        b.rays[p] = r;
        b.contribution[p] = contribution;
        b.lanes[p] = lit;
        return;
    }
    b.rays[p].org = select(lit, r.org, b.rays[p].org);
    b.rays[p].dir = select(lit, r.dir, b.rays[p].dir);
    b.rays[p].t_max = select(lit, r.t_max, b.rays[p].t_max);
    b.contribution[p] = select(lit, contribution, b.contribution[p]);
    b.lanes[p] = mask_or(b.lanes[p], lit);
}

template <int W>
inline vfloat<W> random_at(const vint<W>& pixel, const vint<W>& sample, uint32_t seed,
                           const vint<W>& key, uint32_t purpose, uint32_t index, uint32_t coord) {
    // path_dim of core/rng.h, lane-wise
    const vint<W> salt = hash_u32<W>(broadcast<W>((purpose << 28) ^ (index << 2) ^ coord));
    const vint<W> dim = hash_u32<W>(key ^ salt) | broadcast<W>(0x80000000u);
    return random_float<W>(pixel, sample, dim, broadcast<W>(seed));
}

template <int W>
inline vint<W> child_keys(const vint<W>& key, uint32_t purpose, uint32_t index) {
    const vint<W> salt = hash_u32<W>(broadcast<W>((purpose << 28) ^ index ^ 0x68e31da4u));
    return hash_u32<W>(key ^ salt);
}

}  // namespace shade_detail

/// miss_radiance of shade_scalar.h for W rays: each lane's map (`env_map`, else the scene's
/// environment), else the background.
template <int W>
inline Vec3<W> miss_radiance(const Scene& scene, const vint<W>& env_map, const Vec3<W>& dir,
                             vmask<W> active) {
    const vint<W> map = select(lt(env_map, vint<W>(0)), vint<W>(scene.environment), env_map);
    Vec3<W> out = shade_detail::bc<W>(scene.background);
    // one look-up per distinct map among the lanes (almost always one)
    vmask<W> todo = mask_andnot(active, lt(map, vint<W>(0)));
    while (any(todo)) {
        const int32_t t = get(map, first_active(todo));
        const vmask<W> same = mask_and(todo, eq(map, vint<W>(t)));
        out = select(same, environment_lookup<W>(scene.textures[size_t(t)], dir, same), out);
        todo = mask_andnot(todo, same);
    }
    return out;
}

/// What shading needs of W rays and their closest hits, in registers (the fields of a PathQueue
/// entry, its hit, and the pixel and sample indices that key its random numbers).
template <int W>
struct ShadeInput {
    RayPacket<W> rays;
    HitPacket<W> hits;
    Vec3<W> weight;
    vint<W> slot, key, refl_depth, refr_depth, env, pixel;
    vint<W> sample;  ///< the sample index of each lane's path (its random numbers)
    vmask<W> local_only;
};

/// A wavefront holds several samples of a tile's pixels: sample j of its batch at tile slot i (a
/// pixel of the tile) is wavefront slot j * max_block_rays + i.
inline constexpr int tile_slot_bits = 8;
static_assert(max_block_rays == 1 << tile_slot_bits);

/// What a wavefront's slots stand for: the image pixel of each tile slot, and the sample index of
/// the batch's first sample (slot s is sample first_sample + s / max_block_rays).
struct SlotMap {
    const int32_t* pixel = nullptr;
    int32_t first_sample = 0;
};

/// Queue entries idx[0..k) of `q` with their hits `h` as shading input (gathers); `slots` maps
/// a slot to its pixel and sample. Lanes from k on are inactive.
template <int W>
inline ShadeInput<W> gather_shade_input(const PathQueue& q, const HitArrays& h,
                                        const SlotMap& slots, const int32_t* idx, vmask<W> active) {
    using namespace shade_detail;
    vint<W> ids;
    if constexpr (W == 1) {
        ids = idx[0];
    } else {
        ids = load<W>(idx);  // idx has room for W entries; lanes past k are masked
    }
    ShadeInput<W> in;
    in.rays.org = {gather_lanes<W>(q.ox, ids, active, 0.0f),
                   gather_lanes<W>(q.oy, ids, active, 0.0f),
                   gather_lanes<W>(q.oz, ids, active, 0.0f)};
    in.rays.dir = {gather_lanes<W>(q.dx, ids, active, 0.0f),
                   gather_lanes<W>(q.dy, ids, active, 0.0f),
                   gather_lanes<W>(q.dz, ids, active, 1.0f)};
    in.hits.t = gather_lanes<W>(h.t, ids, active, 0.0f);
    in.hits.u = gather_lanes<W>(h.u, ids, active, 0.0f);
    in.hits.v = gather_lanes<W>(h.v, ids, active, 0.0f);
    in.hits.prim = gather_lanes<W>(h.prim, ids, active, int32_t{-1});
    in.hits.object = gather_lanes<W>(h.object, ids, active, int32_t{-1});
    in.weight = {gather_lanes<W>(q.wr, ids, active, 0.0f), gather_lanes<W>(q.wg, ids, active, 0.0f),
                 gather_lanes<W>(q.wb, ids, active, 0.0f)};
    in.slot = gather_lanes<W>(q.slot, ids, active, int32_t{0});
    in.key = gather_lanes<W>(q.key, ids, active, int32_t{0});
    in.refl_depth = gather_lanes<W>(q.reflection_depth, ids, active, int32_t{0});
    in.refr_depth = gather_lanes<W>(q.refraction_depth, ids, active, int32_t{0});
    in.env = gather_lanes<W>(q.env_map, ids, active, int32_t{-1});
    in.local_only =
        mask_andnot(active, eq(gather_lanes<W>(q.local_only, ids, active, int32_t{0}), vint<W>(0)));
    const vint<W> tile_slot = in.slot & vint<W>(max_block_rays - 1);
    in.pixel = float_as_int(gather(reinterpret_cast<const float*>(slots.pixel), tile_slot, active));
    in.sample = vint<W>(slots.first_sample) + shift_right_logical<tile_slot_bits>(in.slot);
    return in;
}

/// Shades the `active` lanes of `in`, all hits of material `m`: adds their direct light and
/// ambient term to the tile's slots, and queues shadow rays (per light) and secondary rays.
/// Target: ShadeTarget (queues), or PacketTarget<W> for kernels without secondary rays.
template <int W, uint32_t F, class Target>
void shade_hits(const Scene& scene, const Material& m, const ShadeParams& params, uint32_t seed,
                const ShadeInput<W>& in, vmask<W> active, const Target& out) {
    using namespace shade_detail;
    const ShadingOptions& o = scene.shading;
    const vfloat<W> zero(0.0f), one(1.0f);
    const RayPacket<W>& rays = in.rays;
    const HitPacket<W>& hits = in.hits;
    const Vec3<W>& weight = in.weight;
    const vint<W>&slot = in.slot, &key = in.key, &pixel = in.pixel, &sample = in.sample;
    const vint<W>&refl_depth = in.refl_depth, &refr_depth = in.refr_depth, &env = in.env;
    const vmask<W> local_only = mask_and(active, in.local_only);

    if (m.emissive()) {
        accumulate<W>(out, slot, weight * bc<W>(m.emission), active);
        return;
    }

    // the shading point (shade_scalar.cpp: shading_point)
    const SurfacePacket<W> sp = surface_at(scene, rays, hits, active);
    const vfloat<W> reach = ray_reach<W>(rays, hits.t);
    const Vec3<W> view = rays.dir / sqrt(dot(rays.dir, rays.dir));
    Vec3<W> ns = sp.shading_normal;
    if constexpr ((F & feature_textures) != 0) {
        if (m.normal_map >= 0) {
            // per lane: the triangle's dp/du (meshes only; other shapes keep their normal)
            Vec3<W> dpdu = make_vec3<W>(0.0f, 0.0f, 0.0f);
            uint32_t mesh_bits = 0;
            glm::mat3 to_world(1.0f);
            for_each_active(active, [&](int i) {
                const Object& obj = scene.objects[size_t(get(hits.object, i))];
                if (obj.kind != ShapeKind::mesh) return;
                const Mesh& mesh = scene.meshes[obj.shape];
                const vec3 d = triangle_dpdu(mesh, uint32_t(get(hits.prim, i)));
                set(dpdu.x, i, d.x), set(dpdu.y, i, d.y), set(dpdu.z, i, d.z);
                to_world = mesh.normal_to_world;  // one mesh per material in practice
                mesh_bits |= 1u << i;
            });
            if (mesh_bits != 0) {
                const vmask<W> on_mesh = mask_from_bits<W>(mesh_bits);
                const Vec3<W> texel =
                    texture_lookup<W>(scene.textures[size_t(m.normal_map)], sp.u, sp.v, on_mesh);
                ns = select(on_mesh,
                            normal_from_map<W>(m.normal_map_mode, texel, ns, dpdu, to_world), ns);
            }
        }
    }
    const vmask<W> entering = mask_not(dot(sp.geometric_normal, view) > zero);
    const Vec3<W> ng = select(entering, sp.geometric_normal, -sp.geometric_normal);
    ns = select(dot(ns, ng) < zero, -ns, ns);
    ns = face_viewer<W>(keep_above<W>(ns, ng), ng, -view);
    Vec3<W> c_d = bc<W>(m.c_d), c_s = bc<W>(m.c_s);
    if constexpr ((F & feature_textures) != 0) {
        if (m.texture >= 0) {
            c_d = texture_lookup<W>(scene.textures[size_t(m.texture)], sp.u, sp.v, active);
            if (m.texture_specular) c_s = c_d;
        }
    }
    // secondary rays see the material's reflection map, else the one their path carries
    const vint<W> child_env = m.env_map >= 0 ? vint<W>(m.env_map) : env;

    // glass (shade_scalar.cpp: glass_term)
    if constexpr ((F & feature_refraction) != 0) {
        if (m.refractive) {
            const vmask<W> alive = mask_and(mask_andnot(active, local_only),
                                            lt(refr_depth, vint<W>(o.max_refraction_depth)));
            if (none(alive)) return;
            const vfloat<W> eta = select(entering, vfloat<W>(m.ior), vfloat<W>(1.0f / m.ior));
            const vfloat<W> cos_i = neg(dot(view, ns));
            Vec3<W> t_dir;
            vfloat<W> cos_t;
            // two statements: t_dir is written by refract_direction, then read
            vmask<W> refracts = refract_direction<W>(view, ns, eta, t_dir, cos_t);
            refracts = mask_and(refracts, dot(t_dir, ng) < zero);
            const vfloat<W> r = select(
                refracts, m.fresnel && o.fresnel ? fresnel_dielectric<W>(cos_i, eta, cos_t) : zero,
                one);
            const Vec3<W> reflected_dir = reflect_direction<W>(view, ns);
            const Vec3<W> org_out = offset_ray_origin(sp.position, ng, reach);
            const Vec3<W> org_in = offset_ray_origin(sp.position, -ng, reach);
            const vec3 no_filter(1.0f);
            const vmask<W> reflects = mask_and(alive, r > zero);
            if (o.override_reflected) {
                accumulate<W>(out, slot, (weight * r) * bc<W>(o.reflected_color), reflects);
            } else if (o.reflection) {
                // below the geometric surface: discarded
                const vmask<W> traced = mask_and(reflects, dot(ng, reflected_dir) > zero);
                if (any(traced)) {
                    out.counts->reflection_rays += uint64_t(count(traced));
                    const Vec3<W> filter = select(entering, bc<W>(no_filter), bc<W>(m.filter));
                    const vint<W> child = child_keys<W>(key, purpose_reflect, 0);
                    for (const bool inside : {false, true}) {
                        // reflected inside where the ray came from inside
                        const vmask<W> lanes =
                            inside ? mask_andnot(traced, entering) : mask_and(traced, entering);
                        if (any(lanes))
                            push_packet<W>(inside ? *out.next_inside : *out.next, org_out,
                                           reflected_dir, weight * r, filter, slot, child,
                                           refl_depth, refr_depth + vint<W>(1), child_env,
                                           vint<W>(0), lanes);
                    }
                }
            }
            const vmask<W> transmits = mask_and(mask_and(alive, refracts), r < one);
            if (o.refraction && any(transmits)) {
                out.counts->refraction_rays += uint64_t(count(transmits));
                const Vec3<W> filter = select(entering, bc<W>(m.filter), bc<W>(no_filter));
                const vint<W> child = child_keys<W>(key, purpose_refract, 0);
                for (const bool inside : {false, true}) {
                    // refracted inside where the ray came from outside
                    const vmask<W> lanes =
                        inside ? mask_and(transmits, entering) : mask_andnot(transmits, entering);
                    if (any(lanes))
                        push_packet<W>(inside ? *out.next_inside : *out.next, org_in, t_dir,
                                       weight * (one - r), filter, slot, child, refl_depth,
                                       refr_depth + vint<W>(1), child_env, vint<W>(0), lanes);
                }
            }
            return;
        }
    }

    // mirror weights (shade_scalar.cpp: mirror_term): the local term is scaled by 1 - R
    Vec3<W> local_weight = weight;
    const Vec3<W> origin = offset_ray_origin(sp.position, ng, reach);
    if constexpr ((F & feature_reflection) != 0) {
        if (m.reflection > 0.0f) {
            accumulate<W>(out, slot, weight * (vfloat<W>(m.k_a_after) * c_d), active);
            const vmask<W> mirror = mask_and(mask_andnot(active, local_only),
                                             lt(refl_depth, vint<W>(o.max_reflection_depth)));
            if (any(mirror)) {
                const vfloat<W> r = m.fresnel && o.fresnel
                                        ? schlick<W>(m.reflection, neg(dot(view, ns)))
                                        : vfloat<W>(m.reflection);
                local_weight = select(mirror, o.local ? weight * (one - r) : weight * zero, weight);
                const Vec3<W> mirror_weight = (weight * r) * c_s;
                if (o.override_reflected) {
                    accumulate<W>(out, slot, mirror_weight * bc<W>(o.reflected_color), mirror);
                } else if (o.reflection) {
                    const Vec3<W> dir = reflect_direction<W>(view, ns);
                    // a reflection about a mapped n_s below the geometric surface is discarded
                    const vmask<W> traced = mask_and(mirror, dot(ng, dir) > zero);
                    out.counts->reflection_rays += uint64_t(count(traced));
                    push_packet<W>(*out.next, origin, dir, mirror_weight, bc<W>(vec3(1.0f)), slot,
                                   child_keys<W>(key, purpose_mirror, 0), refl_depth + vint<W>(1),
                                   refr_depth, child_env, vint<W>(0), traced);
                }
            }
        }
    }

    // local term (shade_scalar.cpp: local_term)
    accumulate<W>(out, slot, local_weight * (vfloat<W>(m.k_a) * c_d), active);
    const BrdfScaling brdf = scene.shading.brdf;
    const Vec3<W> wo = -view;
    for (size_t j = 0; j < scene.lights.size(); ++j) {
        const Light& light = scene.lights[j];
        const int n = light_sample_count(light, params);
        const float sample_weight = 1.0f / static_cast<float>(n);
        const Vec3<W> light_color = bc<W>(light.color);
        for (int i = 0; i < n; ++i) {
            vfloat<W> u1 = zero, u2 = zero, u3 = zero;
            if constexpr ((F & feature_area_lights) != 0) {
                if (light.is_area()) {
                    const uint32_t id = static_cast<uint32_t>(j << 16 | static_cast<uint32_t>(i));
                    u1 = random_at<W>(pixel, sample, seed, key, purpose_light, id, 0);
                    u2 = random_at<W>(pixel, sample, seed, key, purpose_light, id, 1);
                    u3 = random_at<W>(pixel, sample, seed, key, purpose_light, id, 2);
                }
            }
            const LightSamplePacket<W> ls = sample_light<W>(light, origin, i, n, u1, u2, u3);
            const vmask<W> lit = mask_and(mask_and(active, ls.valid),
                                          mask_and(dot(ns, ls.dir) > zero, dot(ng, ls.dir) > zero));
            if (none(lit)) continue;
            const Vec3<W> f = diffuse_factor<W>(m, brdf, c_d, ns, ls.dir) +
                              specular_factor<W>(m, brdf, c_s, ns, ls.dir, wo);
            const Vec3<W> contribution =
                local_weight * (((vfloat<W>(sample_weight) * ls.factor) * light_color) * f);
            if (!light.shadows) {
                accumulate<W>(out, slot, contribution, lit);
                continue;
            }
            out.counts->shadow_rays += uint64_t(count(lit));
            add_shadow_rays<W>(out, j, i, origin, ls.dir, ls.distance, contribution, slot, lit);
        }
    }
    if constexpr ((F & feature_glossy) != 0) {
        if (m.model == SpecularModel::glossy_phong) {
            const vmask<W> spawn = mask_andnot(active, local_only);
            if (none(spawn)) return;
            const int n = glossy_sample_count(m, params);
            const Vec3<W> mirror = reflect_direction<W>(view, ns);
            const vfloat<W> inv_n(1.0f / static_cast<float>(n));
            for (int i = 0; i < n; ++i) {
                const uint32_t id = static_cast<uint32_t>(i);
                const vfloat<W> u1 = random_at<W>(pixel, sample, seed, key, purpose_glossy, id, 0);
                const vfloat<W> u2 = random_at<W>(pixel, sample, seed, key, purpose_glossy, id, 1);
                const Vec3<W> wi = sample_phong_lobe<W>(mirror, m.exponent, u1, u2);
                const Vec3<W> w = glossy_weight<W>(m, brdf, c_s, ns, wi);
                const vmask<W> ok =
                    mask_and(mask_and(spawn, dot(ng, wi) > zero),
                             mask_or(mask_or(ne(w.x, zero), ne(w.y, zero)), ne(w.z, zero)));
                const Vec3<W> ray_weight = local_weight * (w * inv_n);
                out.counts->glossy_rays += uint64_t(count(ok));
                push_packet<W>(*out.next, origin, wi, ray_weight, bc<W>(vec3(1.0f)), slot,
                               child_keys<W>(key, purpose_glossy, id), refl_depth, refr_depth,
                               child_env, vint<W>(1), ok);
            }
        }
    }
}

/// Shades k <= W hits of material `m`: queue entries idx[0..k) of `q` with hits `h`.
template <int W, uint32_t F>
void shade_batch(const Scene& scene, const Material& m, const ShadeParams& params, uint32_t seed,
                 const SlotMap& slots, const PathQueue& q, const HitArrays& h, const int32_t* idx,
                 int k, const ShadeTarget& out) {
    const vmask<W> active = mask_from_bits<W>(k >= 32 ? ~0u : (1u << k) - 1u);
    shade_hits<W, F>(scene, m, params, seed, gather_shade_input<W>(q, h, slots, idx, active),
                     active, out);
}

}  // namespace raylane
