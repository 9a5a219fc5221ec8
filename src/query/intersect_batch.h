// query: closest-hit and any-hit queries of a caller's arrays of rays (a NumPy array, a ray
// file), spread over threads: the scalar path ray by ray, or the packet path with coherent
// rays as blocks (intersect_block.h) and the others as streams (intersect_stream.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/bvh.h"
#include "raylane/mesh.h"  // Coherence
#include "scene/scene.h"

namespace raylane {

/// Rays as strided float arrays: ray i starts at org + i * org_stride (x, y, z) and goes along
/// dir + i * dir_stride. t_min is 0; t_max is t_max[i], or t_max_all when t_max is null.
/// An (N, 6) array of origin and direction is org = data, dir = data + 3, both strides 6.
struct RayArrays {
    const float* org = nullptr;
    const float* dir = nullptr;
    size_t org_stride = 3;  ///< floats from one ray's origin to the next
    size_t dir_stride = 3;
    const float* t_max = nullptr;
    float t_max_all = infinity;
    size_t count = 0;
};

/// Where the closest hits go, one entry per ray (normal: three floats per ray); a null
/// pointer is not written. A miss is t = inf, prim = object = -1, u = v = 0, normal 0.
struct HitBuffers {
    float* t = nullptr;
    int32_t* prim = nullptr;    ///< triangle index in its mesh
    int32_t* object = nullptr;  ///< index into SceneData::objects
    float* u = nullptr;         ///< barycentric weight of the triangle's second corner
    float* v = nullptr;         ///< and of its third
    float* normal = nullptr;    ///< unit geometric normal of a mesh triangle (winding side)
};

enum class BatchPath : uint8_t { scalar, packet };

/// How the packet path groups rays is the public raylane::Coherence (raylane/mesh.h):
/// `automatic` looks at each block of max_block_rays consecutive rays: a block whose directions
/// all lie within about 25 degrees of its first ray's (rays_coherent) goes through the block
/// traversal, the others through streams.

struct BatchParams {
    BatchPath path = BatchPath::packet;
    Coherence coherence = Coherence::automatic;
    int threads = 0;  ///< 0 = all hardware threads
};

/// The unit geometric normal of every triangle of every mesh (SceneData::meshes order), as
/// surface_at gives it, so that a batch writes HitBuffers::normal with one look-up per hit.
struct TriangleNormals {
    std::vector<std::vector<vec3>> meshes;
};
TriangleNormals make_triangle_normals(const SceneData& scene);

/// Rays per task of a batch: each task is a stream of at most this many rays.
inline constexpr size_t batch_task_rays = 16384;

/// Closest hits of every ray in (0, t_max). A ray whose origin or direction is not finite, whose
/// direction is zero, or whose t_max is not above 0 (NaN included) is a miss without being traced.
/// Both paths give the same hits, bit for bit (prim, object, t, u, v). Flush-to-zero is set while
/// tracing, as the renderers do, and the calling thread's floating-point modes are restored.
/// `normals`, when given, must be make_triangle_normals(scene); without it the normals are
/// computed hit by hit.
void intersect_closest_batch(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                             const HitBuffers& hits, const BatchParams& params,
                             const TriangleNormals* normals = nullptr);

/// Whether each ray hits anything in (0, t_max): occluded[i] is 1 or 0. Rays that are not
/// traced (see intersect_closest_batch) are 0.
void intersect_any_batch(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                         uint8_t* occluded, const BatchParams& params);

/// Whether rays first .. first + count - 1 point within about 25 degrees of each other (every
/// direction's cosine with the first traced ray's is at least 0.9); rays that are not traced
/// are left out.
bool rays_coherent(const RayArrays& rays, size_t first, size_t count);

}  // namespace raylane
