// io: the objects of the scene format (SceneReader, io/scene_reader.h): analytic shapes and
// meshes, their transforms, the "fit" of a mesh, and the baking of meshes into world space.
#include <cmath>
#include <string>

#include "core/error.h"
#include "io/load_mesh.h"
#include "io/model_path.h"
#include "io/scene_reader.h"
#include "scene/mesh_normals.h"
#include "scene/split_mesh.h"
#include "scene/transform.h"

namespace raylane {

namespace {

bool all_finite(const mat4& m) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(m[c][r])) return false;
        }
    }
    return true;
}

}  // namespace

Transform SceneReader::read_transform(const Node& n) const {
    expect_keys(n, {"translate", "rotate", "rotate_deg", "scale"});
    Transform t;
    if (const Json* v = find(n, "translate")) {
        t.translate = dvec3(Node{v, member_path(n.path, "translate")});
    }
    const Json* rotate = find(n, "rotate");
    const Json* rotate_deg = find(n, "rotate_deg");
    if (rotate && rotate_deg) {
        fail(child(n, "rotate_deg"), "give either rotate or rotate_deg, not both");
    }
    if (rotate) {
        Node list{rotate, member_path(n.path, "rotate")};
        expect(list, rotate->is_array(), "an array of {\"axis\", \"deg\"} rotations");
        // Written as a product, like T * R * S: the last rotation is applied first.
        for (size_t i = 0; i < rotate->size(); ++i) {
            Node r{&(*rotate)[i], element_path(list.path, i)};
            expect_keys(r, {"axis", "deg"});
            int axis = choice(child(r, "axis"), {"x", "y", "z"});
            t.rotate = t.rotate * make_rotation(axis, number(child(r, "deg")));
        }
    }
    if (rotate_deg) {
        t.rotate = make_rotation_xyz(dvec3(Node{rotate_deg, member_path(n.path, "rotate_deg")}));
    }
    if (const Json* v = find(n, "scale")) {
        Node s{v, member_path(n.path, "scale")};
        if (v->is_number()) {
            t.scale = glm::dvec3(number(s));
        } else {
            expect(s, v->is_array() && v->size() == 3, "a number or an array of 3 numbers");
            t.scale = dvec3(s);
        }
        if (t.scale.x == 0.0 || t.scale.y == 0.0 || t.scale.z == 0.0) {
            fail(s, "must not be zero (the transform would not be invertible)");
        }
    }
    return t;
}

/// The "fit" normalisation of a mesh with the given bounds (see transform.h, make_fit).
glm::dmat4 SceneReader::read_fit(const Node& n, const Aabb& bounds) const {
    expect_keys(n, {"size", "axis", "scale", "offset"});
    const Json* size = find(n, "size");
    const Json* scale = find(n, "scale");
    if (size && scale) fail(child(n, "scale"), "give either size or scale, not both");
    if (!size && !scale) fail(n, "needs \"size\" or \"scale\"");
    double s = 0.0;
    if (scale) {
        if (find(n, "axis")) fail(child(n, "axis"), "only goes with \"size\"");
        s = number(child(n, "scale"), Sign::positive);
    } else {
        int axis = bounds.empty() ? 0 : bounds.longest_axis();
        if (const Json* v = find(n, "axis")) {
            int a = choice(Node{v, member_path(n.path, "axis")}, {"x", "y", "z", "longest"});
            if (a < 3) axis = a;
        }
        double extent = bounds.empty() ? 0.0 : double(bounds.extent()[axis]);
        if (!(extent > 0.0)) {
            fail(n, std::string("the mesh has no extent along ") + "xyz"[axis] + " to fit");
        }
        s = number(child(n, "size"), Sign::positive) / extent;
    }
    glm::dvec3 offset(0.0);
    if (const Json* v = find(n, "offset")) {
        offset = dvec3(Node{v, member_path(n.path, "offset")});
    }
    return make_fit(bounds, s, offset);
}

void SceneReader::read_object(const Node& n, SceneData& scene) {
    expect(n, n.j->is_object(), "an object");
    constexpr ShapeKind kinds[] = {ShapeKind::sphere, ShapeKind::box,      ShapeKind::cylinder,
                                   ShapeKind::plane,  ShapeKind::triangle, ShapeKind::mesh};
    Object object;
    object.kind = kinds[choice(child(n, "shape"),
                               {"sphere", "box", "cylinder", "plane", "triangle", "mesh"})];
    expect_shape_keys(n, object.kind);
    object.material = material_index(n, scene);
    Transform t;
    if (const Json* v = find(n, "transform")) {
        t = read_transform(Node{v, member_path(n.path, "transform")});
    }
    // A shape with a transform (and every cylinder and mesh) is given in its own space and
    // the transform takes it to the world; without one its points are world points. Either
    // way it moves with the world origin.
    const bool own_space =
        !is_identity(t) || object.kind == ShapeKind::cylinder || object.kind == ShapeKind::mesh;
    if (own_space) t.translate -= world_origin_;
    if (object.kind == ShapeKind::mesh) {
        // Baked into world space: the object keeps the identity transform.
        read_mesh(n, t, object, scene);
        return;
    }
    read_shape(n, own_space, object, scene);
    set_transform(object, t);
    if (!all_finite(object.world_from_object) || !all_finite(object.object_from_world)) {
        fail(find(n, "transform") ? child(n, "transform") : n,
             "the matrix overflows the float range");
    }
    scene.objects.push_back(object);
}

/// An object of shape `kind` has only that shape's keys.
void SceneReader::expect_shape_keys(const Node& n, ShapeKind kind) const {
    switch (kind) {
        case ShapeKind::sphere:
            expect_keys(n, {"shape", "material", "transform", "center", "radius"});
            break;
        case ShapeKind::box:
            expect_keys(n, {"shape", "material", "transform", "min", "max"});
            break;
        case ShapeKind::cylinder:
            expect_keys(n, {"shape", "material", "transform", "radius", "height"});
            break;
        case ShapeKind::plane:
            expect_keys(n, {"shape", "material", "transform", "point", "normal"});
            break;
        case ShapeKind::triangle:
            expect_keys(n, {"shape", "material", "transform", "vertices"});
            break;
        case ShapeKind::mesh:
            expect_keys(n, {"shape", "material", "transform", "file", "fit", "normals"});
            break;
    }
}

/// The analytic shape of an object (not a mesh): appended to its scene array, its index in
/// object.shape. Its points are in its own space or, when not `own_space`, world points.
void SceneReader::read_shape(const Node& n, bool own_space, Object& object,
                             SceneData& scene) const {
    auto shape_point = [&](const Node& p) { return own_space ? vector(p) : point(p); };
    const vec3 shape_origin = own_space ? vec3(0.0f) : vec3(-world_origin_);
    switch (object.kind) {
        case ShapeKind::sphere: {
            Sphere s;
            s.center = shape_origin;
            if (const Json* v = find(n, "center")) {
                s.center = shape_point(Node{v, member_path(n.path, "center")});
            }
            s.radius = real(child(n, "radius"), Sign::positive);
            object.shape = uint32_t(scene.spheres.size());
            scene.spheres.push_back(s);
            break;
        }
        case ShapeKind::box: {
            Box b;
            Node hi = child(n, "max");
            b.lo = shape_point(child(n, "min"));
            b.hi = shape_point(hi);
            if (!(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z)) {
                fail(hi, "must be >= min in every component");
            }
            object.shape = uint32_t(scene.boxes.size());
            scene.boxes.push_back(b);
            break;
        }
        case ShapeKind::cylinder: {
            Cylinder c;
            c.radius = real(child(n, "radius"), Sign::positive);
            c.height = real(child(n, "height"), Sign::positive);
            object.shape = uint32_t(scene.cylinders.size());
            scene.cylinders.push_back(c);
            break;
        }
        case ShapeKind::plane: {
            Plane p;
            p.point = shape_origin;
            if (const Json* v = find(n, "point")) {
                p.point = shape_point(Node{v, member_path(n.path, "point")});
            }
            p.normal = direction(child(n, "normal"));
            object.shape = uint32_t(scene.planes.size());
            scene.planes.push_back(p);
            break;
        }
        case ShapeKind::triangle: {
            Node verts = child(n, "vertices");
            expect(verts, verts.j->is_array() && verts.j->size() == 3, "an array of 3 points");
            Triangle tri;
            tri.p0 = shape_point(Node{&(*verts.j)[0], element_path(verts.path, 0)});
            tri.p1 = shape_point(Node{&(*verts.j)[1], element_path(verts.path, 1)});
            tri.p2 = shape_point(Node{&(*verts.j)[2], element_path(verts.path, 2)});
            glm::dvec3 e1 = glm::dvec3(tri.p1) - glm::dvec3(tri.p0);
            glm::dvec3 e2 = glm::dvec3(tri.p2) - glm::dvec3(tri.p0);
            if (glm::cross(e1, e2) == glm::dvec3(0.0)) {
                fail(verts, "the triangle has zero area");
            }
            object.shape = uint32_t(scene.triangles.size());
            scene.triangles.push_back(tri);
            break;
        }
        case ShapeKind::mesh:  // read_mesh
            break;
    }
}

/// Loads (once per file), fits and bakes a mesh into world space, and appends it to
/// scene.meshes with `object` to scene.objects. An object with a "material" key gives it to
/// every face; without one, a file that names materials gives one mesh and object per material
/// (split_by_material, model_material), the faces it leaves unnamed the default material.
void SceneReader::read_mesh(const Node& n, const Transform& t, Object object, SceneData& scene) {
    Node file = child(n, "file");
    std::string name = text(file);
    std::string resolved;
    try {
        resolved = find_model(name, dir_);
    } catch (const InputError& e) {
        fail(file, e.what());
    }
    auto it = meshes_.find(resolved);
    if (it == meshes_.end()) it = meshes_.emplace(resolved, load_mesh(resolved)).first;
    // the file's last object takes the mesh: a copy is megabytes of fresh pages
    const bool last_use = --mesh_uses_[resolved] <= 0;
    MeshData mesh = last_use ? std::move(meshes_.extract(it).mapped()) : it->second;
    if (mesh.name.empty()) mesh.name = name;
    // normals: "auto" (the file's, else smooth), "file", "smooth" or "flat"
    const char* modes[] = {"auto", "file", "smooth", "flat"};
    const int mode = find(n, "normals")
                         ? choice(child(n, "normals"), {modes[0], modes[1], modes[2], modes[3]})
                         : 0;
    if (mode == 1 && mesh.normal_tris.empty())
        fail(child(n, "normals"), "the mesh file has no normals");
    if (mode == 2 || (mode == 0 && mesh.normal_tris.empty())) compute_smooth_normals(mesh);
    if (mode == 3) drop_normals(mesh);
    glm::dmat4 world_from_object = make_world_from_object(t);
    if (const Json* v = find(n, "fit")) {
        world_from_object =
            world_from_object * read_fit(Node{v, member_path(n.path, "fit")}, mesh_bounds(mesh));
    }
    bake_transform(mesh, world_from_object);
    for (vec3 p : mesh.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            fail(n, "the transform moves mesh positions outside the float range");
        }
    }
    // an object that names its material gives it to every face; else the file's own materials
    if (find(n, "material")) mesh.material_names.clear();
    const std::vector<std::string> libraries = mesh.material_libraries;
    const uint32_t own = object.material;
    for (MeshPart& part : split_by_material(std::move(mesh))) {
        object.material = part.material.empty()
                              ? own
                              : model_material(part.material, resolved, libraries, own, scene);
        object.shape = uint32_t(scene.meshes.size());
        scene.meshes.push_back(std::move(part.mesh));
        scene.objects.push_back(object);
    }
}

}  // namespace raylane
