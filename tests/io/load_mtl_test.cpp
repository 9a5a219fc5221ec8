// Tests of io/load_mtl: Wavefront MTL libraries and their mapping onto Raylane's materials.
#include "io/load_mtl.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

std::string error_of(std::string_view text) {
    try {
        parse_mtl(text, "m.mtl");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(LoadMtl, ReadsTheKeywordsRaylaneUsesWithCommentsAndEveryLineEnd) {
    const MtlLibrary lib = parse_mtl(
        "# a library\r\nnewmtl red\r\n  Kd 0.63 0.065 0.05 # Red\r\n  Ks 0 0 0\r\n"
        "  Ns 10\rNi 1.5\rillum 2\rKa 1 1 1\n"
        "newmtl apple\nKD 0.8\nKs 0.5 0.5 0.5\nNs 225\nmap_Kd -bm 1.0 -s 1 1 1 tex\\apple "
        "diff.png\n"
        "norm normals.png\nd 0.5\nTf 1 1 1\n",
        "m.mtl");
    ASSERT_EQ(lib.materials.size(), 2u);
    const MtlMaterial& red = lib.materials[0];
    EXPECT_EQ(red.name, "red");
    EXPECT_EQ(red.kd, vec3(0.63f, 0.065f, 0.05f));
    EXPECT_EQ(red.ks, vec3(0.0f));
    EXPECT_EQ(red.ns, 10.0f);
    EXPECT_EQ(red.illum, 2);
    const MtlMaterial& apple = lib.materials[1];
    EXPECT_EQ(apple.kd, vec3(0.8f));  // one number: grey; keywords in any case
    EXPECT_EQ(apple.map_kd, "tex/apple diff.png");
    EXPECT_EQ(apple.map_bump, "normals.png");
    EXPECT_EQ(apple.d, 0.5f);
    EXPECT_EQ(lib.ignored, (std::vector<std::string>{"d", "Tf"}));
}

TEST(LoadMtl, MapsOntoRaylanesMaterials) {
    MtlMaterial m;
    m.name = "shiny";
    m.kd = vec3(0.5f, 0.25f, 0.125f);
    m.ks = vec3(0.2f, 0.4f, 0.1f);
    m.ns = 0.5f;
    m.illum = 3;
    const Material out = material_from_mtl(m);
    EXPECT_EQ(out.name, "shiny");
    EXPECT_EQ(out.c_d, m.kd);
    EXPECT_EQ(out.k_d, 1.0f);
    EXPECT_EQ(out.k_a, 0.1f);
    EXPECT_EQ(out.c_s, m.ks);
    EXPECT_EQ(out.k_s, 1.0f);
    EXPECT_EQ(out.exponent, 1.0f);    // Ns below 1
    EXPECT_EQ(out.reflection, 0.4f);  // illum 3: a mirror of strength max(Ks)
    EXPECT_FALSE(out.refractive);
    m.illum = 7;
    m.ni = 1.33f;
    m.ke = vec3(17.0f, 12.0f, 4.0f);
    m.ks = vec3(0.0f);
    const Material glass = material_from_mtl(m);
    EXPECT_TRUE(glass.refractive);
    EXPECT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.k_s, 0.0f);
    EXPECT_EQ(glass.emission, vec3(17.0f, 12.0f, 4.0f));
}

TEST(LoadMtl, BadLinesNameFileLineAndReason) {
    EXPECT_EQ(error_of("Kd 1 1 1\n"), "m.mtl:1: Kd before any newmtl");
    EXPECT_EQ(error_of("newmtl a\nKd 1 x 1\n"), "m.mtl:2: expected a number, got 'x'");
    EXPECT_EQ(error_of("newmtl a\r\nKd 1 1\r\n"), "m.mtl:2: Kd needs 1 or 3 numbers");
    EXPECT_EQ(error_of("newmtl a\nNs\n"), "m.mtl:2: Ns needs one number");
    EXPECT_EQ(error_of("newmtl\n"), "m.mtl:1: newmtl needs a name");
    EXPECT_EQ(error_of("newmtl a\nmap_Kd -bm\n"), "m.mtl:2: map_Kd names no file");
    EXPECT_EQ(error_of("newmtl a\nmap_Kd -zz 1 t.png\n"), "m.mtl:2: unknown texture option '-zz'");
    EXPECT_EQ(error_of("newmtl a\nKd nan 1 1\n"), "m.mtl:2: expected a number, got 'nan'");
}

TEST(LoadMtl, AFileThatCannotBeReadSaysSo) {
    test::TempDir dir("raylane_mtl_");
    EXPECT_THROW(load_mtl((dir.path / "missing.mtl").string()), InputError);
    test::write_file(dir.path / "a.mtl", "newmtl a\nKd 0.1 0.2 0.3\n");
    EXPECT_EQ(load_mtl((dir.path / "a.mtl").string()).materials.at(0).kd, vec3(0.1f, 0.2f, 0.3f));
}

}  // namespace
}  // namespace raylane
