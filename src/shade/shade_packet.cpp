// shade: packet local shading. Mirrors shade_scalar.cpp step by step.
#include "shade/shade_packet.h"

#include "core/offset_packet.h"
#include "simd/bits.h"
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
Vec3<W> shade_hit(const Scene& scene, const Accel& accel, const RayPacket<W>& rays,
                  const HitPacket<W>& hits, vmask<W> active, ShadeCounts& counts) {
    const SurfacePacket<W> sp = surface_at(scene, rays, hits, active);
    const MaterialPacket<W> m = gather_materials<W>(scene, sp.material, active);
    const vfloat<W> zero(0.0f);
    // face the viewer
    Vec3<W> ng = sp.geometric_normal, ns = sp.shading_normal;
    ng = select(dot(ng, rays.dir) > zero, -ng, ng);
    ns = select(dot(ns, ng) < zero, -ns, ns);
    const Vec3<W> view = rays.dir / sqrt(dot(rays.dir, rays.dir));
    const Vec3<W> mirror = view - (vfloat<W>(2.0f) * dot(view, ns)) * ns;
    const Vec3<W> origin = offset_ray_origin(sp.position, ng);

    Vec3<W> color = m.k_a * m.c_d;
    for (const Light& light : scene.lights) {
        // light direction and factor
        Vec3<W> to_light;
        vfloat<W> factor, t_max;
        vmask<W> lit = active;
        if (light.kind == LightKind::point) {
            to_light = make_vec3<W>(light.position.x, light.position.y, light.position.z) - origin;
            const vfloat<W> d2 = dot(to_light, to_light);
            lit = mask_and(lit, d2 > zero);
            factor = vfloat<W>(light.intensity) / d2;
            const vfloat<W> d = sqrt(d2);
            to_light = to_light / d;
            t_max = d;
        } else {
            to_light = make_vec3<W>(light.direction.x, light.direction.y, light.direction.z);
            factor = vfloat<W>(light.intensity);
            t_max = vfloat<W>(infinity);
        }
        const vfloat<W> cos_theta = dot(ns, to_light);
        lit = mask_and(lit, mask_and(cos_theta > zero, dot(ng, to_light) > zero));
        if (none(lit)) continue;
        // shadow
        if (light.shadows) {
            counts.shadow_rays += static_cast<uint64_t>(count(lit));
            RayPacket<W> shadow;
            shadow.org = origin;
            shadow.dir = to_light;
            shadow.t_min = zero;
            shadow.t_max = select(lit, t_max, vfloat<W>(-1.0f));
            lit = mask_andnot(lit, intersect_any(scene, accel, shadow, lit));
            if (none(lit)) continue;
        }
        // diffuse + Phong
        const Vec3<W> radiance = make_vec3<W>(light.color.x, light.color.y, light.color.z) * factor;
        color = select(lit, color + ((m.k_d * cos_theta) * radiance) * m.c_d, color);
        const vfloat<W> cos_alpha = dot(to_light, mirror);
        const vmask<W> spec = mask_and(mask_and(lit, m.k_s > zero), cos_alpha > zero);
        if (any(spec)) {
            const vfloat<W> p = pow(select(spec, cos_alpha, vfloat<W>(1.0f)), m.exponent);
            color = select(spec, color + ((m.k_s * p) * radiance) * m.c_s, color);
        }
    }
    return color;
}

template Vec3<1> shade_hit<1>(const Scene&, const Accel&, const RayPacket<1>&, const HitPacket<1>&,
                              vmask<1>, ShadeCounts&);
#if XSIMD_WITH_SSE2
template Vec3<4> shade_hit<4>(const Scene&, const Accel&, const RayPacket<4>&, const HitPacket<4>&,
                              vmask<4>, ShadeCounts&);
#endif
#if XSIMD_WITH_AVX2
template Vec3<8> shade_hit<8>(const Scene&, const Accel&, const RayPacket<8>&, const HitPacket<8>&,
                              vmask<8>, ShadeCounts&);
#endif
#if XSIMD_WITH_AVX512F
template Vec3<16> shade_hit<16>(const Scene&, const Accel&, const RayPacket<16>&,
                                const HitPacket<16>&, vmask<16>, ShadeCounts&);
#endif

}  // namespace raylane
