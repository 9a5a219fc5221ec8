// bench: what bench_intersect's two parts share: the rays in SoA form and the Raylane packet
// contenders, which intersect_bench_packet.cpp defines once per instruction set (at the set's
// width) and intersect_bench.cpp times and registers. Compiled for the baseline and for every
// set, so it holds no SIMD types; nor can it include Google Benchmark's header, which runs code
// at start-up (a set's objects must not).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "accel/bvh.h"
#include "scene/scene.h"

namespace raylane::bench {

inline constexpr size_t chunk = 256;          ///< rays per task
inline constexpr size_t stream_rays = 16384;  ///< rays per task and stream of the Stream contenders
/// Primary rays per 16x16 tile, and shadow rays per tile and light: a block of the Block
/// contenders (max_block_rays, traverse/intersect_block.h).
inline constexpr size_t tile_rays = 256;

/// A ray set in SoA form, padded with inactive rays (t_max = -1) to a multiple of `chunk`, so
/// every contender reads its rays without repacking (as a renderer generating them would).
struct RaySoa {
    size_t size = 0;          ///< real rays; the padding follows
    std::vector<float> c[8];  ///< org x y z, dir x y z, t_min, t_max
    const float* at(int k, size_t i) const { return c[k].data() + i; }
};

/// Traces rays [first, last) of a ray set (whole packets; padding lanes are inactive): closest
/// hits, or any hit with `any_hit` (shadow rays).
using TraceRays = void (*)(const SceneData& scene, const Accel& accel, const RaySoa& rays,
                           bool any_hit, size_t first, size_t last);

/// A Raylane packet contender of one instruction set.
struct PacketContender {
    std::string name;  ///< its benchmarks' names after "BM_Intersect_": "Packet8", "Block16Sah"
    TraceRays trace = nullptr;
    BvhBuild build = BvhBuild::median;  ///< the tree it traverses
    size_t rays_per_task = chunk;       ///< the rays each task traces (a multiple of `chunk`)
};

/// Makes the compiler treat `value` as read, so that the work producing it stays (Google
/// Benchmark's DoNotOptimize, for the code that cannot include its header).
template <class T>
inline void keep(const T& value) {
    asm volatile("" : : "r"(&value) : "memory");
}

}  // namespace raylane::bench
