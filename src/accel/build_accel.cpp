// accel: the two-level acceleration structure: a median-split BVH per mesh (triangles reordered
// to leaf order) and a top-level median-split BVH over the bounded objects.
#include "accel/bvh.h"

namespace raylane {
namespace {

Aabb transformed(const Aabb& box, const mat4& m) {
    Aabb out;
    for (int corner = 0; corner < 8; ++corner) {
        vec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
               (corner & 4) ? box.hi.z : box.lo.z);
        out.grow(vec3(m * glm::vec4(p, 1.0f)));
    }
    return out;
}

}  // namespace

BuildParams build_params(std::string_view bvh) {
    BuildParams params;
    params.method = bvh == "sah" ? BvhBuild::sah : BvhBuild::median;
    return params;
}

Aabb object_bounds(const SceneData& scene, const Object& object) {
    Aabb box;
    switch (object.kind) {
        case ShapeKind::sphere: {
            const Sphere& s = scene.spheres[object.shape];
            box = {s.center - vec3(s.radius), s.center + vec3(s.radius)};
            break;
        }
        case ShapeKind::box:
            box = {scene.boxes[object.shape].lo, scene.boxes[object.shape].hi};
            break;
        case ShapeKind::cylinder: {
            const Cylinder& c = scene.cylinders[object.shape];
            box = {vec3(-c.radius, 0.0f, -c.radius), vec3(c.radius, c.height, c.radius)};
            break;
        }
        case ShapeKind::plane:
            return {};  // unbounded
        case ShapeKind::triangle: {
            const Triangle& t = scene.triangles[object.shape];
            for (vec3 p : {t.p0, t.p1, t.p2})
                box.grow(object.has_transform ? vec3(object.world_from_object * glm::vec4(p, 1.0f))
                                              : p);
            return box;
        }
        case ShapeKind::mesh: {
            for (vec3 p : scene.meshes[object.shape].positions) box.grow(p);
            return box;  // meshes are in world space
        }
    }
    return object.has_transform ? transformed(box, object.world_from_object) : box;
}

Accel build_accel(const SceneData& scene, const BuildParams& params) {
    Accel accel;
    accel.meshes.reserve(scene.meshes.size());
    for (const MeshData& mesh : scene.meshes)
        accel.meshes.push_back(build_mesh_accel(mesh, params));
    std::vector<Aabb> bounded;
    std::vector<uint32_t> bounded_ids;
    accel.object_bounds.resize(scene.objects.size());
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& object = scene.objects[i];
        if (object.kind == ShapeKind::plane) {
            accel.unbounded.push_back(static_cast<uint32_t>(i));
            continue;
        }
        accel.object_bounds[i] = object_bounds(scene, object);
        if (accel.object_bounds[i].empty()) continue;  // an empty mesh: nothing to hit
        bounded.push_back(accel.object_bounds[i]);
        bounded_ids.push_back(static_cast<uint32_t>(i));
    }
    accel.top = params.method == BvhBuild::sah ? build_bvh_sah(bounded, params)
                                               : build_bvh_median(bounded, params);
    for (uint32_t& id : accel.top.prim_ids) id = bounded_ids[id];  // leaf order -> object index
    return accel;
}

}  // namespace raylane
