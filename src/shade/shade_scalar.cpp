// shade: scalar local shading. Mirrored by shade_packet.cpp.
#include "shade/shade_scalar.h"

#include <cmath>

#include "core/offset.h"
#include "traverse/intersect_scalar.h"

namespace raylane {

vec3 shade_hit(const Scene& scene, const Accel& accel, const Ray& ray, const Hit& hit,
               ShadeCounts& counts) {
    const SurfacePoint sp = surface_at(scene, ray, hit);
    const Material& m = scene.materials[sp.material];
    // face the viewer
    vec3 ng = sp.geometric_normal, ns = sp.shading_normal;
    if (glm::dot(ng, ray.dir) > 0.0f) ng = -ng;
    if (glm::dot(ns, ng) < 0.0f) ns = -ns;
    const vec3 view = ray.dir / std::sqrt(glm::dot(ray.dir, ray.dir));
    const vec3 mirror = view - 2.0f * glm::dot(view, ns) * ns;
    const vec3 origin = offset_ray_origin(sp.position, ng);

    vec3 color = m.k_a * m.c_d;
    for (const Light& light : scene.lights) {
        // light direction and factor
        vec3 to_light;
        float factor, t_max;
        if (light.kind == LightKind::point) {
            to_light = light.position - origin;
            const float d2 = glm::dot(to_light, to_light);
            if (!(d2 > 0.0f)) continue;
            factor = light.intensity / d2;
            to_light /= std::sqrt(d2);
            t_max = std::sqrt(d2);
        } else {
            to_light = light.direction;
            factor = light.intensity;
            t_max = infinity;
        }
        const float cos_theta = glm::dot(ns, to_light);
        if (!(cos_theta > 0.0f) || !(glm::dot(ng, to_light) > 0.0f)) continue;
        // shadow
        if (light.shadows) {
            ++counts.shadow_rays;
            const Ray shadow{origin, to_light, 0.0f, t_max};
            if (intersect_any(scene, accel, shadow)) continue;
        }
        // diffuse + Phong
        const vec3 radiance = light.color * factor;
        color += m.k_d * cos_theta * radiance * m.c_d;
        if (m.k_s > 0.0f) {
            const float cos_alpha = glm::dot(to_light, mirror);
            if (cos_alpha > 0.0f)
                color += m.k_s * std::pow(cos_alpha, m.exponent) * radiance * m.c_s;
        }
    }
    return color;
}

}  // namespace raylane
