// core: a single ray and its closest hit (the scalar reference path); mirrored by ray_packet.h.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>

namespace raylane {

using glm::vec2;
using glm::vec3;

// Every instruction set's copy of the packet path shares the scene and BVH structs with the
// baseline code (core/isa.h), so their GLM members must have one layout whatever the -march:
// GLM's plain types, never its SIMD-aligned ones (GLM_FORCE_DEFAULT_ALIGNED_GENTYPES).
static_assert(sizeof(glm::vec3) == 12 && alignof(glm::vec3) == 4);
static_assert(sizeof(glm::vec4) == 16 && alignof(glm::vec4) == 4);
static_assert(sizeof(glm::mat4) == 64 && alignof(glm::mat4) == 4);

inline constexpr float infinity = std::numeric_limits<float>::infinity();
inline constexpr uint32_t invalid_id = 0xffffffffu;

/// A ray o + t d, accepted for t in the open interval (t_min, t_max).
/// dir need not be unit length; inv_dir is the exact reciprocal (1 / d, computed by division).
struct Ray {
    vec3 org{0.0f};
    vec3 dir{0.0f, 0.0f, 1.0f};
    float t_min = 0.0f;
    float t_max = infinity;
};

/// The closest hit found so far. prim == invalid_id means no hit.
struct Hit {
    float t = infinity;
    uint32_t prim = invalid_id;    ///< triangle index in its mesh (0 for analytic shapes)
    uint32_t object = invalid_id;  ///< index into SceneData::objects
    vec2 uv{0.0f};                 ///< triangle barycentrics (u, v) or shape parameters
    bool hit() const { return prim != invalid_id; }
};

/// Counters a traversal keeps for one ray (the bvh-cost AOV and the benchmarks' counters).
struct TraversalStats {
    uint32_t nodes_visited = 0;  ///< BVH nodes whose box was tested, both levels
    uint32_t prims_tested = 0;   ///< primitive intersection tests
};

/// Exact reciprocal of each direction component (division, never rcp: numerics.md §0.2).
inline vec3 reciprocal(vec3 d) { return vec3(1.0f / d.x, 1.0f / d.y, 1.0f / d.z); }

}  // namespace raylane
