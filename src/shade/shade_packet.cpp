// shade: packet local shading. Mirrors shade_scalar.cpp step by step.
#include "shade/shade_packet.h"

#include "core/offset_packet.h"
#include "traverse/intersect_packet.h"

namespace raylane {
namespace {

/// The material parameters of each lane (broadcast when all lanes share one material).
template <int W>
struct MaterialPacket {
    Vec3<W> c_d, c_s;
    vfloat<W> k_d, k_a, k_s, exponent;
};

template <int W>
MaterialPacket<W> gather_materials(const Scene& scene, const vint<W>& ids, vmask<W> active) {
    MaterialPacket<W> m;
    const int first = first_active(active);
    const int32_t id0 = get(ids, first);
    bool uniform = true;
    for_each_active(active, [&](int i) { uniform = uniform && get(ids, i) == id0; });
    auto fill = [&](int i, const Material& mat) {
        set(m.c_d.x, i, mat.c_d.x), set(m.c_d.y, i, mat.c_d.y), set(m.c_d.z, i, mat.c_d.z);
        set(m.c_s.x, i, mat.c_s.x), set(m.c_s.y, i, mat.c_s.y), set(m.c_s.z, i, mat.c_s.z);
        set(m.k_d, i, mat.k_d), set(m.k_a, i, mat.k_a), set(m.k_s, i, mat.k_s);
        set(m.exponent, i, mat.exponent);
    };
    if (uniform) {
        const Material& mat = scene.materials[static_cast<uint32_t>(id0)];
        m.c_d = make_vec3<W>(mat.c_d.x, mat.c_d.y, mat.c_d.z);
        m.c_s = make_vec3<W>(mat.c_s.x, mat.c_s.y, mat.c_s.z);
        m.k_d = vfloat<W>(mat.k_d);
        m.k_a = vfloat<W>(mat.k_a);
        m.k_s = vfloat<W>(mat.k_s);
        m.exponent = vfloat<W>(mat.exponent);
    } else {
        for_each_active(
            active, [&](int i) { fill(i, scene.materials[static_cast<uint32_t>(get(ids, i))]); });
    }
    return m;
}

}  // namespace

template <int W>
void shade_hit(const Scene& scene, const Accel& accel, const RayPacket<W>* rays,
               const HitPacket<W>* hits, const vmask<W>* active, int count, Vec3<W>* color,
               ShadeCounts& counts) {
    constexpr int max_packets = max_block_rays / W;
    Vec3<W> ng[max_packets], ns[max_packets], mirror[max_packets], origin[max_packets];
    MaterialPacket<W> m[max_packets];
    const vfloat<W> zero(0.0f);
    for (int p = 0; p < count; ++p) {
        if (none(active[p])) continue;
        const SurfacePacket<W> sp = surface_at(scene, rays[p], hits[p], active[p]);
        m[p] = gather_materials<W>(scene, sp.material, active[p]);
        // face the viewer
        ng[p] = select(dot(sp.geometric_normal, rays[p].dir) > zero, -sp.geometric_normal,
                       sp.geometric_normal);
        ns[p] = select(dot(sp.shading_normal, ng[p]) < zero, -sp.shading_normal, sp.shading_normal);
        const Vec3<W> view = rays[p].dir / sqrt(dot(rays[p].dir, rays[p].dir));
        mirror[p] = view - (vfloat<W>(2.0f) * dot(view, ns[p])) * ns[p];
        origin[p] = offset_ray_origin(sp.position, ng[p]);
        color[p] = m[p].k_a * m[p].c_d;
    }

    for (const Light& light : scene.lights) {
        RayPacket<W> shadow[max_packets];
        vmask<W> lit[max_packets], occluded[max_packets];
        vfloat<W> factor[max_packets], cos_theta[max_packets];
        bool any_lit = false;
        for (int p = 0; p < count; ++p) {
            // light direction and factor
            Vec3<W> to_light;
            vfloat<W> t_max;
            lit[p] = active[p];
            if (light.kind == LightKind::point) {
                to_light =
                    make_vec3<W>(light.position.x, light.position.y, light.position.z) - origin[p];
                const vfloat<W> d2 = dot(to_light, to_light);
                lit[p] = mask_and(lit[p], d2 > zero);
                factor[p] = vfloat<W>(light.intensity) / d2;
                const vfloat<W> d = sqrt(d2);
                to_light = to_light / d;
                t_max = d;
            } else {
                to_light = make_vec3<W>(light.direction.x, light.direction.y, light.direction.z);
                factor[p] = vfloat<W>(light.intensity);
                t_max = vfloat<W>(infinity);
            }
            cos_theta[p] = dot(ns[p], to_light);
            lit[p] = mask_and(lit[p], mask_and(cos_theta[p] > zero, dot(ng[p], to_light) > zero));
            shadow[p].org = origin[p];
            shadow[p].dir = to_light;
            shadow[p].t_min = zero;
            shadow[p].t_max = select(lit[p], t_max, vfloat<W>(-1.0f));
            any_lit = any_lit || any(lit[p]);
        }
        if (!any_lit) continue;
        // shadow
        if (light.shadows) {
            for (int p = 0; p < count; ++p)
                counts.shadow_rays += static_cast<uint64_t>(raylane::count(lit[p]));
            intersect_any_block(scene, accel, shadow, lit, occluded, count);
            for (int p = 0; p < count; ++p) lit[p] = mask_andnot(lit[p], occluded[p]);
        }
        // diffuse + Phong
        const Vec3<W> light_color = make_vec3<W>(light.color.x, light.color.y, light.color.z);
        for (int p = 0; p < count; ++p) {
            if (none(lit[p])) continue;
            const Vec3<W> radiance = light_color * factor[p];
            color[p] = select(lit[p], color[p] + ((m[p].k_d * cos_theta[p]) * radiance) * m[p].c_d,
                              color[p]);
            const vfloat<W> cos_alpha = dot(shadow[p].dir, mirror[p]);
            const vmask<W> spec = mask_and(mask_and(lit[p], m[p].k_s > zero), cos_alpha > zero);
            if (any(spec)) {
                const vfloat<W> pw = pow(select(spec, cos_alpha, vfloat<W>(1.0f)), m[p].exponent);
                color[p] =
                    select(spec, color[p] + ((m[p].k_s * pw) * radiance) * m[p].c_s, color[p]);
            }
        }
    }
}

template void shade_hit<1>(const Scene&, const Accel&, const RayPacket<1>*, const HitPacket<1>*,
                           const vmask<1>*, int, Vec3<1>*, ShadeCounts&);
#if XSIMD_WITH_SSE2
template void shade_hit<4>(const Scene&, const Accel&, const RayPacket<4>*, const HitPacket<4>*,
                           const vmask<4>*, int, Vec3<4>*, ShadeCounts&);
#endif
#if XSIMD_WITH_AVX2
template void shade_hit<8>(const Scene&, const Accel&, const RayPacket<8>*, const HitPacket<8>*,
                           const vmask<8>*, int, Vec3<8>*, ShadeCounts&);
#endif
#if XSIMD_WITH_AVX512F
template void shade_hit<16>(const Scene&, const Accel&, const RayPacket<16>*, const HitPacket<16>*,
                            const vmask<16>*, int, Vec3<16>*, ShadeCounts&);
#endif

}  // namespace raylane
