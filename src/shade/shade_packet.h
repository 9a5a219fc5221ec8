// shade: the packet path's shading kernels. Mirrors shade_scalar.cpp: the same functions in the
// same order, with shade_hits in place of trace_path. shade_hits shades W hits of one material at
// a time (grouped by a counting sort in the wavefront, by object in a camera packet when the
// scene has no secondary rays; docs/architecture.md): the terms of shade_scalar.cpp (local
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
#include "core/rng.h"
#include "scene/features.h"
#include "scene/mesh_normals.h"
#include "scene/scene.h"
#include "shade/brdf_packet.h"
#include "shade/lights_packet.h"
#include "shade/optics_packet.h"
#include "shade/path_queue.h"
#include "shade/shade_io_packet.h"
#include "shade/shade_scalar.h"
#include "shade/texture_packet.h"
#include "simd/hash.h"
#include "simd/lanes.h"
#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"
#include "traverse/surface_packet.h"

namespace raylane::RAYLANE_ISA_NS {
namespace shade_detail {

/// A hit ready for shading: position, normals turned to face the viewer, colours after textures
/// (shade_scalar.cpp's ShadingPoint, W lanes).
template <int W>
struct ShadingPointPacket {
    Vec3<W> position;
    Vec3<W> ng;    ///< geometric normal on the viewer's side
    Vec3<W> ns;    ///< shading normal (normal-mapped), on the side of ng
    Vec3<W> view;  ///< unit ray direction
    Vec3<W> c_d, c_s;
    vmask<W> entering;  ///< the ray arrives on the side the geometric normal points to
    vfloat<W> reach;    ///< ray_reach of the ray that found the point (offset_ray_origin)
};

template <int W, uint32_t F>
[[gnu::always_inline]] inline ShadingPointPacket<W> shading_point(const SceneData& scene,
                                                                  const Material& m,
                                                                  const RayPacket<W>& rays,
                                                                  const HitPacket<W>& hits,
                                                                  vmask<W> active) {
    const vfloat<W> zero(0.0f);
    const SurfacePacket<W> sp = surface_at(scene, rays, hits, active);
    ShadingPointPacket<W> p;
    p.position = sp.position;
    p.reach = ray_reach<W>(rays, hits.t);
    p.view = rays.dir / sqrt(dot(rays.dir, rays.dir));
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
                const MeshData& mesh = scene.meshes[obj.shape];
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
    // face the viewer
    p.entering = mask_not(dot(sp.geometric_normal, p.view) > zero);
    p.ng = select(p.entering, sp.geometric_normal, -sp.geometric_normal);
    ns = select(dot(ns, p.ng) < zero, -ns, ns);
    p.ns = face_viewer<W>(keep_above<W>(ns, p.ng), p.ng, -p.view);
    p.c_d = broadcast_vec3<W>(m.c_d);
    p.c_s = broadcast_vec3<W>(m.c_s);
    if constexpr ((F & feature_textures) != 0) {
        if (m.texture >= 0) {
            p.c_d = texture_lookup<W>(scene.textures[size_t(m.texture)], sp.u, sp.v, active);
            if (m.texture_specular) p.c_s = p.c_d;
        }
    }
    return p;
}

/// random_at of shade_scalar.cpp, lane-wise: the random number of each lane's path, keyed by its
/// pixel, sample and path key.
template <int W>
inline vfloat<W> random_at(const vint<W>& pixel, const vint<W>& sample, uint32_t seed,
                           const vint<W>& key, uint32_t purpose, uint32_t index, uint32_t coord) {
    // path_dim of core/rng.h, lane-wise
    const vint<W> salt = hash_u32<W>(broadcast<W>((purpose << 28) ^ (index << 2) ^ coord));
    const vint<W> dim = hash_u32<W>(key ^ salt) | broadcast<W>(0x80000000u);
    return random_float<W>(pixel, sample, dim, broadcast<W>(seed));
}

/// k_a c_d + lights (diffuse + specular lobe, shadow rays) + glossy rays, weighted by
/// `local_weight` (the path's weight; (1 - R) of it on mirror lanes): the ambient term and the
/// lights without shadows go to the slots, shadow rays to the light's queue, glossy rays to the
/// next pass.
template <int W, uint32_t F, class Target>
[[gnu::always_inline]] inline void local_term(const SceneData& scene, const Material& m,
                                              const ShadingPointPacket<W>& p,
                                              const ShadeInput<W>& in, const Vec3<W>& local_weight,
                                              const ShadeParams& params, uint32_t seed,
                                              const Target& out, vmask<W> active) {
    const vfloat<W> zero(0.0f);
    const BrdfScaling brdf = scene.shading.brdf;
    const Vec3<W> wo = -p.view;
    const Vec3<W> origin = offset_ray_origin(p.position, p.ng, p.reach);
    accumulate<W>(out, in.path, local_weight * (vfloat<W>(m.k_a) * p.c_d), active);
    for (size_t j = 0; j < scene.lights.size(); ++j) {
        const Light& light = scene.lights[j];
        const int n = light_sample_count(light, params);
        const float sample_weight = 1.0f / static_cast<float>(n);
        const Vec3<W> light_color = broadcast_vec3<W>(light.color);
        for (int i = 0; i < n; ++i) {
            vfloat<W> u1 = zero, u2 = zero, u3 = zero;
            if constexpr ((F & feature_area_lights) != 0) {
                if (light.is_area()) {
                    const uint32_t id = static_cast<uint32_t>(j << 16 | static_cast<uint32_t>(i));
                    u1 = random_at<W>(in.pixel, in.sample, seed, in.key, purpose_light, id, 0);
                    u2 = random_at<W>(in.pixel, in.sample, seed, in.key, purpose_light, id, 1);
                    u3 = random_at<W>(in.pixel, in.sample, seed, in.key, purpose_light, id, 2);
                }
            }
            const LightSamplePacket<W> ls = sample_light<W>(light, origin, i, n, u1, u2, u3);
            const vmask<W> lit =
                mask_and(mask_and(active, ls.valid),
                         mask_and(dot(p.ns, ls.dir) > zero, dot(p.ng, ls.dir) > zero));
            if (none(lit)) continue;
            const Vec3<W> f = diffuse_factor<W>(m, brdf, p.c_d, p.ns, ls.dir) +
                              specular_factor<W>(m, brdf, p.c_s, p.ns, ls.dir, wo);
            const Vec3<W> contribution =
                local_weight * (((vfloat<W>(sample_weight) * ls.factor) * light_color) * f);
            if (!light.shadows) {
                accumulate<W>(out, in.path, contribution, lit);
                continue;
            }
            out.counts->shadow_rays += uint64_t(count(lit));
            add_shadow_rays<W>(out, j, i, origin, ls.dir, ls.distance, contribution, in.path, lit);
        }
    }
    if constexpr ((F & feature_glossy) != 0) {
        if (m.model == SpecularModel::glossy_phong) {
            const vmask<W> spawn = mask_andnot(active, in.local_only);
            if (none(spawn)) return;
            const int n = glossy_sample_count(m, params);
            const Vec3<W> mirror = reflect_direction<W>(p.view, p.ns);
            const vfloat<W> inv_n(1.0f / static_cast<float>(n));
            // secondary rays see the material's reflection map, else the one their path carries
            const vint<W> child_env = m.env_map >= 0 ? vint<W>(m.env_map) : in.env;
            for (int i = 0; i < n; ++i) {
                const uint32_t id = static_cast<uint32_t>(i);
                const vfloat<W> u1 =
                    random_at<W>(in.pixel, in.sample, seed, in.key, purpose_glossy, id, 0);
                const vfloat<W> u2 =
                    random_at<W>(in.pixel, in.sample, seed, in.key, purpose_glossy, id, 1);
                const Vec3<W> wi = sample_phong_lobe<W>(mirror, m.exponent, u1, u2);
                const Vec3<W> w = glossy_weight<W>(m, brdf, p.c_s, p.ns, wi);
                // below the surface: counts in n, contributes nothing (the report's estimator)
                const vmask<W> ok =
                    mask_and(mask_and(spawn, dot(p.ng, wi) > zero),
                             mask_or(mask_or(ne(w.x, zero), ne(w.y, zero)), ne(w.z, zero)));
                const Vec3<W> ray_weight = local_weight * (w * inv_n);
                out.counts->glossy_rays += uint64_t(count(ok));
                push_packet<W>(*out.next, origin, wi, ray_weight, broadcast_vec3<W>(vec3(1.0f)),
                               in.slot, in.path, child_keys<W>(in.key, purpose_glossy, id),
                               in.refl_depth, in.refr_depth, child_env, vint<W>(1), ok);
            }
        }
    }
}

/// (1 - R) local + R c_s L_mirror, R = Schlick(r0, cos) or r0, on the `mirror` lanes: the mirror
/// ray goes to the next pass with weight R c_s (or the override colour to the slots). Returns
/// the local term's weight: (1 - R) times the path's weight on the mirror lanes (0 when the
/// local term is off), the path's weight on the others. shade_hits adds k_a_after c_d.
template <int W, class Target>
[[gnu::always_inline]] inline Vec3<W> mirror_term(const SceneData& scene, const Material& m,
                                                  const ShadingPointPacket<W>& p,
                                                  const ShadeInput<W>& in, const Target& out,
                                                  vmask<W> mirror) {
    const ShadingOptions& o = scene.shading;
    const vfloat<W> zero(0.0f), one(1.0f);
    const Vec3<W>& weight = in.weight;
    const vfloat<W> r = m.fresnel && o.fresnel ? schlick<W>(m.reflection, neg(dot(p.view, p.ns)))
                                               : vfloat<W>(m.reflection);
    const Vec3<W> local_weight =
        select(mirror, o.local ? weight * (one - r) : weight * zero, weight);
    const Vec3<W> mirror_weight = (weight * r) * p.c_s;
    if (o.override_reflected) {
        accumulate<W>(out, in.path, mirror_weight * broadcast_vec3<W>(o.reflected_color), mirror);
    } else if (o.reflection) {
        const Vec3<W> dir = reflect_direction<W>(p.view, p.ns);
        // a reflection about a mapped n_s below the geometric surface is discarded
        const vmask<W> traced = mask_and(mirror, dot(p.ng, dir) > zero);
        out.counts->reflection_rays += uint64_t(count(traced));
        const vint<W> child_env = m.env_map >= 0 ? vint<W>(m.env_map) : in.env;
        push_packet<W>(*out.next, offset_ray_origin(p.position, p.ng, p.reach), dir, mirror_weight,
                       broadcast_vec3<W>(vec3(1.0f)), in.slot, in.path,
                       child_keys<W>(in.key, purpose_mirror, 0), in.refl_depth + vint<W>(1),
                       in.refr_depth, child_env, vint<W>(0), traced);
    }
    return local_weight;
}

/// R L_reflected + (1 - R) L_refracted with exact Fresnel (or R = 0 when Fresnel is off) and
/// Beer's law on the segment inside (the filter a ray carries into the glass); total internal
/// reflection reflects everything. The `alive` lanes' rays go to the next pass, those that
/// travel inside the glass to their own queue.
template <int W, class Target>
[[gnu::always_inline]] inline void glass_term(const SceneData& scene, const Material& m,
                                              const ShadingPointPacket<W>& p,
                                              const ShadeInput<W>& in, const Target& out,
                                              vmask<W> alive) {
    const ShadingOptions& o = scene.shading;
    const vfloat<W> zero(0.0f), one(1.0f);
    const Vec3<W>& weight = in.weight;
    const vfloat<W> eta = select(p.entering, vfloat<W>(m.ior), vfloat<W>(1.0f / m.ior));
    const vfloat<W> cos_i = neg(dot(p.view, p.ns));
    Vec3<W> t_dir;
    vfloat<W> cos_t;
    // two statements: t_dir is written by refract_direction, then read
    vmask<W> refracts = refract_direction<W>(p.view, p.ns, eta, t_dir, cos_t);
    refracts = mask_and(refracts, dot(t_dir, p.ng) < zero);
    const vfloat<W> r = select(
        refracts, m.fresnel && o.fresnel ? fresnel_dielectric<W>(cos_i, eta, cos_t) : zero, one);
    const Vec3<W> reflected_dir = reflect_direction<W>(p.view, p.ns);
    const Vec3<W> org_out = offset_ray_origin(p.position, p.ng, p.reach);
    const Vec3<W> org_in = offset_ray_origin(p.position, -p.ng, p.reach);
    const vec3 no_filter(1.0f);
    const vint<W> child_env = m.env_map >= 0 ? vint<W>(m.env_map) : in.env;
    const vmask<W> reflects = mask_and(alive, r > zero);
    // the rays this interaction may trace (a reflection below the geometric surface is
    // discarded); past glass_fork_depth only the larger of two (scene.h)
    const vmask<W> no_lanes = mask_from_bits<W>(0);
    vmask<W> traced = o.reflection && !o.override_reflected
                          ? mask_and(reflects, dot(p.ng, reflected_dir) > zero)
                          : no_lanes;
    vmask<W> transmits = o.refraction ? mask_and(mask_and(alive, refracts), r < one) : no_lanes;
    const vmask<W> no_fork =
        mask_andnot(mask_and(traced, transmits), lt(in.refr_depth, vint<W>(glass_fork_depth)));
    const vmask<W> reflection_larger = r >= vfloat<W>(0.5f);
    traced = mask_andnot(traced, mask_andnot(no_fork, reflection_larger));
    transmits = mask_andnot(transmits, mask_and(no_fork, reflection_larger));
    if (o.override_reflected)
        accumulate<W>(out, in.path, (weight * r) * broadcast_vec3<W>(o.reflected_color), reflects);
    if (any(traced)) {
        out.counts->reflection_rays += uint64_t(count(traced));
        const Vec3<W> filter =
            select(p.entering, broadcast_vec3<W>(no_filter), broadcast_vec3<W>(m.filter));
        const vint<W> child = child_keys<W>(in.key, purpose_reflect, 0);
        for (const bool inside : {false, true}) {
            // reflected inside where the ray came from inside
            const vmask<W> lanes =
                inside ? mask_andnot(traced, p.entering) : mask_and(traced, p.entering);
            if (any(lanes))
                push_packet<W>(inside ? *out.next_inside : *out.next, org_out, reflected_dir,
                               weight * r, filter, in.slot, in.path, child, in.refl_depth,
                               in.refr_depth + vint<W>(1), child_env, vint<W>(0), lanes);
        }
    }
    if (any(transmits)) {
        out.counts->refraction_rays += uint64_t(count(transmits));
        const Vec3<W> filter =
            select(p.entering, broadcast_vec3<W>(m.filter), broadcast_vec3<W>(no_filter));
        const vint<W> child = child_keys<W>(in.key, purpose_refract, 0);
        for (const bool inside : {false, true}) {
            // refracted inside where the ray came from outside
            const vmask<W> lanes =
                inside ? mask_and(transmits, p.entering) : mask_andnot(transmits, p.entering);
            if (any(lanes))
                push_packet<W>(inside ? *out.next_inside : *out.next, org_in, t_dir,
                               weight * (one - r), filter, in.slot, in.path, child, in.refl_depth,
                               in.refr_depth + vint<W>(1), child_env, vint<W>(0), lanes);
        }
    }
}

}  // namespace shade_detail

/// miss_radiance of shade_scalar.h for W rays: each lane's map (`env_map`, else the scene's
/// environment), else the background.
template <int W>
inline Vec3<W> miss_radiance(const SceneData& scene, const vint<W>& env_map, const Vec3<W>& dir,
                             vmask<W> active) {
    const vint<W> map = select(lt(env_map, vint<W>(0)), vint<W>(scene.environment), env_map);
    Vec3<W> out = broadcast_vec3<W>(scene.background);
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

/// Shades the `active` lanes of `in`, all hits of material `m` (trace_path of shade_scalar.cpp
/// after its intersection): adds their direct light and ambient term to the tile's slots, and
/// queues shadow rays (per light) and secondary rays. Target: ShadeTarget (queues), or
/// PacketTarget<W> for kernels without secondary rays.
template <int W, uint32_t F, class Target>
void shade_hits(const SceneData& scene, const Material& m, const ShadeParams& params, uint32_t seed,
                const ShadeInput<W>& in, vmask<W> active, const Target& out) {
    using namespace shade_detail;
    const ShadingOptions& o = scene.shading;
    const vmask<W> local_only = mask_and(active, in.local_only);
    if (m.emissive()) {
        accumulate<W>(out, in.path, in.weight * broadcast_vec3<W>(m.emission), active);
        return;
    }
    const ShadingPointPacket<W> p = shading_point<W, F>(scene, m, in.rays, in.hits, active);
    if constexpr ((F & feature_refraction) != 0) {
        if (m.refractive) {
            // glass ignores lights; glossy rays and paths past the limit see it black
            const vmask<W> alive = mask_and(mask_andnot(active, local_only),
                                            lt(in.refr_depth, vint<W>(o.max_refraction_depth)));
            if (any(alive)) glass_term<W>(scene, m, p, in, out, alive);
            return;
        }
    }
    // the mirror before the local term, whose weight it scales by 1 - R; k_a_after c_d with or
    // without the mirror ray, as in trace_path
    Vec3<W> local_weight = in.weight;
    if constexpr ((F & feature_reflection) != 0) {
        if (m.reflection > 0.0f) {
            accumulate<W>(out, in.path, in.weight * (vfloat<W>(m.k_a_after) * p.c_d), active);
            const vmask<W> mirror = mask_and(mask_andnot(active, local_only),
                                             lt(in.refl_depth, vint<W>(o.max_reflection_depth)));
            if (any(mirror)) local_weight = mirror_term<W>(scene, m, p, in, out, mirror);
        }
    }
    local_term<W, F>(scene, m, p, in, local_weight, params, seed, out, active);
}

/// Shades a packet of k <= W hits of material `m`, gathered from the queue: entries idx[0..k) of
/// `q` with hits `h`.
template <int W, uint32_t F>
void shade_packet(const SceneData& scene, const Material& m, const ShadeParams& params,
                  uint32_t seed, const SlotMap& slots, const PathQueue& q, const HitArrays& h,
                  const int32_t* idx, int k, const ShadeTarget& out) {
    const vmask<W> active = mask_from_bits<W>(k >= 32 ? ~0u : (1u << k) - 1u);
    shade_hits<W, F>(scene, m, params, seed, gather_shade_input<W>(q, h, slots, idx, active),
                     active, out);
}

}  // namespace raylane::RAYLANE_ISA_NS
