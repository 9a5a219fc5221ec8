// render: the packet renderer: per tile, W-wide packets of primary rays traced and shaded
// together. Mirrors render_scalar.h; the same samples, so the same image up to rounding.
#pragma once

#include "accel/bvh.h"
#include "render/render_params.h"
#include "scene/scene.h"

namespace raylane {

/// Renders like render_scalar on the packet path of the instruction set in use (core/isa.h), at
/// its packet width.
RenderResult render_packet(const SceneData& scene, const Accel& accel, const RenderParams& params);

}  // namespace raylane

#if defined(RAYLANE_ISA_NS)  // in this instruction set's copy of the code (simd/namespace.h)
#include "simd/namespace.h"
namespace raylane::RAYLANE_ISA_NS {

/// render_packet in this set, at its packet width.
RenderResult render_packet_isa(const SceneData& scene, const Accel& accel,
                               const RenderParams& params);

/// The same at a chosen width (1, or any width this set runs), for tests and benchmarks.
template <int W>
RenderResult render_packet_width(const SceneData& scene, const Accel& accel,
                                 const RenderParams& params);

}  // namespace raylane::RAYLANE_ISA_NS
#endif
