// raylane/mesh.h: ray queries against a triangle mesh: closest hits and occlusion of a batch of
// rays given as arrays, written into arrays the caller owns, on all threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

#include "raylane/scene.h"  // TracePath

namespace raylane {

/// A batch of rays as strided arrays, as NumPy lays them out: ray i's origin is the three floats
/// at byte offset i * origin_stride from `origins`, its direction those at i * direction_stride
/// from `directions` (both strides multiples of 4; an (N, 6) array is origins = data,
/// directions = data + 3, strides 24). Each ray is traced over (0, t_max).
struct Rays {
    size_t count = 0;
    const float* origins = nullptr;
    size_t origin_stride = 3 * sizeof(float);
    const float* directions = nullptr;
    size_t direction_stride = 3 * sizeof(float);
    const float* t_max = nullptr;  ///< one per ray, contiguous; null: every ray's is t_max_all
    float t_max_all = std::numeric_limits<float>::infinity();
};

/// Where closest hits go, `count` entries each (normal: 3 floats per ray); a null array is not
/// written. A miss is t = inf, triangle = -1, u = v = 0, normal 0.
struct Hits {
    float* t = nullptr;
    int32_t* triangle = nullptr;  ///< index of the triangle hit
    float* u = nullptr;           ///< barycentric weight of the triangle's second corner
    float* v = nullptr;           ///< and of its third
    float* normal = nullptr;      ///< unit geometric normal, on the side the winding gives
};

/// How the packet path groups rays: `automatic` sends each run of rays that point within about
/// 25 degrees of each other through the block traversal, the others through streams.
enum class Coherence { automatic, coherent, incoherent };

struct QuerySettings {
    TracePath path = TracePath::packet;
    Coherence coherence = Coherence::automatic;
    int threads = 0;  ///< 0 = all
};

/// A triangle mesh and its BVHs, built once. Queries may run from any number of threads at once.
/// Both paths give the same hits, bit for bit. A ray whose origin or direction is not finite,
/// whose direction is zero or whose t_max is not above 0 is a miss without being traced.
class Mesh {
  public:
    /// Copies `vertex_count` vertices (x, y, z each) and `triangle_count` triangles (three
    /// vertex indices each) and builds the BVHs. Throws Error for a null array with a non-zero
    /// count, a vertex that is not finite or an index out of range. Zero-area triangles are
    /// kept (they are never hit) so that triangle indices stay the caller's.
    Mesh(const float* vertices, size_t vertex_count, const uint32_t* triangles,
         size_t triangle_count);
    /// Loads an OBJ or PLY model (.obj, .ply, optionally .gz); a relative name that is not a
    /// file is looked up on RAYLANE_MODEL_PATH. Zero-area faces are dropped, as in a scene.
    static Mesh load(const std::string& path);

    /// The closest hit of each ray. Throws Error when an array the call needs is null.
    void intersect(const Rays& rays, const Hits& hits, const QuerySettings& settings = {}) const;
    /// Whether each ray hits anything: occluded[i] is 1 or 0.
    void occluded(const Rays& rays, uint8_t* occluded, const QuerySettings& settings = {}) const;

    size_t vertex_count() const;
    size_t triangle_count() const;
    const float* vertices() const;      ///< x, y, z of each vertex
    const uint32_t* triangles() const;  ///< three vertex indices per triangle
    double build_ms() const;            ///< time the BVH build took

    struct State;  ///< the implementation (src/api/), opaque here

  private:
    explicit Mesh(std::shared_ptr<const State> state);
    std::shared_ptr<const State> state_;
};

/// The file a model name names: `name` itself when it is a file or an absolute path, else the
/// first folder on RAYLANE_MODEL_PATH that holds it. Throws Error naming every folder searched.
std::string find_model(const std::string& name);

}  // namespace raylane
