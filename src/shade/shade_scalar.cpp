// shade: the recursive reference shading of one path. Mirrored by shade_packet.h, which
// computes the same terms for packets of hits grouped by material.
#include "shade/shade_scalar.h"

#include <cmath>

#include "core/offset.h"
#include "core/rng.h"
#include "scene/mesh_normals.h"
#include "shade/brdf_scalar.h"
#include "shade/lights_scalar.h"
#include "shade/optics_scalar.h"
#include "shade/texture_scalar.h"
#include "traverse/intersect_scalar.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

/// A hit ready for shading: position, normals turned to face the viewer, colours after textures.
struct ShadingPoint {
    vec3 position{0.0f};
    vec3 ng{0.0f, 1.0f, 0.0f};    ///< geometric normal on the viewer's side
    vec3 ns{0.0f, 1.0f, 0.0f};    ///< shading normal (normal-mapped), on the side of ng
    vec3 view{0.0f, 0.0f, 1.0f};  ///< unit ray direction
    vec3 c_d{0.0f}, c_s{0.0f};
    bool entering = true;  ///< the ray arrives on the side the geometric normal points to
    float reach = 0.0f;    ///< ray_reach of the ray that found the point (offset_ray_origin)
};

ShadingPoint shading_point(const SceneData& scene, const Material& m, const Ray& ray,
                           const Hit& hit) {
    const SurfacePoint sp = surface_at(scene, ray, hit);
    ShadingPoint p;
    p.position = sp.position;
    p.reach = ray_reach(ray, hit.t);
    p.view = ray.dir / std::sqrt(glm::dot(ray.dir, ray.dir));
    vec3 ns = sp.shading_normal;
    const Object& object = scene.objects[hit.object];
    if (m.normal_map >= 0 && object.kind == ShapeKind::mesh) {
        const MeshData& mesh = scene.meshes[object.shape];
        const vec3 texel = texture_lookup(scene.textures[size_t(m.normal_map)], sp.uv);
        ns = normal_from_map(m.normal_map_mode, texel, ns, triangle_dpdu(mesh, hit.prim),
                             mesh.normal_to_world);
    }
    // face the viewer
    p.entering = !(glm::dot(sp.geometric_normal, p.view) > 0.0f);
    p.ng = p.entering ? sp.geometric_normal : -sp.geometric_normal;
    if (glm::dot(ns, p.ng) < 0.0f) ns = -ns;
    p.ns = face_viewer(keep_above(ns, p.ng), p.ng, -p.view);
    p.c_d = m.texture >= 0 ? texture_lookup(scene.textures[size_t(m.texture)], sp.uv) : m.c_d;
    p.c_s = m.texture >= 0 && m.texture_specular ? p.c_d : m.c_s;
    return p;
}

float random_at(const SampleIndex& index, uint32_t key, uint32_t purpose, uint32_t i,
                uint32_t coord) {
    return random_float(index.pixel, index.sample, path_dim(key, purpose, i, coord), index.seed);
}

/// k_a c_d + lights (diffuse + specular lobe, shadow rays) + glossy rays.
vec3 local_term(const SceneData& scene, const Accel& accel, const Material& m,
                const ShadingPoint& p, const PathRay& path, const SampleIndex& index,
                const ShadeParams& params, ShadeCounts& counts) {
    const BrdfScaling brdf = scene.shading.brdf;
    const vec3 wo = -p.view;
    const vec3 origin = offset_ray_origin(p.position, p.ng, p.reach);
    vec3 color = m.k_a * p.c_d;
    for (size_t j = 0; j < scene.lights.size(); ++j) {
        const Light& light = scene.lights[j];
        const int n = light_sample_count(light, params);
        const float weight = 1.0f / static_cast<float>(n);
        for (int i = 0; i < n; ++i) {
            const uint32_t id = static_cast<uint32_t>(j << 16 | static_cast<uint32_t>(i));
            const float u1 = random_at(index, path.key, purpose_light, id, 0);
            const float u2 = random_at(index, path.key, purpose_light, id, 1);
            const float u3 = random_at(index, path.key, purpose_light, id, 2);
            const LightSample ls = sample_light(light, origin, i, n, u1, u2, u3);
            if (!ls.valid || !(glm::dot(p.ns, ls.dir) > 0.0f) || !(glm::dot(p.ng, ls.dir) > 0.0f))
                continue;
            if (light.shadows) {
                ++counts.shadow_rays;
                if (intersect_any(scene, accel, Ray{origin, ls.dir, 0.0f, ls.distance})) continue;
            }
            const vec3 f = diffuse_factor(m, brdf, p.c_d, p.ns, ls.dir) +
                           specular_factor(m, brdf, p.c_s, p.ns, ls.dir, wo);
            color += (weight * ls.factor) * light.color * f;
        }
    }
    if (m.model == SpecularModel::glossy_phong && !path.local_only) {
        const int n = glossy_sample_count(m, params);
        const vec3 mirror = reflect_direction(p.view, p.ns);
        vec3 sum(0.0f);
        for (int i = 0; i < n; ++i) {
            const uint32_t id = static_cast<uint32_t>(i);
            const float u1 = random_at(index, path.key, purpose_glossy, id, 0);
            const float u2 = random_at(index, path.key, purpose_glossy, id, 1);
            const vec3 wi = sample_phong_lobe(mirror, m.exponent, u1, u2);
            const vec3 w = glossy_weight(m, brdf, p.c_s, p.ns, wi);
            // below the surface: counts in n, contributes nothing (the report's estimator)
            if (!(glm::dot(p.ng, wi) > 0.0f) || w == vec3(0.0f)) continue;
            ++counts.glossy_rays;
            PathRay child;
            child.ray = Ray{origin, wi, 0.0f, infinity};
            child.key = child_key(path.key, purpose_glossy, id);
            child.local_only = true;
            child.env_map = m.env_map >= 0 ? m.env_map : path.env_map;
            sum += w * trace_path(scene, accel, child, index, params, counts).radiance;
        }
        color += sum / static_cast<float>(n);
    }
    return color;
}

/// (1 - R) local + R c_s L_mirror + k_a_after c_d, R = Schlick(r0, cos) or r0.
vec3 mirror_term(const SceneData& scene, const Accel& accel, const Material& m,
                 const ShadingPoint& p, const vec3& local, const PathRay& path,
                 const SampleIndex& index, const ShadeParams& params, ShadeCounts& counts) {
    const ShadingOptions& o = scene.shading;
    const float cos_theta = -glm::dot(p.view, p.ns);
    const float r = m.fresnel && o.fresnel ? schlick(m.reflection, cos_theta) : m.reflection;
    const vec3 dir = reflect_direction(p.view, p.ns);
    vec3 mirrored(0.0f);
    if (o.override_reflected) {
        mirrored = o.reflected_color;
    } else if (o.reflection && glm::dot(p.ng, dir) > 0.0f) {
        // a reflection about a mapped n_s that points below the geometric surface is discarded
        ++counts.reflection_rays;
        PathRay child;
        child.ray = Ray{offset_ray_origin(p.position, p.ng, p.reach), dir, 0.0f, infinity};
        child.key = child_key(path.key, purpose_mirror, 0);
        child.reflection_depth = path.reflection_depth + 1;
        child.refraction_depth = path.refraction_depth;
        child.env_map = m.env_map >= 0 ? m.env_map : path.env_map;
        mirrored = trace_path(scene, accel, child, index, params, counts).radiance;
    }
    const vec3 local_part = o.local ? (1.0f - r) * local : vec3(0.0f);
    return local_part + r * p.c_s * mirrored + m.k_a_after * p.c_d;
}

/// R L_reflected + (1 - R) L_refracted with exact Fresnel (or R = 0 when Fresnel is off) and
/// Beer's law on the segment inside; total internal reflection reflects everything.
vec3 glass_term(const SceneData& scene, const Accel& accel, const Material& m,
                const ShadingPoint& p, const PathRay& path, const SampleIndex& index,
                const ShadeParams& params, ShadeCounts& counts) {
    const ShadingOptions& o = scene.shading;
    const float eta = p.entering ? m.ior : 1.0f / m.ior;
    const float cos_i = -glm::dot(p.view, p.ns);
    vec3 t_dir;
    float cos_t = 0.0f;
    const bool refracts =
        refract_direction(p.view, p.ns, eta, t_dir, cos_t) && glm::dot(t_dir, p.ng) < 0.0f;
    const float r = !refracts                ? 1.0f
                    : m.fresnel && o.fresnel ? fresnel_dielectric(cos_i, eta, cos_t)
                                             : 0.0f;
    auto trace_child = [&](vec3 org_normal, vec3 dir, uint32_t purpose, bool inside) {
        PathRay child;
        child.ray = Ray{offset_ray_origin(p.position, org_normal, p.reach), dir, 0.0f, infinity};
        child.key = child_key(path.key, purpose, 0);
        child.reflection_depth = path.reflection_depth;
        child.refraction_depth = path.refraction_depth + 1;
        child.env_map = m.env_map >= 0 ? m.env_map : path.env_map;
        const PathResult res = trace_path(scene, accel, child, index, params, counts);
        return inside ? res.radiance * beer_transmittance(m.filter, res.t) : res.radiance;
    };
    const vec3 r_dir = reflect_direction(p.view, p.ns);
    // the rays this interaction may trace (a reflection below the geometric surface is discarded)
    bool reflect_ray =
        r > 0.0f && o.reflection && !o.override_reflected && glm::dot(p.ng, r_dir) > 0.0f;
    bool refract_ray = refracts && r < 1.0f && o.refraction;
    if (reflect_ray && refract_ray && path.refraction_depth >= glass_fork_depth) {
        // no more forks: the larger branch only (scene.h: glass_fork_depth)
        reflect_ray = r >= 0.5f;
        refract_ray = !reflect_ray;
    }
    vec3 color(0.0f);
    if (r > 0.0f && o.override_reflected) color += r * o.reflected_color;
    if (reflect_ray) {
        ++counts.reflection_rays;
        // a reflection inside the glass travels inside
        color += r * trace_child(p.ng, r_dir, purpose_reflect, !p.entering);
    }
    if (refract_ray) {
        ++counts.refraction_rays;
        color += (1.0f - r) * trace_child(-p.ng, t_dir, purpose_refract, p.entering);
    }
    return color;
}

}  // namespace

vec3 miss_radiance(const SceneData& scene, int32_t env_map, vec3 dir) {
    const int32_t map = env_map >= 0 ? env_map : scene.environment;
    if (map >= 0) return environment_lookup(scene.textures[size_t(map)], dir);
    return scene.background;
}

PathResult trace_path(const SceneData& scene, const Accel& accel, const PathRay& path,
                      const SampleIndex& index, const ShadeParams& params, ShadeCounts& counts) {
    const Hit hit = intersect_closest(scene, accel, path.ray);
    if (!hit.hit()) return {miss_radiance(scene, path.env_map, path.ray.dir), infinity};
    const Material& m = scene.materials[scene.objects[hit.object].material];
    if (m.emissive()) return {m.emission, hit.t};
    const ShadingPoint p = shading_point(scene, m, path.ray, hit);
    if (m.refractive) {
        // glass ignores lights; glossy rays and paths past the limit see it black
        if (path.local_only || path.refraction_depth >= scene.shading.max_refraction_depth)
            return {vec3(0.0f), hit.t};
        return {glass_term(scene, accel, m, p, path, index, params, counts), hit.t};
    }
    const vec3 local = local_term(scene, accel, m, p, path, index, params, counts);
    if (m.reflection > 0.0f && !path.local_only &&
        path.reflection_depth < scene.shading.max_reflection_depth) {
        return {mirror_term(scene, accel, m, p, local, path, index, params, counts), hit.t};
    }
    return {m.reflection > 0.0f ? local + m.k_a_after * p.c_d : local, hit.t};
}

}  // namespace raylane
