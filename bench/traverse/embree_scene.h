// bench: Embree 3 restricted to one instruction set, for bench_intersect's Embree contenders:
// one device per set, and meshes as a scene on it.
#pragma once

#include <embree3/rtcore.h>

#include <map>
#include <string>
#include <vector>

#include "core/isa.h"
#include "scene/scene.h"

namespace raylane::bench {

/// Embree's device for an instruction set, made on first use with the configuration
/// "isa=<set>": Embree 3.13 takes Raylane's names (sse4.2, avx2, avx512) and then runs that
/// set's kernels alone. (It takes an unknown name for SSE2, silently.)
inline RTCDevice embree_device(Isa isa) {
    static std::map<Isa, RTCDevice> devices;
    RTCDevice& device = devices[isa];
    if (!device) device = rtcNewDevice((std::string("isa=") + isa_name(isa)).c_str());
    return device;
}

/// The meshes (their own coordinates) as one committed scene on the set's device.
inline RTCScene make_embree_scene(Isa isa, const std::vector<MeshData>& meshes) {
    RTCDevice device = embree_device(isa);
    RTCScene scene = rtcNewScene(device);
    for (const MeshData& mesh : meshes) {
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              mesh.positions.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            for (int k = 0; k < 3; ++k) v[3 * i + size_t(k)] = mesh.positions[i][k];
        auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.tris.size()));
        for (size_t i = 0; i < mesh.tris.size(); ++i)
            for (int k = 0; k < 3; ++k) idx[3 * i + size_t(k)] = mesh.tris[i][k];
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
    return scene;
}

}  // namespace raylane::bench
