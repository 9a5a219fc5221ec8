// render: the packet renderer and the primary-hit comparison of the instruction set in use
// (core/isa.h); each is compiled once per set (render_packet.cpp, primary_ids.cpp).
#include "core/isa.h"
#include "render/primary_ids.h"
#include "render/render_packet.h"

#define RAYLANE_DECLARE(ns)                                                       \
    namespace raylane {                                                           \
    inline namespace ns {                                                         \
    RenderResult render_packet_isa(const SceneData& scene, const Accel& accel,    \
                                   const RenderParams& params);                   \
    size_t primary_id_mismatches_isa(const SceneData& scene, const Accel& accel); \
    }                                                                             \
    }
RAYLANE_FOR_EACH_ISA(RAYLANE_DECLARE)
#undef RAYLANE_DECLARE

namespace raylane {

RenderResult render_packet(const SceneData& scene, const Accel& accel, const RenderParams& params) {
    RAYLANE_DISPATCH(render_packet_isa(scene, accel, params));
}

size_t primary_id_mismatches(const SceneData& scene, const Accel& accel) {
    RAYLANE_DISPATCH(primary_id_mismatches_isa(scene, accel));
}

}  // namespace raylane
