// render: the packet renderer's analysis images (aov_packet.h).
#include "render/aov_packet.h"

#include "traverse/intersect_block.h"
#include "traverse/intersect_packet.h"
#include "traverse/surface_packet.h"

namespace raylane::RAYLANE_ISA_NS {

template <int W>
void aov_values(const SceneData& scene, const Accel& accel, const RayPacket<W>* rays,
                const vmask<W>* active, int count, Aov aov, Vec3<W>* value) {
    constexpr int max_packets = max_block_rays / W;
    HitPacket<W> hits[max_packets];
    vmask<W> hit[max_packets];
    vint<W> nodes[max_packets];
    if (aov == Aov::bvh_cost) {
        // the cost of each ray on its own (a packet's traversal would give every lane the
        // packet's count): single-lane traversals, the scalar path's node counts
        for (int p = 0; p < count; ++p) {
            nodes[p] = vint<W>(0);
            hits[p] = HitPacket<W>{};
            for_each_active(active[p], [&](int i) {
                RayPacket<1> one;
                one.org = make_vec3<1>(get(rays[p].org.x, i), get(rays[p].org.y, i),
                                       get(rays[p].org.z, i));
                one.dir = make_vec3<1>(get(rays[p].dir.x, i), get(rays[p].dir.y, i),
                                       get(rays[p].dir.z, i));
                one.t_min = get(rays[p].t_min, i);
                one.t_max = get(rays[p].t_max, i);
                int32_t n = 0;
                const HitPacket<1> h = intersect_closest<1>(scene, accel, one, true, &n);
                set(nodes[p], i, n);
                set(hits[p].t, i, h.t);
            });
        }
    } else {
        intersect_closest_block(scene, accel, rays, active, hits, count);
    }
    for (int p = 0; p < count; ++p) hit[p] = mask_and(active[p], hits[p].t < vfloat<W>(infinity));
    const Vec3<W> black = make_vec3<W>(0.0f, 0.0f, 0.0f);
    for (int p = 0; p < count; ++p) {
        switch (aov) {
            case Aov::color:
                value[p] = black;
                break;
            case Aov::normal:
                value[p] =
                    any(hit[p])
                        ? select(hit[p], surface_at(scene, rays[p], hits[p], hit[p]).shading_normal,
                                 black)
                        : black;
                break;
            case Aov::depth: {
                const vfloat<W> t = select(hit[p], hits[p].t, vfloat<W>(0.0f));
                value[p] = {t, t, t};
                break;
            }
            case Aov::bvh_cost: {
                const vfloat<W> n = to_float(nodes[p]);
                value[p] = {n, n, n};
                break;
            }
        }
    }
}

// Instantiations: the widths of this instruction set (RAYLANE_FOR_EACH_WIDTH, simd/simd.h).
#define RAYLANE_INSTANTIATE(W)                                                       \
    template void aov_values<W>(const SceneData&, const Accel&, const RayPacket<W>*, \
                                const vmask<W>*, int, Aov, Vec3<W>*);
RAYLANE_FOR_EACH_WIDTH(RAYLANE_INSTANTIATE)
#undef RAYLANE_INSTANTIATE

}  // namespace raylane::RAYLANE_ISA_NS
