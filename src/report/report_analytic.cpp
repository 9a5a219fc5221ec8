// report: the report's analytic references (report_analytic.h).
#include "report/report_analytic.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "render/camera_rays.h"

namespace raylane {
namespace {

using dvec3 = glm::dvec3;

/// The lit-sphere case: nullopt when the scene is not one.
std::optional<AnalyticReference> lit_sphere(const SceneData& scene, int supersampling) {
    if (scene.objects.size() != 1 || scene.environment >= 0) return std::nullopt;
    const Object& obj = scene.objects[0];
    if (obj.kind != ShapeKind::sphere || obj.has_transform ||
        obj.material >= scene.materials.size())
        return std::nullopt;
    const Material& m = scene.materials[obj.material];
    if (m.model != SpecularModel::phong || m.texture >= 0 || m.reflection != 0.0f || m.refractive ||
        m.emissive() || m.normal_map >= 0 || m.env_map >= 0)
        return std::nullopt;
    const Camera& cam = scene.camera;
    const dvec3 centre(scene.spheres[obj.shape].center);
    const double radius = scene.spheres[obj.shape].radius;
    const CameraFrame f = make_camera_frame(cam);
    const dvec3 org(f.origin);
    if (!(glm::length(org - centre) > radius) || cam.lens_radius != 0.0f) return std::nullopt;
    for (const Light& l : scene.lights) {
        if (l.kind == LightKind::point && !(glm::length(dvec3(l.position) - centre) > radius))
            return std::nullopt;
        if (l.kind != LightKind::point && l.kind != LightKind::directional) return std::nullopt;
    }
    const dvec3 c_d(m.c_d), c_s(m.c_s), background(scene.background);

    // radiance along the unit direction d from the camera
    auto radiance = [&](const dvec3& d) -> dvec3 {
        const dvec3 oc = org - centre;
        const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
        const double disc = b * b - c;
        if (disc < 0.0) return background;
        const double t = -b - std::sqrt(disc);  // camera outside: the near root
        if (!(t > 0.0)) return background;
        const dvec3 p = org + t * d;
        const dvec3 n = (p - centre) / radius;
        const dvec3 mirror = d - 2.0 * glm::dot(d, n) * n;
        dvec3 colour = double(m.k_a) * c_d;
        for (const Light& l : scene.lights) {
            dvec3 to_light;
            double factor;
            if (l.kind == LightKind::point) {
                to_light = dvec3(l.position) - p;
                const double d2 = glm::dot(to_light, to_light);
                factor = l.intensity / d2;
                to_light /= std::sqrt(d2);
            } else {
                to_light = dvec3(l.direction);
                factor = l.intensity;
            }
            const double cos_theta = glm::dot(n, to_light);
            if (!(cos_theta > 0.0)) continue;
            const dvec3 e = dvec3(l.color) * factor;
            colour += double(m.k_d) * cos_theta * e * c_d;
            const double cos_alpha = glm::dot(to_light, mirror);
            if (m.k_s > 0.0f && cos_alpha > 0.0)
                colour += double(m.k_s) * std::pow(cos_alpha, double(m.exponent)) * e * c_s;
        }
        return colour;
    };

    AnalyticReference out;
    out.name = "lit sphere, " + std::to_string(supersampling) + "x" +
               std::to_string(supersampling) + " supersampled per pixel in double";
    out.film = make_film(cam.width, cam.height);
    const double half_w = f.half_width, half_h = f.half_height;
    const dvec3 u(f.u), v(f.v), w(f.w);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, cam.height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y) {
                for (int x = 0; x < cam.width; ++x) {
                    dvec3 sum(0.0);
                    for (int j = 0; j < supersampling; ++j) {
                        for (int i = 0; i < supersampling; ++i) {
                            // camera_ray of render/camera_rays.h, in double
                            const double px = x + (i + 0.5) / supersampling,
                                         py = y + (j + 0.5) / supersampling;
                            const double sx = (2.0 * px / cam.width - 1.0) * half_w;
                            const double sy = (1.0 - 2.0 * py / cam.height) * half_h;
                            const dvec3 d = glm::normalize(w + sx * u + sy * v);
                            sum += radiance(d);
                        }
                    }
                    out.film.at(x, y) = vec3(sum / double(supersampling * supersampling));
                }
            }
        });
    return out;
}

bool is_convex(ShapeKind kind) {
    return kind == ShapeKind::sphere || kind == ShapeKind::box || kind == ShapeKind::cylinder;
}

/// The mirror furnace: nullopt when the scene is not one.
std::optional<AnalyticReference> mirror_furnace(const SceneData& scene) {
    if (scene.objects.size() != 1 || scene.environment >= 0) return std::nullopt;
    const Object& obj = scene.objects[0];
    if (!is_convex(obj.kind) || obj.material >= scene.materials.size()) return std::nullopt;
    const Material& m = scene.materials[obj.material];
    const ShadingOptions& s = scene.shading;
    const bool fresnel = m.fresnel && s.fresnel;
    if (m.reflection != 1.0f || fresnel || m.c_s != vec3(1.0f) || m.k_a_after != 0.0f ||
        (m.texture >= 0 && m.texture_specular) || m.refractive || m.emissive() ||
        m.normal_map >= 0 || m.env_map >= 0 || !s.reflection || s.max_reflection_depth < 1 ||
        s.override_reflected)
        return std::nullopt;
    AnalyticReference out;
    out.name = "mirror furnace, every pixel = background";
    out.film = make_film(scene.camera.width, scene.camera.height);
    std::fill(out.film.pixels.begin(), out.film.pixels.end(), scene.background);
    return out;
}

}  // namespace

std::optional<AnalyticReference> analytic_reference(const SceneData& scene, int supersampling) {
    if (auto r = lit_sphere(scene, std::max(1, supersampling))) return r;
    if (auto r = mirror_furnace(scene)) return r;
    return std::nullopt;
}

}  // namespace raylane
