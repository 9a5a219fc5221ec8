// distribute: the scene hash of parts (scene_hash.h) follows the scene's files and nothing else.
#include "distribute/scene_hash.h"

#include <gtest/gtest.h>

#include <string>

#include "io/load_scene.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

TEST(SceneHash, IsSixteenHexDigitsAndTheSameForTheSameScene) {
    const std::string h = scene_hash(make_builtin_scene());
    EXPECT_EQ(h.size(), 16u);
    EXPECT_EQ(h.find_first_not_of("0123456789abcdef"), std::string::npos) << h;
    EXPECT_EQ(scene_hash(make_builtin_scene()), h);
}

TEST(SceneHash, ChangesWithTheSceneFileAndTheModelItLoads) {
    const test::TempDir dir("raylane_scene_hash_");
    const auto obj = dir.path / "tri.obj";
    const auto json = dir.path / "scene.json";
    const std::string scene_text =
        R"({"camera": {"position": [0,0,-2], "look_at": [0,0,0], "fov_deg": 60,
            "resolution": [8,8]}, "objects": [{"shape": "mesh", "file": "tri.obj"}]})";
    test::write_file(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    test::write_file(json, scene_text);
    const std::string first = scene_hash(load_scene(json.string()));
    EXPECT_EQ(scene_hash(load_scene(json.string())), first);
    EXPECT_NE(first, scene_hash(make_builtin_scene()));
    // one vertex moved in the model: the scene file is the same, the hash is not
    test::write_file(obj, "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string moved = scene_hash(load_scene(json.string()));
    EXPECT_NE(moved, first);
    // a space more in the scene file
    test::write_file(json, scene_text + " ");
    EXPECT_NE(scene_hash(load_scene(json.string())), moved);
}

}  // namespace
}  // namespace raylane
