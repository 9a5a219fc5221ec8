// bench: bench_intersect's Raylane packet contenders, compiled once per instruction set
// (raylane_isa_objects) at the set's width W: Packet<W> (intersect_closest / intersect_any per
// packet), Block<W> (blocks of max_block_rays rays), Stream<W> (streams of stream_rays rays),
// and Packet<W>Sah and Block<W>Sah through the binned SAH build. intersect_bench.cpp times them.
#include <string>
#include <vector>

#include "traverse/intersect_block.h"
#include "traverse/intersect_contenders.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_stream.h"

namespace raylane::RAYLANE_ISA_NS {

namespace {

using bench::keep;
using bench::RaySoa;

/// Packet of rays i .. i + W - 1 straight from the SoA arrays; padding lanes are inactive.
template <int W>
RayPacket<W> load_packet(const RaySoa& s, size_t i, vmask<W>& active) {
    RayPacket<W> p;
    p.org = load_vec3<W>(s.at(0, i), s.at(1, i), s.at(2, i));
    p.dir = load_vec3<W>(s.at(3, i), s.at(4, i), s.at(5, i));
    p.t_min = load<W>(s.at(6, i));
    p.t_max = load<W>(s.at(7, i));
    active = p.t_max >= p.t_min;
    return p;
}

/// One packet at a time.
template <int W>
void trace_packets(const SceneData& scene, const Accel& accel, const RaySoa& soa, bool any_hit,
                   size_t first, size_t last) {
    for (size_t i = first; i < last; i += W) {
        vmask<W> active;
        const RayPacket<W> p = load_packet<W>(soa, i, active);
        if (none(active)) continue;  // a shadow packet whose primary rays all missed
        if (any_hit) {
            keep(intersect_any(scene, accel, p, active));
        } else {
            keep(intersect_closest(scene, accel, p, active));
        }
    }
}

/// Blocks of max_block_rays consecutive rays (a 16x16 tile for the primary rays).
template <int W>
void trace_blocks(const SceneData& scene, const Accel& accel, const RaySoa& soa, bool any_hit,
                  size_t first, size_t last) {
    static_assert(bench::tile_rays == size_t(max_block_rays));  // a block per tile
    static_assert(bench::chunk % max_block_rays == 0);          // tasks hold whole blocks
    constexpr int per_block = max_block_rays / W;
    RayPacket<W> p[per_block];
    vmask<W> active[per_block], occluded[per_block];
    HitPacket<W> hits[per_block];
    for (size_t b = first; b < last; b += max_block_rays) {
        int count = 0;
        for (size_t i = b; i < b + max_block_rays; i += W, ++count)
            p[count] = load_packet<W>(soa, i, active[count]);
        if (any_hit) {
            intersect_any_block(scene, accel, p, active, occluded, count);
            keep(occluded[0]);
        } else {
            intersect_closest_block(scene, accel, p, active, hits, count);
            keep(hits[0]);
        }
    }
}

/// The rays [first, last) as one stream through intersect_closest_stream / intersect_any_stream.
template <int W>
void trace_stream(const SceneData& scene, const Accel& accel, const RaySoa& soa, bool any_hit,
                  size_t first, size_t last) {
    thread_local std::vector<RayPacket<W>> p;
    thread_local std::vector<vmask<W>> active, occluded;
    thread_local std::vector<HitPacket<W>> hits;
    const size_t count = (last - first) / W;
    p.resize(count), active.resize(count), occluded.resize(count), hits.resize(count);
    for (size_t k = 0; k < count; ++k) p[k] = load_packet<W>(soa, first + k * W, active[k]);
    if (any_hit) {
        intersect_any_stream(scene, accel, p.data(), active.data(), occluded.data(), int(count));
        keep(occluded[0]);
    } else {
        intersect_closest_stream(scene, accel, p.data(), active.data(), hits.data(), int(count));
        keep(hits[0]);
    }
}

}  // namespace

/// This set's contenders at its width, for bench_intersect to register.
std::vector<bench::PacketContender> intersect_packet_contenders() {
    constexpr int W = native_width;
    const std::string w = std::to_string(W);
    return {
        {"Packet" + w, trace_packets<W>},
        {"Block" + w, trace_blocks<W>},
        {"Stream" + w, trace_stream<W>, BvhBuild::median, bench::stream_rays},
        // again through the SAH build (a comparison option: the rays are the same, the tree is
        // not the report's)
        {"Packet" + w + "Sah", trace_packets<W>, BvhBuild::sah},
        {"Block" + w + "Sah", trace_blocks<W>, BvhBuild::sah},
    };
}

}  // namespace raylane::RAYLANE_ISA_NS
