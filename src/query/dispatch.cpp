// query: the batch queries of the instruction set in use (core/isa.h), compiled once per set
// (intersect_batch.cpp).
#include "core/isa.h"
#include "query/intersect_batch.h"

#define RAYLANE_DECLARE(ns)                                                                      \
    namespace raylane {                                                                          \
    inline namespace ns {                                                                        \
    void intersect_closest_batch_isa(const SceneData& scene, const Accel& accel,                 \
                                     const RayArrays& rays, const HitBuffers& hits,              \
                                     const BatchParams& params, const TriangleNormals* normals); \
    void intersect_any_batch_isa(const SceneData& scene, const Accel& accel,                     \
                                 const RayArrays& rays, uint8_t* occluded,                       \
                                 const BatchParams& params);                                     \
    }                                                                                            \
    }
RAYLANE_FOR_EACH_ISA(RAYLANE_DECLARE)
#undef RAYLANE_DECLARE

namespace raylane {

void intersect_closest_batch(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                             const HitBuffers& hits, const BatchParams& params,
                             const TriangleNormals* normals) {
    RAYLANE_DISPATCH(intersect_closest_batch_isa(scene, accel, rays, hits, params, normals));
}

void intersect_any_batch(const SceneData& scene, const Accel& accel, const RayArrays& rays,
                         uint8_t* occluded, const BatchParams& params) {
    RAYLANE_DISPATCH(intersect_any_batch_isa(scene, accel, rays, occluded, params));
}

}  // namespace raylane
