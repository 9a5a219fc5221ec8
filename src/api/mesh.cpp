// api: raylane::Mesh (raylane/mesh.h): a triangle mesh from the caller's arrays or a model file,
// as a scene of one object, and the batch ray queries of query/intersect_batch.h over it.
#include "raylane/mesh.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>

#include "accel/bvh.h"
#include "api/guard.h"
#include "core/clock.h"
#include "io/load_mesh.h"
#include "io/model_path.h"
#include "query/intersect_batch.h"

namespace raylane {

/// A mesh as a scene of one object, so that every query goes through the same code as a render.
struct Mesh::State {
    SceneData scene;
    Accel accel;
    TriangleNormals normals;  ///< each triangle's unit normal, for Hits::normal
    double build_ms = 0.0;
};

namespace {

std::shared_ptr<const Mesh::State> build(MeshData mesh) {
    auto s = std::make_shared<Mesh::State>();
    const double t = now_seconds();
    s->scene.materials.push_back(Material{});
    if (!mesh.tris.empty()) {
        Object object;
        object.kind = ShapeKind::mesh;
        s->scene.objects.push_back(object);
    }
    s->scene.meshes.push_back(std::move(mesh));
    s->accel = build_accel(s->scene, BuildParams{});
    s->normals = make_triangle_normals(s->scene);
    s->build_ms = elapsed_ms(t);
    return s;
}

bool aligned(const void* p) { return reinterpret_cast<uintptr_t>(p) % alignof(float) == 0; }

/// Throws unless a float array the call reads or writes is usable: non-null when there are
/// rays, 4-byte aligned.
void check_array(const void* p, const char* name, size_t count, bool needed) {
    if (p == nullptr) {
        if (needed && count > 0)
            throw Error(std::string(name) + ": null, for " + std::to_string(count) + " rays");
        return;
    }
    if (!aligned(p)) throw Error(std::string(name) + ": not aligned to 4 bytes");
}

void check_stride(size_t stride, const char* name) {
    if (stride % sizeof(float) != 0)
        throw Error(std::string(name) + ": " + std::to_string(stride) +
                    " bytes, not a multiple of 4");
}

RayArrays ray_arrays(const Rays& rays) {
    check_array(rays.origins, "origins", rays.count, true);
    check_array(rays.directions, "directions", rays.count, true);
    check_array(rays.t_max, "t_max", rays.count, false);
    check_stride(rays.origin_stride, "origin_stride");
    check_stride(rays.direction_stride, "direction_stride");
    RayArrays a;
    a.org = rays.origins;
    a.dir = rays.directions;
    a.org_stride = rays.origin_stride / sizeof(float);
    a.dir_stride = rays.direction_stride / sizeof(float);
    a.t_max = rays.t_max;
    a.t_max_all = rays.t_max_all;
    a.count = rays.count;
    return a;
}

BatchParams batch_params(const QuerySettings& settings) {
    check_range("threads", settings.threads, 0, 1024);
    BatchParams p;
    p.path = settings.path == TracePath::scalar ? BatchPath::scalar : BatchPath::packet;
    p.coherence = settings.coherence;
    p.threads = settings.threads;
    return p;
}

}  // namespace

Mesh::Mesh(const float* vertices, size_t vertex_count, const uint32_t* triangles,
           size_t triangle_count) {
    state_ = guarded([&] {
        if (vertices == nullptr && vertex_count > 0) throw Error("vertices: null");
        if (triangles == nullptr && triangle_count > 0) throw Error("triangles: null");
        if (vertex_count > UINT32_MAX)
            throw Error("vertices: " + std::to_string(vertex_count) + ", more than 2^32 - 1");
        MeshData mesh;
        mesh.name = "<arrays>";
        mesh.positions.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) {
            const float* p = vertices + 3 * i;
            if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
                throw Error("vertices: row " + std::to_string(i) + " is not finite (" +
                            std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
                            std::to_string(p[2]) + ")");
            mesh.positions[i] = vec3(p[0], p[1], p[2]);
        }
        mesh.tris.resize(triangle_count);
        for (size_t i = 0; i < triangle_count; ++i) {
            for (int j = 0; j < 3; ++j) {
                const uint32_t index = triangles[3 * i + size_t(j)];
                if (index >= vertex_count)
                    throw Error("triangles: row " + std::to_string(i) + " holds index " +
                                std::to_string(index) + ", outside 0 .. " +
                                std::to_string(int64_t(vertex_count) - 1) + " (vertices has " +
                                std::to_string(vertex_count) + " rows)");
                mesh.tris[i][j] = index;
            }
        }
        return build(std::move(mesh));
    });
}

Mesh::Mesh(std::shared_ptr<const State> state) : state_(std::move(state)) {}

Mesh Mesh::load(const std::string& path) {
    return guarded([&] { return Mesh(build(load_mesh(find_model(path)))); });
}

void Mesh::intersect(const Rays& rays, const Hits& hits, const QuerySettings& settings) const {
    guarded([&] {
        const RayArrays a = ray_arrays(rays);
        check_array(hits.t, "t", rays.count, false);
        check_array(hits.triangle, "triangle", rays.count, false);
        check_array(hits.u, "u", rays.count, false);
        check_array(hits.v, "v", rays.count, false);
        check_array(hits.normal, "normal", rays.count, false);
        HitBuffers out;
        out.t = hits.t, out.prim = hits.triangle, out.u = hits.u, out.v = hits.v;
        out.normal = hits.normal;
        intersect_closest_batch(state_->scene, state_->accel, a, out, batch_params(settings),
                                &state_->normals);
    });
}

void Mesh::occluded(const Rays& rays, uint8_t* occluded, const QuerySettings& settings) const {
    guarded([&] {
        const RayArrays a = ray_arrays(rays);
        if (occluded == nullptr && rays.count > 0)
            throw Error("occluded: null, for " + std::to_string(rays.count) + " rays");
        intersect_any_batch(state_->scene, state_->accel, a, occluded, batch_params(settings));
    });
}

size_t Mesh::vertex_count() const { return state_->scene.meshes[0].positions.size(); }
size_t Mesh::triangle_count() const { return state_->scene.meshes[0].tris.size(); }

const float* Mesh::vertices() const {
    static_assert(sizeof(vec3) == 3 * sizeof(float));
    return reinterpret_cast<const float*>(state_->scene.meshes[0].positions.data());
}

const uint32_t* Mesh::triangles() const {
    static_assert(sizeof(uvec3) == 3 * sizeof(uint32_t));
    return reinterpret_cast<const uint32_t*>(state_->scene.meshes[0].tris.data());
}

double Mesh::build_ms() const { return state_->build_ms; }

std::string find_model(const std::string& name) {
    return guarded([&] {
        std::error_code ec;
        if (std::filesystem::exists(name, ec)) return name;
        return raylane::find_model(name, ".");
    });
}

}  // namespace raylane
