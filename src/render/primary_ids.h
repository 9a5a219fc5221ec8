// render: primary-hit agreement of the two paths, for `raylane compare` and the equivalence
// tests; primary_ids.cpp computes it once per instruction set, dispatch.cpp picks the set in use.
#pragma once

#include <cstddef>

#include "accel/bvh.h"
#include "scene/scene.h"

namespace raylane {

/// Primary rays through every pixel centre, traced by the scalar path and by the packet path
/// of the instruction set in use, at its width: the number of pixels whose hit (object and
/// primitive) differs.
size_t primary_id_mismatches(const SceneData& scene, const Accel& accel);

}  // namespace raylane
