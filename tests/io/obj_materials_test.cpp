// Tests of an OBJ's own materials: usemtl and mtllib in load_obj, and the scene loader's split
// by material with the MTL's materials, textures and normal maps, overrides and warnings.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "image/film.h"
#include "io/load_obj.h"
#include "io/load_scene.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

using test::TempDir;
using test::write_file;

/// Two quads side by side: faces 1-2 before any usemtl, 3-4 "red", 5-6 "blue", 7-8 after a
/// bare usemtl (the default material), and the library `mtllib`.
std::string quads_obj(const std::string& mtllib) {
    std::string obj = "mtllib " + mtllib + "\n";
    for (int q = 0; q < 4; ++q) {
        const std::string x0 = std::to_string(2 * q), x1 = std::to_string(2 * q + 1);
        obj += "v " + x0 + " 0 0\nv " + x1 + " 0 0\nv " + x1 + " 1 0\nv " + x0 + " 1 0\n";
    }
    const char* names[] = {nullptr, "usemtl red", "usemtl blue", "usemtl"};
    for (int q = 0; q < 4; ++q) {
        if (names[q]) obj += std::string(names[q]) + "\n";
        const int b = 4 * q + 1;
        obj += "f " + std::to_string(b) + " " + std::to_string(b + 1) + " " +
               std::to_string(b + 2) + " " + std::to_string(b + 3) + "\n";
    }
    return obj;
}

/// A scene of quads.obj whose mesh object names no material (the model's own apply), with a
/// "default" material and `materials` more.
std::string scene_json(const std::string& materials, const std::string& object_keys = "") {
    return R"({"version": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0],
               "fov_deg": 40, "resolution": [16, 16]},
               "materials": {"default": {"c_d": [0.2, 0.2, 0.2]})" +
           materials + R"(},
               "objects": [{"shape": "mesh", "file": "quads.obj")" +
           object_keys + R"(}],
               "lights": [{"type": "point", "position": [0, 0, -5]}]})";
}

TEST(ObjMaterials, LoadObjGivesEachFaceItsMaterial) {
    TempDir dir("raylane_objmat_");
    write_file(dir.path / "quads.obj", quads_obj("lib one.mtl two.mtl"));
    const MeshData m = load_obj((dir.path / "quads.obj").string());
    EXPECT_EQ(m.material_libraries, (std::vector<std::string>{"lib", "one.mtl", "two.mtl"}));
    // red, blue, then "" (the faces before any usemtl and after the bare one)
    ASSERT_EQ(m.material_names, (std::vector<std::string>{"red", "blue", ""}));
    EXPECT_EQ(m.tri_material, (std::vector<uint32_t>{2, 2, 0, 0, 1, 1, 2, 2}));
}

TEST(ObjMaterials, TheSceneSplitsTheModelByItsMtlMaterials) {
    TempDir dir("raylane_objmat_");
    write_file(dir.path / "quads.obj", quads_obj("quads.mtl"));
    write_file(dir.path / "quads.mtl",
               "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 50\nnewmtl blue\r\nKd 0 0 1\r\n");
    const SceneData s = load_scene_from_string(scene_json(""), (dir.path / "s.json").string());
    ASSERT_EQ(s.objects.size(), 3u);  // red, blue, and the default
    auto material_of = [&](size_t o) { return s.materials[s.objects[o].material]; };
    EXPECT_EQ(material_of(0).name, "red");
    EXPECT_EQ(material_of(0).c_d, vec3(1, 0, 0));
    EXPECT_EQ(material_of(0).exponent, 50.0f);
    EXPECT_EQ(material_of(1).c_d, vec3(0, 0, 1));
    EXPECT_EQ(material_of(2).name, "default");
    for (size_t o = 0; o < 3; ++o)
        EXPECT_EQ(s.meshes[s.objects[o].shape].tris.size(), o == 2 ? 4u : 2u);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(ObjMaterials, TheScenesMaterialOfTheSameNameOverridesTheModels) {
    TempDir dir("raylane_objmat_");
    write_file(dir.path / "quads.obj", quads_obj("quads.mtl"));
    write_file(dir.path / "quads.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    const SceneData s = load_scene_from_string(scene_json(R"(, "red": {"c_d": [0, 1, 0]})"),
                                               (dir.path / "s.json").string());
    EXPECT_EQ(s.materials[s.objects[0].material].c_d, vec3(0, 1, 0));
    EXPECT_EQ(s.materials[s.objects[1].material].c_d, vec3(0, 0, 1));
}

TEST(ObjMaterials, AnObjectThatNamesItsMaterialGivesItToEveryFace) {
    TempDir dir("raylane_objmat_");
    write_file(dir.path / "quads.obj", quads_obj("quads.mtl"));
    write_file(dir.path / "quads.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    const SceneData s = load_scene_from_string(
        scene_json(R"(, "mine": {"c_d": [0, 1, 0]})", R"(, "material": "mine")"),
        (dir.path / "s.json").string());
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.materials[s.objects[0].material].name, "mine");
    EXPECT_EQ(s.meshes[0].tris.size(), 8u);
    EXPECT_TRUE(s.warnings.empty());
}

TEST(ObjMaterials, AMissingLibraryOrMaterialWarnsAndUsesTheDefaultMaterial) {
    TempDir dir("raylane_objmat_");
    write_file(dir.path / "quads.obj", quads_obj("missing.mtl"));
    const std::string scene = (dir.path / "s.json").string();
    const SceneData s = load_scene_from_string(scene_json(""), scene);
    ASSERT_EQ(s.objects.size(), 3u);
    for (const Object& o : s.objects) EXPECT_EQ(s.materials[o.material].name, "default");
    // one line for the library, one per material it should have held
    ASSERT_EQ(s.warnings.size(), 3u);
    EXPECT_NE(s.warnings[0].find("material library missing.mtl not read"), std::string::npos)
        << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("material red is in none of its libraries"), std::string::npos)
        << s.warnings[1];
    write_file(dir.path / "missing.mtl", "newmtl red\nKd 1 0 0\nd 0.5\n");
    const SceneData t = load_scene_from_string(scene_json(""), scene);
    EXPECT_EQ(t.materials[t.objects[0].material].name, "red");
    EXPECT_EQ(t.materials[t.objects[1].material].name, "default");  // blue is undefined
    ASSERT_EQ(t.warnings.size(), 2u);
    EXPECT_NE(t.warnings[0].find("ignored d"), std::string::npos) << t.warnings[0];
    EXPECT_NE(t.warnings[1].find("material blue is in none"), std::string::npos) << t.warnings[1];
}

TEST(ObjMaterials, TexturesAndNormalMapsAreFoundNextToTheLibraryWithWindowsSeparators) {
    TempDir dir("raylane_objmat_");
    write_file(dir.path / "quads.obj", quads_obj("mat\\quads.mtl"));
    write_file(dir.path / "mat" / "quads.mtl",
               "newmtl red\nKd 1 1 1\nmap_Kd tex\\red.png\nmap_Bump -bm 1 tex\\flat.png\n"
               "newmtl blue\nmap_Kd tex/none.png\n");
    Film red = make_film(2, 2), flat = make_film(2, 2);
    for (vec3& p : red.pixels) p = vec3(1, 0, 0);
    for (vec3& p : flat.pixels) p = vec3(0.5f, 0.5f, 1.0f);
    std::filesystem::create_directories(dir.path / "mat" / "tex");
    write_png((dir.path / "mat" / "tex" / "red.png").string(), red, Encoding::srgb);
    write_png((dir.path / "mat" / "tex" / "flat.png").string(), flat, Encoding::linear);
    const SceneData s = load_scene_from_string(scene_json(""), (dir.path / "s.json").string());
    const Material& m = s.materials[s.objects[0].material];
    EXPECT_GE(m.texture, 0);
    EXPECT_GE(m.normal_map, 0);
    EXPECT_EQ(s.materials[s.objects[1].material].texture, -1);  // its texture is missing
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("mat/quads.mtl: material blue: "), std::string::npos)
        << s.warnings[0];
    EXPECT_NE(s.warnings[0].find("mat/tex/none.png: cannot read"), std::string::npos)
        << s.warnings[0];
}

}  // namespace
}  // namespace raylane
