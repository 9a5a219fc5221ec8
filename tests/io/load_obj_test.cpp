// tests for io/load_obj.cpp and io/load_mesh.cpp: index forms, layout quirks, the shipped OBJ
// files, malformed input and random byte mutations. The PLY twin is load_ply_test.cpp.
#include "io/load_obj.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "core/error.h"
#include "io/load_mesh.h"
#include "io/load_ply.h"
#include "support/gzip.h"
#include "support/input_error.h"
#include "support/models.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

MeshData obj(std::string_view text) { return load_obj_from_memory(text, "test.obj"); }

/// Checks that loading `text` fails with a one-line message holding every part of `parts`.
void expect_obj_error(std::string_view text, std::initializer_list<std::string_view> parts) {
    std::string message = test::input_error_of([&] { obj(text); });
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (std::string_view part : parts) {
        EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
}

bool same_triangle(uvec3 a, uvec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

void expect_triangles(const std::vector<uvec3>& got, const std::vector<uvec3>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < want.size(); ++i) {
        EXPECT_TRUE(same_triangle(got[i], want[i]))
            << "triangle " << i << ": (" << got[i].x << " " << got[i].y << " " << got[i].z << ")";
    }
}

void expect_same_mesh(const MeshData& a, const MeshData& b) {
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t i = 0; i < a.positions.size(); ++i) EXPECT_EQ(a.positions[i], b.positions[i]);
    ASSERT_EQ(a.normals.size(), b.normals.size());
    for (size_t i = 0; i < a.normals.size(); ++i) EXPECT_EQ(a.normals[i], b.normals[i]);
    ASSERT_EQ(a.uvs.size(), b.uvs.size());
    for (size_t i = 0; i < a.uvs.size(); ++i) EXPECT_EQ(a.uvs[i], b.uvs[i]);
    expect_triangles(a.tris, b.tris);
    expect_triangles(a.normal_tris, b.normal_tris);
    expect_triangles(a.uv_tris, b.uv_tris);
}

constexpr const char* four_vertices =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
    "vn 0 0 1\nvn 0 0 -1\nvn 1 0 0\nvn 0 1 0\n";

// good input -----------------------------------------------------------------------------

TEST(LoadObj, ReadsPositionsUvsAndNormals) {
    // (a face with area: the loader drops zero-area faces, and a mesh needs one face)
    MeshData m =
        obj("v 1.5 -2 3e2\nv 0 0 0\nv 0 1 0\nvt 0.25 0.75\nvn 0 -1 0\nf 1/1/1 2/1/1 3/1/1\n");
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[0], vec3(1.5f, -2.0f, 300.0f));
    ASSERT_EQ(m.uvs.size(), 1u);
    EXPECT_EQ(m.uvs[0], vec2(0.25f, 0.75f));
    ASSERT_EQ(m.normals.size(), 1u);
    EXPECT_EQ(m.normals[0], vec3(0.0f, -1.0f, 0.0f));
}

TEST(LoadObj, ReadsEveryIndexForm) {
    const std::string base = four_vertices;
    MeshData v = obj(base + "f 1 2 3\n");
    expect_triangles(v.tris, {{0, 1, 2}});
    EXPECT_TRUE(v.uv_tris.empty());
    EXPECT_TRUE(v.normal_tris.empty());
    EXPECT_TRUE(v.uvs.empty());
    EXPECT_TRUE(v.normals.empty());

    MeshData vt = obj(base + "f 1/4 2/3 3/2\n");
    expect_triangles(vt.tris, {{0, 1, 2}});
    expect_triangles(vt.uv_tris, {{3, 2, 1}});
    EXPECT_TRUE(vt.normal_tris.empty());
    EXPECT_EQ(vt.uvs.size(), 4u);

    MeshData vn = obj(base + "f 1//2 2//3 3//4\n");
    expect_triangles(vn.tris, {{0, 1, 2}});
    expect_triangles(vn.normal_tris, {{1, 2, 3}});
    EXPECT_TRUE(vn.uv_tris.empty());
    EXPECT_EQ(vn.normals.size(), 4u);

    MeshData all = obj(base + "f 1/2/3 2/3/4 3/4/1\n");
    expect_triangles(all.tris, {{0, 1, 2}});
    expect_triangles(all.uv_tris, {{1, 2, 3}});
    expect_triangles(all.normal_tris, {{2, 3, 0}});
}

TEST(LoadObj, ReadsNegativeIndicesRelativeToTheVerticesSoFar) {
    MeshData m =
        obj(std::string(four_vertices) + "f -4/-3/-2 -3/-2/-1 -1/-1/-4\nv 5 5 5\nf -1 -2 -3\n");
    expect_triangles(m.tris, {{0, 1, 3}, {4, 3, 2}});
    // The second face has no vt/vn, so the mesh has neither (documented).
    EXPECT_TRUE(m.uv_tris.empty());
    EXPECT_TRUE(m.normal_tris.empty());

    MeshData same = obj(std::string(four_vertices) + "f -4/-4/-4 -3/-3/-3 -2/-2/-2\n");
    MeshData positive = obj(std::string(four_vertices) + "f 1/1/1 2/2/2 3/3/3\n");
    expect_same_mesh(same, positive);
}

TEST(LoadObj, TriangulatesPolygonsAsAFan) {
    MeshData quad = obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    expect_triangles(quad.tris, {{0, 1, 2}, {0, 2, 3}});
    MeshData pentagon =
        obj("v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 5/1/1 4/1/1 3/1/1 2/1/1 1/1/1\n"
            "vt 0 0\nvn 0 0 1\n");
    expect_triangles(pentagon.tris, {{4, 3, 2}, {4, 2, 1}, {4, 1, 0}});
    expect_triangles(pentagon.uv_tris, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
    expect_triangles(pentagon.normal_tris, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
}

TEST(LoadObj, AcceptsCrlfTabsRunsOfSpacesAndNoFinalNewline) {
    MeshData plain = obj("v 1 2 3\nv 4 5 6\nv 7 8 10\nvt 0.5 0.5\nf 1/1 2/1 3/1\n");
    MeshData messy =
        obj("\xEF\xBB\xBFv  1 2 3\r\n\tv\t4\t5\t6  \r\n  v 7   8 10 \t\r\n\r\nvt 0.5 0.5\r\nf  "
            "1/1\t2/1 3/1 ");
    expect_same_mesh(plain, messy);
}

TEST(LoadObj, ReadsLfCrlfAndCrLineEndsAlike) {
    const char* const lines[] = {"v 0 0 0",         "vt 0.5 0.25", "v 2 0 0",       "",
                                 "# comment",       "v 0 3 0",     "f 1/1 2/1 3/1", "v 0 0 4",
                                 "f -4/1 -2/1 -1/1"};
    std::string lf, crlf, cr, mixed;
    const char* const mixed_ends[] = {"\n", "\r", "\r\n"};
    for (size_t i = 0; i < std::size(lines); ++i) {
        lf += std::string(lines[i]) + "\n";
        crlf += std::string(lines[i]) + "\r\n";
        cr += std::string(lines[i]) + "\r";
        mixed += std::string(lines[i]) + mixed_ends[i % 3];
    }
    for (const std::string& text : {lf, crlf, cr, mixed}) {
        MeshData m = obj(text);
        ASSERT_EQ(m.positions.size(), 4u);
        EXPECT_EQ(m.positions[1], vec3(2, 0, 0));
        EXPECT_EQ(m.positions[3], vec3(0, 0, 4));
        ASSERT_EQ(m.uvs.size(), 1u);
        EXPECT_EQ(m.uvs[0], vec2(0.5f, 0.25f));
        expect_triangles(m.tris, {{0, 1, 2}, {0, 2, 3}});
        expect_triangles(m.uv_tris, {{0, 0, 0}, {0, 0, 0}});
    }
}

TEST(LoadObjErrors, CountsLinesEndedByACrAlone) {
    expect_obj_error("v 0 0 0\rv 1 0 0\r\rv 0 x 0\r", {"test.obj:4:", "bad number 'x'"});
    expect_obj_error("v 0 0 0\r\nv 1 0 0\rv 0 1 0\nf 1 2 5\r\n", {"test.obj:4:", "index 5"});
}

TEST(LoadObj, ReadsCornersWithAnEmptyTextureOrNormalIndex) {
    const std::string base = four_vertices;
    for (const char* face : {"f 1/ 2/ 3/\n", "f 1// 2// 3//\n", "f 1/ 2// 3\n"}) {
        SCOPED_TRACE(face);
        MeshData m = obj(base + face);
        expect_triangles(m.tris, {{0, 1, 2}});
        EXPECT_TRUE(m.uv_tris.empty());
        EXPECT_TRUE(m.normal_tris.empty());
    }
    MeshData uv = obj(base + "f 1/4/ 2/3/ 3/2/\n");
    expect_triangles(uv.tris, {{0, 1, 2}});
    expect_triangles(uv.uv_tris, {{3, 2, 1}});
    EXPECT_TRUE(uv.normal_tris.empty());
    // an empty index is still one form: `v` and `v//vn` do not mix
    expect_obj_error(base + "f 1// 2//2 3//3\n", {"test.obj:13:", "mixes index forms v and v//vn"});
}

TEST(LoadObj, AcceptsABareUsemtl) {
    MeshData m = obj("usemtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl \t\r\nf 1 2 3\nusemtl red\n");
    EXPECT_EQ(m.positions.size(), 3u);
    expect_triangles(m.tris, {{0, 1, 2}});
}

TEST(LoadObj, IgnoresCommentsGroupsMaterialsAndUnknownKeywords) {
    MeshData m =
        obj("# header comment\nmtllib box.mtl\no box\ng side\ns 1\ns off\nusemtl red paint\n"
            "vp 0.5 0.5\ncurv2 1 2\nv 0 0 0 # inline comment\nv 1 0 0 1.0\nv 0 1 0 0.1 0.2 0.3\n"
            "l 1 2\np 1\nf 1 2 3 # the only face\n#f 1 2 3\n");
    EXPECT_EQ(m.positions.size(), 3u);
    expect_triangles(m.tris, {{0, 1, 2}});
}

TEST(LoadObj, ReadsTextureCoordinatesWithOneToThreeValues) {
    MeshData m =
        obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nvt 0.25 0.75\nvt 0.1 0.2 0.3\nf 1/1 2/2 3/3\n");
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[0], vec2(0.5f, 0.0f));
    EXPECT_EQ(m.uvs[1], vec2(0.25f, 0.75f));
    EXPECT_EQ(m.uvs[2], vec2(0.1f, 0.2f));
}

TEST(LoadObj, DropsNormalsAndUvsWhenSomeFacesLackThem) {
    MeshData m = obj(std::string(four_vertices) + "f 1/1/1 2/2/2 3/3/3\nf 1/1 3/3 4/4\n");
    EXPECT_EQ(m.tris.size(), 2u);
    EXPECT_EQ(m.uv_tris.size(), 2u);
    EXPECT_TRUE(m.normal_tris.empty());
    EXPECT_TRUE(m.normals.empty());
    MeshData none = obj(std::string(four_vertices) + "f 1/1/1 2/2/2 3/3/3\nf 1 3 4\n");
    EXPECT_TRUE(none.uv_tris.empty());
    EXPECT_TRUE(none.uvs.empty());
}

TEST(LoadObj, AcceptsFacesBeforeTheVerticesTheyUse) {
    MeshData m = obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    expect_triangles(m.tris, {{0, 1, 2}});
}

TEST(LoadObj, LoadsFromDiskAndNamesTheMeshAfterTheFile) {
    fs::path dir = fs::temp_directory_path() / ("raylane_obj_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    fs::path file = dir / "Tri.OBJ";
    std::ofstream(file) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3";
    MeshData m = load_mesh(file.string());
    EXPECT_EQ(m.name, "Tri.OBJ");
    EXPECT_EQ(m.tris.size(), 1u);
    MeshData direct = load_obj(file.string());
    expect_same_mesh(m, direct);
    fs::remove_all(dir);
}

// shipped models -------------------------------------------------------------------------

TEST(LoadObj, ReadsTheDragon) {
    const std::string path = test::models_dir + "/dragon.obj";
    if (!fs::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    MeshData m = load_obj(path);
    EXPECT_EQ(m.name, "dragon.obj");
    EXPECT_EQ(m.positions.size(), 50000u);
    EXPECT_EQ(m.tris.size(), 100000u);
    EXPECT_TRUE(m.normal_tris.empty());
    EXPECT_TRUE(m.uv_tris.empty());
}

struct Bounds {
    vec3 lo{INFINITY};
    vec3 hi{-INFINITY};
};
Bounds bounds_of(const std::vector<vec3>& points) {
    Bounds b;
    for (const vec3& p : points) {
        b.lo = glm::min(b.lo, p);
        b.hi = glm::max(b.hi, p);
    }
    return b;
}
double surface_area(const MeshData& m) {
    double area = 0.0;
    for (const uvec3& t : m.tris) {
        glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return area;
}

TEST(LoadObj, DragonObjMatchesDragonPlyUnderTheDocumentedTransform) {
    const std::string obj_path = test::models_dir + "/dragon.obj";
    const std::string ply_path = test::models_dir + "/dragon.ply";
    if (!fs::exists(obj_path) || !fs::exists(ply_path))
        RAYLANE_MODEL_MISSING() << "dragon files not present";
    MeshData from_obj = load_obj(obj_path);
    MeshData from_ply = load_ply(ply_path);
    ASSERT_EQ(from_obj.tris.size(), from_ply.tris.size());
    ASSERT_EQ(from_obj.positions.size(), from_ply.positions.size());
    // models/README.md: obj = 5.2084 * ply + (0, 4.970, 0).
    for (vec3& p : from_ply.positions) p = 5.2084f * p + vec3(0.0f, 4.970f, 0.0f);
    Bounds a = bounds_of(from_obj.positions);
    Bounds b = bounds_of(from_ply.positions);
    const float extent = glm::length(a.hi - a.lo);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a.lo[k], b.lo[k], 1e-3f * extent) << "axis " << k;
        EXPECT_NEAR(a.hi[k], b.hi[k], 1e-3f * extent) << "axis " << k;
    }
    // Same triangles in another vertex order: the total area agrees (order independent).
    const double area_obj = surface_area(from_obj);
    EXPECT_NEAR(area_obj, surface_area(from_ply), 1e-3 * area_obj);
}

TEST(LoadObj, ReadsTheAppleWithUvsAndNormals) {
    const std::string path = test::models_dir + "/apple/food_apple_01_4k.obj";
    if (!fs::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    MeshData m = load_obj(path);
    EXPECT_EQ(m.positions.size(), 3504u);
    EXPECT_EQ(m.uvs.size(), 4019u);
    EXPECT_EQ(m.normals.size(), 3504u);
    EXPECT_EQ(m.tris.size(), 7012u);
    EXPECT_EQ(m.uv_tris.size(), 7012u);
    EXPECT_EQ(m.normal_tris.size(), 7012u);
    for (const vec2& uv : m.uvs) {
        EXPECT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f);
    }
}

TEST(LoadObj, ReadsTheCornellBoxQuadsWithNegativeIndices) {
    const std::string path = test::models_dir + "/cornell_box/CornellBox-Original.obj";
    if (!fs::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    MeshData m = load_obj(path);
    EXPECT_EQ(m.positions.size(), 72u);
    EXPECT_EQ(m.tris.size(), 36u);
    // The floor quad `f -4 -3 -2 -1` follows the first four vertices.
    expect_triangles({m.tris[0], m.tris[1]}, {{0, 1, 2}, {0, 2, 3}});
    Bounds b = bounds_of(m.positions);
    EXPECT_FLOAT_EQ(b.lo.y, 0.0f);
    EXPECT_FLOAT_EQ(b.hi.y, 1.99f);
}

// malformed input ------------------------------------------------------------------------

TEST(LoadObjErrors, ReportsABadNumberWithItsLine) {
    expect_obj_error("v 0 0 0\nv 1 x 0\n", {"test.obj:2:", "bad number", "'x'"});
    expect_obj_error("v 0 0 0\nvt 0.5 0.5q\n", {"test.obj:2:", "bad number"});
    expect_obj_error("v 0 0\n", {"test.obj:1:", "missing z"});
    expect_obj_error("vn 0 0 1 1\n", {"test.obj:1:", "too many values"});
}

TEST(LoadObjErrors, RejectsNanAndInfiniteCoordinates) {
    expect_obj_error("v 0 0 0\nv nan 0 0\n", {"test.obj:2:", "not a finite"});
    expect_obj_error("v 0 0 0\r\nv 0 inf 0\r\n", {"test.obj:2:", "not a finite"});
    expect_obj_error("v 0 0 1e39\n", {"test.obj:1:", "not a finite"});
}

TEST(LoadObjErrors, RejectsIndexZero) {
    expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 0 2\n", {"test.obj:5:", "index 0"});
}

TEST(LoadObjErrors, ReportsAnOutOfRangeIndexOnTheLineOfTheFace) {
    expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 2 3\n",
                     {"test.obj:5:", "vertex index 4 out of range"});
    // Forward references are fine until the end of the file, then the face line is named.
    expect_obj_error("f 1 2 3\nf 1 2 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\n",
                     {"test.obj:2:", "out of range"});
    expect_obj_error("v 0 0 0\nvt 0 0\nf 1/1 1/1 1/2\n",
                     {"test.obj:3:", "texture coordinate index 2 out of range"});
}

TEST(LoadObjErrors, ReportsANegativeIndexReachingBeforeTheFirstVertex) {
    expect_obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
                     {"test.obj:4:", "relative vertex index -4 out of range"});
}

TEST(LoadObjErrors, RejectsFacesWithFewerThanThreeCorners) {
    expect_obj_error("v 0 0 0\nv 1 0 0\nf 1 2\n", {"test.obj:3:", "2 corners", "at least 3"});
    expect_obj_error("v 0 0 0\nf\n", {"test.obj:2:", "0 corners"});
}

TEST(LoadObjErrors, RejectsAFaceMixingIndexForms) {
    expect_obj_error(std::string(four_vertices) + "f 1//1 2//2 3\n", {"test.obj:13:", "mixes"});
    expect_obj_error(std::string(four_vertices) + "f 1/1/1 2/2/2 3/3\n", {"test.obj:13:", "mixes"});
}

TEST(LoadObjErrors, RejectsMalformedCornersAndLines) {
    expect_obj_error("v 0 0 0\nf 1/x 1 1\n", {"test.obj:2:", "bad face corner", "'1/x'"});
    expect_obj_error("v 0 0 0\nf 1/1/1/ 1 1\n", {"test.obj:2:", "bad face corner", "'1/1/1/'"});
    expect_obj_error("v 0 0 0\nf 1 1 1x\n", {"test.obj:2:", "bad face corner", "'1x'"});
    expect_obj_error("v 0 0 0\n3 4 5\n", {"test.obj:2:", "expected a keyword"});
    expect_obj_error("v 0 0 0\n\x01\x02\n", {"test.obj:2:", "expected a keyword", "\\x01"});
    expect_obj_error("v 0 0 0\nv.x 1 2 3\n", {"test.obj:2:", "bad keyword"});
}

TEST(LoadObjErrors, RejectsAFileWithoutFaces) {
    expect_obj_error("v 0 0 0\n# nothing else\n", {"test.obj", "no faces"});
    expect_obj_error("\n\r\n", {"test.obj", "no faces"});
}

TEST(LoadObjErrors, NamesAMissingFile) {
    std::string message =
        test::input_error_of([] { load_obj("/nonexistent/raylane/missing.obj"); });
    EXPECT_NE(message.find("/nonexistent/raylane/missing.obj"), std::string::npos) << message;
    EXPECT_NE(message.find("cannot read"), std::string::npos) << message;
    message = test::input_error_of([] { load_mesh("/nonexistent/raylane/missing.ply"); });
    EXPECT_NE(message.find("missing.ply: cannot read"), std::string::npos) << message;
}

TEST(LoadObjErrors, ReportsADirectoryGivenAsAFile) {
    const std::string dir =
        fs::temp_directory_path() / ("raylane_dir_" + std::to_string(::getpid()) + ".obj");
    fs::create_directories(dir);
    std::string message = test::input_error_of([&] { load_mesh(dir); });
    fs::remove_all(dir);
    EXPECT_NE(message.find(dir + ": cannot read"), std::string::npos) << message;
    EXPECT_NE(message.find("directory"), std::string::npos) << message;
}

TEST(LoadObjErrors, LoadMeshRejectsUnknownExtensions) {
    std::string message = test::input_error_of([] { load_mesh("models/teapot.stl"); });
    EXPECT_NE(message.find("models/teapot.stl"), std::string::npos) << message;
    EXPECT_NE(message.find("unsupported mesh format '.stl'"), std::string::npos) << message;
    message = test::input_error_of([] { load_mesh("models/teapot"); });
    EXPECT_NE(message.find("no extension"), std::string::npos) << message;
}

TEST(LoadObjErrors, LoadMeshRefusesAFileOver2GiBBeforeReadingIt) {
    // a sparse file: no disk space, and reading it would take seconds and gigabytes
    const std::string path =
        (fs::temp_directory_path() / ("raylane_huge_" + std::to_string(::getpid()) + ".obj"))
            .string();
    std::ofstream(path) << "v 0 0 0\n";
    fs::resize_file(path, uintmax_t(max_mesh_file_bytes) + 1);
    const std::string message = test::input_error_of([&] { load_mesh(path); });
    fs::remove(path);
    EXPECT_EQ(message, path + ": file is 2147483649 bytes, over the limit of 2^31 for a mesh");
}

TEST(LoadObjErrors, SaysAnEmptyFileIsEmpty) {
    EXPECT_EQ(test::input_error_of([] { obj(""); }), "test.obj: is empty");
    test::TempDir dir("raylane_obj_");
    const std::string path = (dir.path / "empty.obj").string();
    test::write_bytes(path, "");
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }), path + ": is empty");
}

TEST(LoadObjErrors, SaysAUtf16FileIsUtf16) {
    const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::string little = "\xFF\xFE";
    std::string big = "\xFE\xFF";
    std::string unmarked;
    for (char c : text) {
        little += std::string{c, '\0'};
        big += std::string{'\0', c};
        unmarked += std::string{c, '\0'};
    }
    for (const std::string& bytes : {little, big, unmarked}) {
        EXPECT_EQ(test::input_error_of([&] { obj(bytes); }),
                  "test.obj: is UTF-16 text; save it as UTF-8 or ASCII");
    }
}

TEST(LoadObjErrors, SaysABinaryFileIsNotATextObj) {
    std::string bytes = "v 0 0 0\nv 1 0 0\n";
    bytes += std::string("\x7f\x45\x4c\x46\x02\x01\x01\x00", 8);  // an ELF header
    EXPECT_EQ(test::input_error_of([&] { obj(bytes); }),
              "test.obj: is a binary file, not a text OBJ (byte 23 is 0x00)");
    std::string controls = "v 0 0 0\n";
    for (int i = 0; i < 16; ++i) controls += static_cast<char>(1 + i % 8);
    EXPECT_EQ(test::input_error_of([&] { obj(controls); }),
              "test.obj: is a binary file, not a text OBJ (byte 23 is 0x08)");
    // gzip data under a plain name
    EXPECT_EQ(test::input_error_of([&] { obj(test::gzip("v 0 0 0\n")); }),
              "test.obj: is gzip-compressed; name it test.obj.gz to read it");
}

// hostile input --------------------------------------------------------------------------

TEST(LoadObjErrors, SurvivesRandomByteMutations) {
    const std::string valid = std::string(four_vertices) +
                              "# comment\r\nusemtl m\nf 1/1/1 2/2/2 3/3/3 4/4/4\n"
                              "f -1//-1 -2//-2 -3//-3\nf 1 2 3\n";
    ASSERT_EQ(obj(valid).tris.size(), 4u);
    std::mt19937 rng(20240611u);
    const char alphabet[] = "0123456789-+./ \t\r\n#eEfvtnx\x00\xff";
    int loaded = 0;
    int rejected = 0;
    for (int iteration = 0; iteration < 4000; ++iteration) {
        std::string text = valid;
        int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            size_t at = rng() % text.size();
            switch (rng() % 4) {
                case 0:
                    text[at] = static_cast<char>(rng() & 0xff);
                    break;
                case 1:
                    text[at] = alphabet[rng() % (sizeof alphabet - 1)];
                    break;
                case 2:
                    text.insert(at, 1, alphabet[rng() % (sizeof alphabet - 1)]);
                    break;
                default:
                    text.resize(at + 1);
                    break;
            }
        }
        try {
            MeshData m = obj(text);
            auto in_range = [](const std::vector<uvec3>& tris, size_t n) {
                for (const uvec3& t : tris) {
                    if (t.x >= n || t.y >= n || t.z >= n) return false;
                }
                return true;
            };
            ASSERT_TRUE(in_range(m.tris, m.positions.size())) << text;
            ASSERT_TRUE(in_range(m.uv_tris, m.uvs.size())) << text;
            ASSERT_TRUE(in_range(m.normal_tris, m.normals.size())) << text;
            ASSERT_TRUE(m.uv_tris.empty() || m.uv_tris.size() == m.tris.size());
            ASSERT_TRUE(m.normal_tris.empty() || m.normal_tris.size() == m.tris.size());
            ++loaded;
        } catch (const InputError& e) {
            ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            ++rejected;
        }
    }
    // Both outcomes happen, so the mutations neither always break nor never touch the file.
    EXPECT_GT(loaded, 0);
    EXPECT_GT(rejected, 0);
}

}  // namespace
}  // namespace raylane
