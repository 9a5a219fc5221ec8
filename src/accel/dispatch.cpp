// accel: the median-split build of the instruction set in use (core/isa.h). The build's vector
// loops are compiled once per set (build_median.cpp and the files it calls); every set builds the
// same tree.
#include "accel/bvh.h"
#include "core/isa.h"

#define RAYLANE_DECLARE(ns)                                                                \
    namespace raylane {                                                                    \
    inline namespace ns {                                                                  \
    Bvh build_bvh_median_isa(std::span<const Aabb> prim_bounds, const BuildParams& params, \
                             MedianSplitPaths* paths);                                     \
    MeshAccel build_mesh_accel_isa(const MeshData& mesh, const BuildParams& params);       \
    }                                                                                      \
    }
RAYLANE_FOR_EACH_ISA(RAYLANE_DECLARE)
#undef RAYLANE_DECLARE

namespace raylane {

Bvh build_bvh_median(std::span<const Aabb> prim_bounds, const BuildParams& params,
                     MedianSplitPaths* paths) {
    RAYLANE_DISPATCH(build_bvh_median_isa(prim_bounds, params, paths));
}

MeshAccel build_mesh_accel(const MeshData& mesh, const BuildParams& params) {
    RAYLANE_DISPATCH(build_mesh_accel_isa(mesh, params));
}

}  // namespace raylane
