// The packet renderer allocates nothing per tile: a render of many tiles makes as many heap
// allocations as a render of few (the film, the tile list and the thread pool's set-up only).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "io/load_scene.h"
#include "render/render_packet.h"

namespace {
std::atomic<long> allocations{0};
}

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(size_t n) {
    ++allocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace raylane {
namespace {

long allocations_for(const SceneData& scene, const Accel& accel, int width, int height) {
    SceneData s = scene;
    s.camera.width = width;
    s.camera.height = height;
    RenderParams p;
    p.threads = 1;  // one worker: the pool's own allocations do not vary with scheduling
    p.spp = 2;
    render_packet(s, accel, p);  // warm-up
    const long before = allocations.load();
    RenderResult r = render_packet(s, accel, p);
    const long after = allocations.load();
    EXPECT_GT(r.stats.total_rays(), r.stats.primary_rays);  // shading traced rays
    return after - before;
}

TEST(RenderPacket, AllocatesNothingPerTile) {
#ifdef RAYLANE_SANITIZED
    GTEST_SKIP() << "the sanitizers replace operator new";
#endif
    const SceneData scene = make_builtin_scene();
    const Accel accel = build_accel(scene, BuildParams{});
    const long few = allocations_for(scene, accel, 32, 32);     // 4 tiles
    const long many = allocations_for(scene, accel, 256, 256);  // 256 tiles
    EXPECT_EQ(few, many);
    EXPECT_LT(many, 64);
}

TEST(RenderPacket, AllocatesNothingPerTileWithSecondaryRaysAndAreaLights) {
#ifdef RAYLANE_SANITIZED
    GTEST_SKIP() << "the sanitizers replace operator new";
#endif
    // glossy rays, area lights and textures; then glass: the queues grow on the first tiles only
    for (const char* name : {"fig01b_glossy_sphere.json", "fig05_refractive_sphere.json"}) {
        const SceneData scene = load_scene(std::string(RAYLANE_SOURCE_DIR) + "/scenes/" + name);
        const Accel accel = build_accel(scene, BuildParams{});
        const long few = allocations_for(scene, accel, 32, 32);
        const long many = allocations_for(scene, accel, 128, 128);
        EXPECT_EQ(few, many) << name;
    }
}

}  // namespace
}  // namespace raylane
