// tests/api: raylane::Scene, the instruction sets and the version through libraylane.so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "raylane/raylane.h"
#include "support/api_error.h"

namespace {

using raylane::test::error_of;

double mean(const raylane::Image& image) {
    double sum = 0.0;
    for (float v : image.pixels) sum += v;
    return image.pixels.empty() ? 0.0 : sum / double(image.pixels.size());
}

TEST(Version, IsTheProjectsVersion) {
    const std::string v = raylane::version();
    EXPECT_EQ(std::count(v.begin(), v.end(), '.'), 2) << v;
    EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(v[0]))) << v;
}

TEST(InstructionSets, TheSetInUseIsCompiledAndRunnable) {
    const auto compiled = raylane::compiled_instruction_sets();
    const auto cpu = raylane::cpu_instruction_sets();
    const std::string in_use = raylane::instruction_set();
    ASSERT_FALSE(compiled.empty());
    EXPECT_NE(std::find(compiled.begin(), compiled.end(), in_use), compiled.end()) << in_use;
    EXPECT_NE(std::find(cpu.begin(), cpu.end(), in_use), cpu.end()) << in_use;
    const int w = raylane::packet_width();
    EXPECT_TRUE(w == 4 || w == 8 || w == 16) << w;
}

TEST(InstructionSets, EverySetThisCpuRunsCanBeChosenAndAnUnknownOneIsRefused) {
    const std::string before = raylane::instruction_set();
    for (const std::string& name : raylane::compiled_instruction_sets()) {
        const auto cpu = raylane::cpu_instruction_sets();
        if (std::find(cpu.begin(), cpu.end(), name) == cpu.end()) continue;
        raylane::use_instruction_set(name);
        EXPECT_EQ(raylane::instruction_set(), name);
    }
    EXPECT_NE(error_of([] {
                  raylane::use_instruction_set("avx9000");
              }).find("unknown instruction set 'avx9000'"),
              std::string::npos);
    EXPECT_NE(error_of([] { raylane::use_instruction_set(""); }), "");
    raylane::use_instruction_set(before);
}

TEST(Scene, TheBuiltInSceneRendersOnBothPathsAlike) {
    const raylane::Scene scene = raylane::Scene::load("");
    EXPECT_EQ(scene.source(), "<built-in>");
    EXPECT_GT(scene.width(), 0);
    raylane::RenderSettings settings;
    settings.width = 48;
    settings.spp = 1;
    const raylane::Image packet = scene.render(settings);
    settings.path = raylane::TracePath::scalar;
    const raylane::Image scalar = scene.render(settings);
    ASSERT_EQ(packet.width, 48);
    EXPECT_EQ(packet.height, 48 * scene.height() / scene.width());
    ASSERT_EQ(packet.channels, 3);
    ASSERT_EQ(packet.pixels.size(), size_t(packet.width) * size_t(packet.height) * 3);
    EXPECT_GT(mean(packet), 0.01) << "a black image";
    ASSERT_EQ(scalar.pixels.size(), packet.pixels.size());
    float max_diff = 0.0f;
    for (size_t i = 0; i < packet.pixels.size(); ++i)
        max_diff = std::max(max_diff, std::abs(packet.pixels[i] - scalar.pixels[i]));
    EXPECT_LT(max_diff, 2e-3f);
}

TEST(Scene, AnalysisImagesHaveTheirChannels) {
    const raylane::Scene scene = raylane::Scene::load("");
    raylane::RenderSettings settings;
    settings.width = 32;
    settings.spp = 1;
    settings.image = raylane::ImageKind::depth;
    const raylane::Image depth = scene.render(settings);
    EXPECT_EQ(depth.channels, 1);
    EXPECT_EQ(depth.pixels.size(), size_t(depth.width) * size_t(depth.height));
    EXPECT_GT(*std::max_element(depth.pixels.begin(), depth.pixels.end()), 0.0f);
    settings.image = raylane::ImageKind::bvh_cost;
    const raylane::Image cost = scene.render(settings);
    EXPECT_EQ(cost.channels, 1);
    EXPECT_GE(*std::min_element(cost.pixels.begin(), cost.pixels.end()), 1.0f);
    settings.image = raylane::ImageKind::normal;
    EXPECT_EQ(scene.render(settings).channels, 3);
}

TEST(Scene, CompareAgreesAndStatsCountTheScene) {
    const raylane::Scene scene = raylane::Scene::load("");
    raylane::CompareSettings settings;
    settings.width = 32;
    settings.spp = 1;
    settings.repeats = 1;
    const raylane::Comparison c = scene.compare(settings);
    EXPECT_TRUE(c.agree) << c.max_abs_diff;
    EXPECT_EQ(c.pixels, size_t(c.width) * size_t(c.height));
    EXPECT_EQ(c.instruction_set, raylane::instruction_set());
    const raylane::SceneStats s = scene.stats();
    EXPECT_GT(s.objects, 0u);
    EXPECT_GT(s.lights, 0u);
    EXPECT_FALSE(s.features.empty());
    EXPECT_GT(s.top_level.nodes, 0u);
}

TEST(Scene, AModelFileIsItsOwnSceneFoundOnTheModelPath) {
    const char* path = RAYLANE_SHARED_DIR "/models/bunny.ply";
    if (!std::ifstream(path)) GTEST_SKIP() << path << " is not there";
    EXPECT_EQ(raylane::Scene::load("bunny.ply").stats().triangles,
              raylane::Scene::load(path).stats().triangles);
    const raylane::Scene scene = raylane::Scene::load(path);
    const raylane::SceneStats s = scene.stats();
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_GT(s.meshes[0].triangles, 60000u);
    EXPECT_GT(s.meshes[0].wide.nodes, 0u);
    raylane::RenderSettings settings;
    settings.width = 32;
    settings.spp = 1;
    EXPECT_GT(mean(scene.render(settings)), 0.01);
}

TEST(Scene, BadInputIsOneError) {
    EXPECT_EQ(error_of([] { raylane::Scene::load("no/such/scene.json"); }),
              "no/such/scene.json: no such file");
    const std::string bad = testing::TempDir() + "bad_scene.json";
    std::ofstream(bad) << "{\n  \"camera\": 12\n}\n";
    const std::string message = error_of([&] { raylane::Scene::load(bad); });
    EXPECT_EQ(message.rfind(bad + ":", 0), 0u) << message;
    const raylane::Scene scene = raylane::Scene::load("");
    raylane::RenderSettings settings;
    settings.spp = -1;
    EXPECT_EQ(error_of([&] { scene.render(settings); }), "spp: -1 is outside 0 .. 1048576");
    settings.spp = 1;
    settings.width = 40000;
    EXPECT_NE(error_of([&] { scene.render(settings); }).find("width"), std::string::npos);
    raylane::CompareSettings compare;
    compare.repeats = 0;
    EXPECT_EQ(error_of([&] { scene.compare(compare); }), "repeats: 0 is outside 1 .. 100");
}

TEST(Scene, CopiesShareTheSceneAndRenderFromManyThreads) {
    const raylane::Scene a = raylane::Scene::load("");
    const raylane::Scene b = a;  // NOLINT(performance-unnecessary-copy-initialization)
    raylane::RenderSettings settings;
    settings.width = 24;
    settings.spp = 1;
    settings.threads = 1;
    raylane::Image ia, ib;
    std::thread t([&] { ia = a.render(settings); });
    ib = b.render(settings);
    t.join();
    EXPECT_EQ(ia.pixels, ib.pixels);
}

}  // namespace
