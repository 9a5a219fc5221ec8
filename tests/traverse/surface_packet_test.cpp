// Equivalence of the packet surface_at (traverse/surface_packet.cpp) with the scalar one: the
// same position, normals, uv and material bit for bit in every hit lane, at every packet width,
// for packets of one object (a mesh's triangles gathered W at a time, a plane W at a time) and
// of several objects (lane by lane): a mesh with normals and uvs of its own (the apple), two
// meshes in one scene (the apple and the bunny, which has neither), analytic shapes. Inactive
// lanes hold out-of-range ids, which the packet path must not read.
#include "traverse/surface_packet.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "support/widths.h"
#include "traverse/intersect_packet.h"
#include "traverse/intersect_scalar.h"
#include "traverse/surface_scalar.h"

namespace raylane {
namespace {

template <class T>
class SurfaceAtPacket : public ::testing::Test {};
TYPED_TEST_SUITE(SurfaceAtPacket, Widths, WidthName);

struct RayHit {
    Ray ray;
    Hit hit;
};

/// The camera rays of a width x height image that hit something, in image order.
std::vector<RayHit> camera_hits(SceneData& scene, const Accel& accel, int width, int height) {
    scene.camera.width = width;
    scene.camera.height = height;
    const CameraFrame frame = make_camera_frame(scene.camera);
    std::vector<RayHit> out;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const Ray r = camera_ray(frame, float(x) + 0.5f, float(y) + 0.5f);
            const Hit h = intersect_closest(scene, accel, r);
            if (h.hit()) out.push_back({r, h});
        }
    }
    return out;
}

/// Packets of up to W consecutive entries of `hits`; with `one_object`, a packet also ends where
/// the object changes. `mixed` counts the lanes on another object than their packet's first.
template <int W>
void check_packets(const SceneData& scene, const std::vector<RayHit>& hits, bool one_object,
                   const std::string& what, int& mixed) {
    mixed = 0;
    for (size_t first = 0; first < hits.size();) {
        size_t last = std::min(first + W, hits.size());
        if (one_object) {
            for (size_t i = first + 1; i < last; ++i) {
                if (hits[i].hit.object != hits[first].hit.object) {
                    last = i;
                    break;
                }
            }
        }
        RayPacket<W> rays;
        HitPacket<W> packet;
        packet.prim = vint<W>(0x7ffffff0);  // inactive lanes: ids far out of range
        packet.object = vint<W>(0x7ffffff0);
        uint32_t lanes = 0;
        for (size_t i = first; i < last; ++i) {
            const int l = int(i - first);
            set_ray(rays, l, hits[i].ray);
            set(packet.t, l, hits[i].hit.t);
            set(packet.prim, l, int32_t(hits[i].hit.prim));
            set(packet.object, l, int32_t(hits[i].hit.object));
            set(packet.u, l, hits[i].hit.uv.x);
            set(packet.v, l, hits[i].hit.uv.y);
            lanes |= 1u << l;
            mixed += i > first && hits[i].hit.object != hits[first].hit.object;
        }
        const SurfacePacket<W> sp = surface_at<W>(scene, rays, packet, mask_from_bits<W>(lanes));
        for (size_t i = first; i < last; ++i) {
            const int l = int(i - first);
            const SurfacePoint s = surface_at(scene, hits[i].ray, hits[i].hit);
            const std::string where =
                what + ", lane " + std::to_string(l) + " of packet at " + std::to_string(first);
            ASSERT_EQ(get_vec3(sp.position, l), s.position) << where;
            ASSERT_EQ(get_vec3(sp.geometric_normal, l), s.geometric_normal) << where;
            ASSERT_EQ(get_vec3(sp.shading_normal, l), s.shading_normal) << where;
            ASSERT_EQ(get(sp.u, l), s.uv.x) << where;
            ASSERT_EQ(get(sp.v, l), s.uv.y) << where;
            ASSERT_EQ(uint32_t(get(sp.material, l)), s.material) << where;
        }
        first = last;
    }
}

/// The apple beside the bunny, on a floor: two meshes, one with normals and uvs, one without.
SceneData two_meshes() {
    return load_scene_from_string(R"({
      "version": 1,
      "camera": {"position": [0, 0.6, -2.2], "look_at": [0, 0.1, 0], "fov_deg": 50,
                 "resolution": [64, 48], "spp": 1},
      "materials": {"m": {"c_d": [0.5, 0.5, 0.5], "k_d": 0.5},
                    "apple": {"c_d": [0.8, 0.2, 0.1], "k_d": 0.5}},
      "objects": [
        {"shape": "plane", "point": [0, -0.3, 0], "normal": [0, 1, 0], "material": "m"},
        {"shape": "mesh", "file": "apple/food_apple_01_4k.obj", "material": "apple",
         "fit": {"size": 0.8}, "transform": {"translate": [-0.45, -0.3, 0]}},
        {"shape": "mesh", "file": "bunny.ply", "material": "m",
         "fit": {"size": 0.8}, "transform": {"translate": [0.45, -0.3, 0]}}
      ],
      "lights": [{"type": "point", "position": [0, 3, -2], "intensity": 10}]
    })",
                                  std::string(RAYLANE_SOURCE_DIR) + "/scenes/two_meshes.json");
}

TYPED_TEST(SurfaceAtPacket, SameSurfaceAsTheScalarPath) {
    constexpr int W = TypeParam::value;
    for (const std::string name : {"fig07b_apple_normal_map", "two meshes", "builtin"}) {
        SceneData scene;
        if (name == "builtin")
            scene = make_builtin_scene();
        else if (name == "two meshes")
            scene = two_meshes();
        else
            scene = load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name + ".json");
        const Accel accel = build_accel(scene, BuildParams{});
        std::vector<RayHit> hits = camera_hits(scene, accel, 64, 48);
        ASSERT_GT(hits.size(), 1000u) << name;
        std::set<uint32_t> objects;  // every object of the scene is seen
        for (const RayHit& h : hits) objects.insert(h.hit.object);
        EXPECT_EQ(objects.size(), scene.objects.size()) << name;
        // image order: packets on the edges of objects hold several (lane by lane)
        int mixed = 0;
        check_packets<W>(scene, hits, false, name + ", image order", mixed);
        if (W > 1) {
            EXPECT_GT(mixed, 0) << name;
        }
        // grouped by object, as the shading's packets are (gathers, the plane's packet form)
        std::stable_sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) {
            return a.hit.object < b.hit.object;
        });
        check_packets<W>(scene, hits, true, name + ", by object", mixed);
        EXPECT_EQ(mixed, 0) << name;
    }
}

/// The apple's triangles have their own normal and uv indices: the gathered path must read
/// them, not the position indices (a mesh without them would not tell the two apart).
TEST(SurfaceAtPacketApple, HasNormalsAndUvsOfItsOwn) {
    const SceneData scene =
        load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/fig07b_apple_normal_map.json");
    bool found = false;
    for (const MeshData& m : scene.meshes) {
        if (m.normal_tris.empty() || m.uv_tris.empty()) continue;
        found = true;
        size_t differ = 0;
        for (size_t t = 0; t < m.tris.size(); ++t)
            differ += m.normal_tris[t] != m.tris[t] || m.uv_tris[t] != m.tris[t];
        EXPECT_GT(differ, 0u);
    }
    EXPECT_TRUE(found);
}

}  // namespace
}  // namespace raylane
