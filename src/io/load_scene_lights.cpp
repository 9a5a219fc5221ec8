// io: the lights of the scene format (SceneReader, io/scene_reader.h): point, directional and
// area lights, and the visible emitter objects that stand in for area lights.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "io/scene_reader.h"
#include "scene/transform.h"

namespace raylane {

namespace {

/// The report's "2ab" of an area light's stand-in (twice the area of a rectangle or disc;
/// 2ab for a box with a, b its two largest extents); 1 when degenerate.
double emitter_area(const Light& light) {
    double area = 0.0;
    const glm::dvec3 e(light.edge_u);
    if (light.kind == LightKind::rect) {
        area = 2.0 * glm::length(glm::cross(e, glm::dvec3(light.edge_v)));
    } else if (light.kind == LightKind::disk) {
        area = 2.0 * std::numbers::pi * double(light.radius) * light.radius;
    } else {
        double a = std::max(e.x, e.y), b = std::max(e.x, e.z);
        if (a == b) b = std::max(e.y, e.z);
        area = 2.0 * a * b;
    }
    return area > 0.0 ? area : 1.0;
}

}  // namespace

Light SceneReader::read_light(const Node& n, SceneData& scene) {
    expect(n, n.j->is_object(), "an object");
    int type = choice(child(n, "type"), {"point", "directional", "rect", "disk", "box"});
    Light light;
    constexpr LightKind kinds[] = {LightKind::point, LightKind::directional, LightKind::rect,
                                   LightKind::disk, LightKind::box};
    light.kind = kinds[type];
    auto path = [&](std::string_view key) { return member_path(n.path, key); };
    switch (light.kind) {
        case LightKind::point:
            expect_keys(n, {"type", "position", "color", "intensity", "shadows"});
            light.position = point(child(n, "position"));
            break;
        case LightKind::directional:
            expect_keys(n, {"type", "direction", "color", "intensity", "shadows"});
            light.direction = direction(child(n, "direction"));
            break;
        case LightKind::rect: {
            expect_keys(n, {"type", "corner", "edge_u", "edge_v", "color", "intensity", "shadows",
                            "samples", "visible"});
            light.position = point(child(n, "corner"));
            light.edge_u = vector(child(n, "edge_u"));
            Node ev = child(n, "edge_v");
            light.edge_v = vector(ev);
            if (!(glm::length(glm::cross(light.edge_u, light.edge_v)) > 0.0f)) {
                fail(ev, "the rectangle has zero area (edges parallel or zero)");
            }
            break;
        }
        case LightKind::disk:
            expect_keys(n, {"type", "center", "normal", "radius", "color", "intensity", "shadows",
                            "samples", "visible"});
            light.position = point(child(n, "center"));
            light.direction = direction(child(n, "normal"));
            light.radius = real(child(n, "radius"), Sign::positive);
            break;
        case LightKind::box: {
            expect_keys(
                n, {"type", "min", "max", "color", "intensity", "shadows", "samples", "visible"});
            Node hi = child(n, "max");
            light.position = point(child(n, "min"));
            const vec3 top = point(hi);
            if (!(light.position.x <= top.x && light.position.y <= top.y &&
                  light.position.z <= top.z)) {
                fail(hi, "must be >= min in every component");
            }
            light.edge_u = top - light.position;
            break;
        }
    }
    if (const Json* v = find(n, "color")) light.color = color(Node{v, path("color")});
    if (const Json* v = find(n, "intensity")) {
        light.intensity = real(Node{v, path("intensity")}, Sign::non_negative);
    }
    if (const Json* v = find(n, "shadows")) light.shadows = boolean(Node{v, path("shadows")});
    const double brightest = std::max({light.color.x, light.color.y, light.color.z});
    if (!(brightest * double(light.intensity) <= double(std::numeric_limits<float>::max())))
        fail(n, "the light's color times its intensity overflows the float range");
    if (light.is_area()) {
        check_area_light(n, light);
        light.samples = 16;
        if (const Json* v = find(n, "samples")) {
            light.samples = integer(Node{v, path("samples")}, 1, 4096);
        }
        bool visible = true;
        if (const Json* v = find(n, "visible")) visible = boolean(Node{v, path("visible")});
        if (visible) add_emitter(light, scene);
    }
    return light;
}

/// Area lights whose derived geometry or emission would leave the float range (or whose
/// stand-in would be degenerate) are errors: nothing infinite may reach the image.
void SceneReader::check_area_light(const Node& n, const Light& light) const {
    auto finite3 = [](vec3 v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    const vec3 far = light.position + light.edge_u + light.edge_v;
    if (!finite3(light.edge_u) || !finite3(far)) {
        fail(n, "the light's extent overflows the float range");
    }
    if (light.kind == LightKind::disk && !(1e-3f * light.radius > 1e-30f)) {
        fail(child(n, "radius"), "is too small (must be > 1e-27)");
    }
    if (!(double(light.intensity) / (4.0 * std::numbers::pi * emitter_area(light)) < 1e30)) {
        fail(n, "the light's emitted radiance overflows (intensity too large for its area)");
    }
}

/// The visible stand-in of an area light (report-scenes.md 1.4): an object of emitted
/// radiance colour * intensity / (4 pi A) that casts no shadows. A is the report's "2ab":
/// twice the area of a rectangle or disc, 2ab for a box with a, b its two largest extents.
void SceneReader::add_emitter(const Light& light, SceneData& scene) {
    Material m;
    m.name = "<area light " + std::to_string(scene.lights.size()) + ">";
    Object o;
    o.casts_shadows = false;
    o.material = uint32_t(scene.materials.size());
    Transform t;
    switch (light.kind) {
        case LightKind::rect: {
            const vec3 p = light.position, u = light.edge_u, v = light.edge_v;
            const Triangle tris[2] = {{p, p + u, p + u + v}, {p, p + u + v, p + v}};
            for (const Triangle& tri : tris) {
                o.kind = ShapeKind::triangle;
                o.shape = uint32_t(scene.triangles.size());
                scene.triangles.push_back(tri);
                scene.objects.push_back(o);
            }
            break;
        }
        case LightKind::disk: {
            const double r = light.radius;
            // a thin cylinder whose axis (+y) is the disc normal
            const glm::dvec3 n(light.direction);
            const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
            const glm::dvec3 tangent = glm::normalize(glm::cross(n, a));
            t.rotate = glm::dmat3(tangent, n, glm::cross(tangent, n));
            const double h = 1e-3 * r;
            t.translate = glm::dvec3(light.position) - 0.5 * h * n;
            o.kind = ShapeKind::cylinder;
            o.shape = uint32_t(scene.cylinders.size());
            scene.cylinders.push_back(Cylinder{float(r), float(h)});
            set_transform(o, t);
            scene.objects.push_back(o);
            break;
        }
        case LightKind::box: {
            o.kind = ShapeKind::box;
            o.shape = uint32_t(scene.boxes.size());
            scene.boxes.push_back(Box{light.position, light.position + light.edge_u});
            scene.objects.push_back(o);
            break;
        }
        default:
            return;
    }
    const double area = emitter_area(light);
    m.emission = light.color * float(double(light.intensity) / (4.0 * std::numbers::pi * area));
    add_material(scene, m);
}

}  // namespace raylane
