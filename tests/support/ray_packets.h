// Test support: rays from a list loaded into packets, for tests that compare the packet path
// with the scalar path ray by ray.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/ray_packet.h"

namespace raylane {

/// W consecutive rays of the list from `first`; spare lanes of the tail packet are inactive and
/// benign (t_max = -1).
template <int W>
RayPacket<W> make_packet(const std::vector<Ray>& rays, size_t first, vmask<W>& active) {
    RayPacket<W> p;
    uint32_t b = 0;
    for (int i = 0; i < W; ++i) {
        Ray r;
        r.t_max = -1.0f;
        if (first + size_t(i) < rays.size()) {
            r = rays[first + size_t(i)];
            b |= 1u << i;
        }
        set_ray(p, i, r);
    }
    active = mask_from_bits<W>(b);
    return p;
}

}  // namespace raylane
