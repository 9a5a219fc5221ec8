// tests for io/load_ply.cpp: every format and property layout written by a small PLY writer
// here, the shipped PLY files, malformed input and random byte mutations. Twin of
// load_obj_test.cpp.
#include "io/load_ply.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "support/gzip.h"
#include "support/input_error.h"
#include "support/models.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

MeshData ply(std::string_view bytes) { return load_ply_from_memory(bytes, "test.ply"); }

void expect_ply_error(std::string_view bytes, std::initializer_list<std::string> parts) {
    std::string message = test::input_error_of([&] { ply(bytes); });
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : parts) {
        EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
}

// a PLY writer ---------------------------------------------------------------------------

/// The mesh every layout below writes: integer coordinates (exact in every type), a quad,
/// a triangle and a pentagon (6 triangles after the fan).
const std::vector<vec3> ref_positions = {{-1, 0, 2}, {2, -2, 1}, {3, 1, 0}, {0, 3, -1}, {1, 1, 1}};
const std::vector<vec3> ref_normals = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}};
const std::vector<vec2> ref_uvs = {{0, 0}, {0.5, 0}, {1, 0.5}, {0.25, 1}, {0.75, 0.75}};
const std::vector<std::vector<double>> ref_faces = {{0, 1, 2, 3}, {0, 3, 4}, {4, 3, 2, 1, 0}};
const std::vector<uvec3> ref_tris = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4},
                                     {4, 3, 2}, {4, 2, 1}, {4, 1, 0}};

struct PropSpec {
    std::string count_type;  ///< empty for a scalar property
    std::string type;
    std::string name;
};

struct ElementSpec {
    std::string name;
    size_t count = 0;
    std::vector<PropSpec> props;
};

enum class Format { ascii, little, big };
const char* format_name(Format f) {
    return f == Format::ascii    ? "ascii"
           : f == Format::little ? "binary_little_endian"
                                 : "binary_big_endian";
}

/// Values of property `p` of record `r`: mesh data for known names, filler otherwise.
std::vector<double> values_of(const ElementSpec& e, const PropSpec& p, size_t r) {
    if (e.name == "vertex") {
        const std::string& n = p.name;
        if (n == "x") return {ref_positions[r].x};
        if (n == "y") return {ref_positions[r].y};
        if (n == "z") return {ref_positions[r].z};
        if (n == "nx") return {ref_normals[r].x};
        if (n == "ny") return {ref_normals[r].y};
        if (n == "nz") return {ref_normals[r].z};
        if (n == "u" || n == "s" || n == "texture_u") return {ref_uvs[r].x};
        if (n == "v" || n == "t" || n == "texture_v") return {ref_uvs[r].y};
    }
    if (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index")) {
        return ref_faces[r];
    }
    if (!p.count_type.empty()) return std::vector<double>(r % 3, 7.0);  // lists of 0, 1, 2 items
    return {static_cast<double>(r % 5)};
}

template <class T>
void put(std::string& out, double value, bool big) {
    auto v = static_cast<T>(value);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    if (big) std::reverse(bytes, bytes + sizeof(T));
    out.append(bytes, sizeof(T));
}

void put_value(std::string& out, const std::string& type, double value, Format format) {
    if (format == Format::ascii) {
        char text[64];
        std::snprintf(text, sizeof text, "%.9g ", value);
        out += text;
        return;
    }
    const bool big = format == Format::big;
    if (type == "char" || type == "int8") return put<int8_t>(out, value, big);
    if (type == "uchar" || type == "uint8") return put<uint8_t>(out, value, big);
    if (type == "short" || type == "int16") return put<int16_t>(out, value, big);
    if (type == "ushort" || type == "uint16") return put<uint16_t>(out, value, big);
    if (type == "int" || type == "int32") return put<int32_t>(out, value, big);
    if (type == "uint" || type == "uint32") return put<uint32_t>(out, value, big);
    if (type == "float" || type == "float32") return put<float>(out, value, big);
    if (type == "double" || type == "float64") return put<double>(out, value, big);
    ADD_FAILURE() << "unknown type " << type;
}

std::string write_header(Format format, const std::vector<ElementSpec>& elements) {
    std::string out = "ply\nformat " + std::string(format_name(format)) + " 1.0\n";
    out += "comment written by load_ply_test\nobj_info nothing\n";
    for (const ElementSpec& e : elements) {
        out += "element " + e.name + " " + std::to_string(e.count) + "\n";
        for (const PropSpec& p : e.props) {
            out += "property " + (p.count_type.empty() ? "" : "list " + p.count_type + " ") +
                   p.type + " " + p.name + "\n";
        }
    }
    return out + "end_header\n";
}

std::string write_ply(Format format, const std::vector<ElementSpec>& elements) {
    std::string out = write_header(format, elements);
    for (const ElementSpec& e : elements) {
        for (size_t r = 0; r < e.count; ++r) {
            for (const PropSpec& p : e.props) {
                std::vector<double> values = values_of(e, p, r);
                if (!p.count_type.empty()) {
                    put_value(out, p.count_type, static_cast<double>(values.size()), format);
                }
                for (double v : values) put_value(out, p.type, v, format);
            }
            if (format == Format::ascii) out += "\n";
        }
    }
    return out;
}

const ElementSpec plain_vertex{
    "vertex", 5, {{"", "float", "x"}, {"", "float", "y"}, {"", "float", "z"}}};
const ElementSpec plain_face{"face", 3, {{"uchar", "int", "vertex_indices"}}};

struct Layout {
    const char* label;
    std::vector<ElementSpec> elements;
    bool normals;
    bool uvs;
};

/// Odd property orders, mixed and sized type names, every uv naming, extra properties before
/// and after the index list, extra elements before and after, lists inside the vertex
/// element (so vertex records have variable size), every list count type.
std::vector<Layout> layouts() {
    return {
        {"plain", {plain_vertex, plain_face}, false, false},
        {"normals and uv, odd order",
         {{"vertex",
           5,
           {{"", "float", "nz"},
            {"", "int", "flags"},
            {"", "float", "v"},
            {"", "float", "z"},
            {"", "float", "nx"},
            {"", "float", "u"},
            {"", "float", "y"},
            {"", "float", "ny"},
            {"", "float", "x"}}},
          {"face",
           3,
           {{"", "uchar", "red"}, {"int", "uint", "vertex_index"}, {"", "int", "flags"}}}},
         true,
         true},
        {"mixed types, extra elements, lists everywhere",
         {{"material",
           2,
           {{"", "uchar", "red"}, {"int", "uchar", "name"}, {"", "double", "shine"}}},
          {"vertex",
           5,
           {{"", "double", "z"},
            {"", "short", "x"},
            {"uchar", "float", "extra_list"},
            {"", "int8", "y"},
            {"", "double", "s"},
            {"", "float64", "t"}}},
          {"face",
           3,
           {{"", "int", "before"},
            {"ushort", "short", "vertex_indices"},
            {"uchar", "float", "texcoord"},
            {"", "float", "after"}}},
          {"edge", 4, {{"", "int", "vertex1"}, {"", "int", "vertex2"}, {"char", "int", "more"}}}},
         false,
         true},
        {"sized names, texture_u, char and uint counts",
         {{"vertex",
           5,
           {{"", "int32", "x"},
            {"", "float32", "texture_v"},
            {"", "int16", "y"},
            {"", "float32", "texture_u"},
            {"", "float32", "z"},
            {"", "double", "nx"},
            {"", "int", "ny"},
            {"", "char", "nz"}}},
          {"face", 3, {{"char", "uint8", "vertex_indices"}}},
          {"tail", 1, {{"uint", "ushort", "stuff"}}}},
         true,
         true},
        {"uint count, int16 index",
         {plain_vertex, {"face", 3, {{"uint32", "int16", "vertex_indices"}, {"", "uint16", "id"}}}},
         false,
         false},
    };
}

void expect_reference_mesh(const MeshData& m, bool normals, bool uvs) {
    ASSERT_EQ(m.positions.size(), ref_positions.size());
    for (size_t i = 0; i < ref_positions.size(); ++i) EXPECT_EQ(m.positions[i], ref_positions[i]);
    ASSERT_EQ(m.tris.size(), ref_tris.size());
    for (size_t i = 0; i < ref_tris.size(); ++i) EXPECT_EQ(m.tris[i], ref_tris[i]) << i;
    if (normals) {
        ASSERT_EQ(m.normals.size(), ref_normals.size());
        for (size_t i = 0; i < ref_normals.size(); ++i) EXPECT_EQ(m.normals[i], ref_normals[i]);
        ASSERT_EQ(m.normal_tris.size(), ref_tris.size());
        for (size_t i = 0; i < ref_tris.size(); ++i) EXPECT_EQ(m.normal_tris[i], ref_tris[i]);
    } else {
        EXPECT_TRUE(m.normals.empty());
        EXPECT_TRUE(m.normal_tris.empty());
    }
    if (uvs) {
        ASSERT_EQ(m.uvs.size(), ref_uvs.size());
        for (size_t i = 0; i < ref_uvs.size(); ++i) EXPECT_EQ(m.uvs[i], ref_uvs[i]);
        ASSERT_EQ(m.uv_tris.size(), ref_tris.size());
        for (size_t i = 0; i < ref_tris.size(); ++i) EXPECT_EQ(m.uv_tris[i], ref_tris[i]);
    } else {
        EXPECT_TRUE(m.uvs.empty());
        EXPECT_TRUE(m.uv_tris.empty());
    }
}

// good input -----------------------------------------------------------------------------

TEST(LoadPly, ReadsEveryLayoutInEveryFormat) {
    for (const Layout& layout : layouts()) {
        for (Format format : {Format::ascii, Format::little, Format::big}) {
            SCOPED_TRACE(std::string(layout.label) + ", " + format_name(format));
            std::string bytes = write_ply(format, layout.elements);
            MeshData m = ply(bytes);
            expect_reference_mesh(m, layout.normals, layout.uvs);
            EXPECT_EQ(m.name, "test.ply");
        }
    }
}

TEST(LoadPly, AcceptsCrlfHeaderAndBlankLinesInAscii) {
    std::string text =
        "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\n"
        "property float y\r\nproperty float z\r\n\r\nelement face 1\r\n"
        "property list uchar int vertex_indices\r\nend_header\r\n"
        "0 0 0\r\n\r\n1 0 0 \r\n\t0 1 0\r\n3 0 1 2";
    MeshData m = ply(text);
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[1], vec3(1, 0, 0));
    ASSERT_EQ(m.tris.size(), 1u);
    EXPECT_EQ(m.tris[0], uvec3(0, 1, 2));
}

TEST(LoadPly, ReadsVerticesStoredAfterTheFaces) {
    std::string bytes = write_ply(Format::little, {plain_face, plain_vertex});
    expect_reference_mesh(ply(bytes), false, false);
}

TEST(LoadPly, IgnoresBytesAfterTheLastBinaryElement) {
    std::string bytes = write_ply(Format::big, {plain_vertex, plain_face}) + "trailing";
    expect_reference_mesh(ply(bytes), false, false);
}

TEST(LoadPly, ReadsCrOnlyAndMixedLineEnds) {
    const std::string lf = write_ply(Format::ascii, {plain_vertex, plain_face});
    std::string cr = lf;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    std::string mixed;
    int n = 0;
    for (char c : lf) mixed += c != '\n' ? std::string(1, c) : (++n % 2 ? "\r" : "\r\n");
    for (const std::string& text : {cr, mixed}) expect_reference_mesh(ply(text), false, false);
    // the last face line ("5 4 3 2 1 0 \r") cut off: 11 header lines, 5 vertices, 2 faces
    EXPECT_EQ(test::input_error_of([&] { ply(cr.substr(0, cr.size() - 13)); }),
              "test.ply:18: ends after 2 of 3 faces");
}

TEST(LoadPly, StartsABinaryBodyAfterTheHeadersOwnLineEnd) {
    // A body whose first byte is LF (x of vertex 0 is the float of bits 0x3f80000a): after a
    // CR-only header it is data, after CR LF and LF headers the same.
    const float x0 = std::bit_cast<float>(uint32_t{0x3f80000a});
    for (const char* end : {"\r", "\r\n", "\n"}) {
        SCOPED_TRACE(end[1] ? "CR LF" : end[0] == '\r' ? "CR" : "LF");
        std::string header = write_header(Format::little, {plain_vertex, plain_face});
        std::string ended;
        for (char c : header) ended += c == '\n' ? std::string(end) : std::string(1, c);
        std::string bytes = write_ply(Format::little, {plain_vertex, plain_face});
        bytes.replace(0, header.size(), ended);
        std::memcpy(&bytes[ended.size()], &x0, 4);
        ASSERT_EQ(bytes[ended.size()], '\n');
        MeshData m = ply(bytes);
        ASSERT_EQ(m.positions.size(), 5u);
        EXPECT_EQ(m.positions[0], vec3(x0, ref_positions[0].y, ref_positions[0].z));
        EXPECT_EQ(m.positions[4], ref_positions[4]);
        EXPECT_EQ(m.tris.size(), ref_tris.size());
    }
}

// shipped models -------------------------------------------------------------------------

TEST(LoadPly, ReadsTheBinaryDragon) {
    const std::string path = test::models_dir + "/dragon.ply";
    if (!fs::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    MeshData m = load_ply(path);
    EXPECT_EQ(m.name, "dragon.ply");
    EXPECT_EQ(m.positions.size(), 50000u);
    EXPECT_EQ(m.tris.size(), 100000u);
    EXPECT_EQ(m.normals.size(), 50000u);
    EXPECT_EQ(m.normal_tris.size(), 100000u);
    EXPECT_TRUE(m.uv_tris.empty());
    // models/README.md: unit normals; bounding box +-1.35294 x +-0.95421 x +-0.60505.
    float worst = 0.0f;
    vec3 hi(0.0f);
    for (size_t i = 0; i < m.positions.size(); ++i) {
        worst = std::max(worst, std::abs(glm::length(m.normals[i]) - 1.0f));
        hi = glm::max(hi, glm::abs(m.positions[i]));
    }
    EXPECT_LT(worst, 1e-3f);
    EXPECT_NEAR(hi.x, 1.35294f, 1e-4f);
    EXPECT_NEAR(hi.y, 0.95421f, 1e-4f);
    EXPECT_NEAR(hi.z, 0.60505f, 1e-4f);
}

TEST(LoadPly, ReadsTheAsciiBunny) {
    const std::string path = test::models_dir + "/bunny.ply";
    if (!fs::exists(path)) RAYLANE_MODEL_MISSING() << path << " not present";
    MeshData m = load_ply(path);
    EXPECT_EQ(m.positions.size(), 35947u);
    EXPECT_EQ(m.tris.size(), 69451u);
    EXPECT_TRUE(m.normal_tris.empty());
    EXPECT_TRUE(m.uv_tris.empty());
    vec3 lo(INFINITY), hi(-INFINITY);
    for (const vec3& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    // models/README.md: min (-0.09469, 0.03299, -0.06187), max (0.06101, 0.18732, 0.05880).
    EXPECT_NEAR(lo.x, -0.09469f, 1e-5f);
    EXPECT_NEAR(lo.y, 0.03299f, 1e-5f);
    EXPECT_NEAR(hi.y, 0.18732f, 1e-5f);
    EXPECT_NEAR(hi.z, 0.05880f, 1e-5f);
}

// malformed input ------------------------------------------------------------------------

const std::string ascii_header =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
// ascii_header has 9 lines: the first vertex is on line 10.

TEST(LoadPlyErrors, RejectsAMissingMagic) {
    expect_ply_error("PLY\nformat ascii 1.0\n", {"test.ply:1:", "'ply'"});
    expect_ply_error("", {"test.ply", "empty"});
    expect_ply_error("\x89PNG\r\n\x1a\n", {"test.ply:1:", "not a PLY file"});
}

TEST(LoadPlyErrors, RejectsUnsupportedFormatsAndBadHeaders) {
    expect_ply_error("ply\nformat binary_middle_endian 1.0\nend_header\n",
                     {"test.ply:2:", "unsupported format 'binary_middle_endian'"});
    expect_ply_error("ply\nformat ascii 2.0\nend_header\n", {"test.ply:2:", "version"});
    expect_ply_error("ply\nformat ascii 1.0\nproperty float x\n",
                     {"test.ply:3:", "property before any element"});
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex many\n", {"test.ply:3:", "bad header"});
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\n",
                     {"test.ply:4:", "unknown property type 'float128'"});
    expect_ply_error("ply\nformat ascii 1.0\nelemnt vertex 1\n",
                     {"test.ply:3:", "unknown keyword"});
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n",
                     {"test.ply:4:", "no end_header"});
    expect_ply_error("ply\nelement vertex 0\nproperty float x\nend_header\n",
                     {"test.ply:4:", "no format line"});
    expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\n",
                     {"test.ply:4:", "count type must be an integer"});
}

/// A header cut in the middle of a line (a download cut short) says that the file ends there,
/// not that the half word is unknown.
TEST(LoadPlyErrors, AHeaderCutMidLineSaysTheFileEndsThere) {
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty u",
        {"test.ply:4:", "the file ends inside the header, after 'property u'", "cut short"});
    expect_ply_error("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x",
                     {"test.ply:4:", "the file ends inside the header"});
    expect_ply_error("ply\nformat ascii 1.0\nelem", {"test.ply:3:", "ends inside the header"});
}

TEST(LoadPlyErrors, RequiresXyzAndVertexIndices) {
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "element face 0\nproperty list uchar int vertex_indices\nend_header\n",
        {"test.ply:3:", "no 'z' property"});
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int corners\nend_header\n",
        {"test.ply:7:", "vertex_indices"});
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n0 0 0\n",
        {"test.ply", "no 'face' element"});
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float nx\nelement face 0\n"
        "property list uchar int vertex_indices\nend_header\n",
        {"test.ply:3:", "nx ny nz"});
}

TEST(LoadPlyErrors, ReportsTheByteOffsetOfATruncatedBinaryBody) {
    const std::string full = write_ply(Format::little, {plain_vertex, plain_face});
    const size_t header = write_header(Format::little, {plain_vertex, plain_face}).size();
    // Cut inside the faces: the vertex block (5 * 12 bytes) is whole, faces are not.
    const size_t faces_at = header + 60;
    // Faces of 17, 13 and 21 bytes; the last one loses its last byte. The count check
    // (3 faces of at least 13 bytes) passes, the pentagon's list does not fit.
    std::string cut = full.substr(0, faces_at + 17 + 13 + 20);
    EXPECT_EQ(test::input_error_of([&] { ply(cut); }),
              "test.ply: byte " + std::to_string(faces_at + 30) +
                  ": list count 5 in 'vertex_indices' needs 20 bytes, but only 19 remain: the "
                  "file ends after 2 of 3 faces");
    // Cut inside the vertices: caught before any vertex is read.
    EXPECT_EQ(test::input_error_of([&] { ply(full.substr(0, header + 30)); }),
              "test.ply: byte " + std::to_string(header + 30) + ": ends after 2 of 5 vertices");
}

TEST(LoadPlyErrors, RejectsABillionVertexHeaderBeforeAllocating) {
    std::string bytes =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n" +
        std::string(1000, '\0');
    EXPECT_EQ(test::input_error_of([&] { ply(bytes); }),
              "test.ply: byte " + std::to_string(bytes.size()) +
                  ": ends after 83 of 1000000000 vertices");
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 18446744073709551615\n"
        "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    EXPECT_EQ(test::input_error_of([&] { ply(text); }),
              "test.ply:13: ends after 1 of 18446744073709551615 faces");
    expect_ply_error(
        "ply\nformat ascii 1.0\nelement vertex 5000000000\nproperty float x\nend_header\n",
        {"test.ply:3:", "too many vertices"});
}

TEST(LoadPlyErrors, RejectsNegativeAndHugeListCounts) {
    ElementSpec vertex = plain_vertex;
    ElementSpec signed_face{"face", 3, {{"char", "int", "vertex_indices"}}};
    std::string bytes = write_ply(Format::little, {vertex, signed_face});
    const size_t faces_at = write_header(Format::little, {vertex, signed_face}).size() + 60;
    bytes[faces_at] = static_cast<char>(-2);
    expect_ply_error(bytes,
                     {"test.ply: byte " + std::to_string(faces_at), "negative list count -2"});

    ElementSpec wide_face{"face", 3, {{"uint", "int", "vertex_indices"}}};
    bytes = write_ply(Format::big, {vertex, wide_face});
    const size_t wide_at = write_header(Format::big, {vertex, wide_face}).size() + 60;
    std::memset(&bytes[wide_at], 0xff, 4);
    expect_ply_error(bytes, {"test.ply: byte " + std::to_string(wide_at), "list count 4294967295"});

    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n",
                     {"test.ply:13:", "negative list count -3"});
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n",
                     {"test.ply:13:", "list count '256' does not fit the uchar"});
}

TEST(LoadPlyErrors, RejectsFacesWithFewerThanThreeVertices) {
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", {"test.ply:13:", "at least 3"});
    std::string bytes = write_ply(Format::little, {plain_vertex, plain_face});
    const size_t faces_at = write_header(Format::little, {plain_vertex, plain_face}).size() + 60;
    bytes[faces_at] = 2;
    expect_ply_error(bytes, {"test.ply: byte " + std::to_string(faces_at), "at least 3"});
}

TEST(LoadPlyErrors, RejectsVertexIndicesOutOfRange) {
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
                     {"test.ply:13:", "vertex index 3 out of range (3 vertices)"});
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n",
                     {"test.ply:13:", "negative vertex index -1"});
    std::string bytes = write_ply(Format::big, {plain_vertex, plain_face});
    const size_t faces_at = write_header(Format::big, {plain_vertex, plain_face}).size() + 60;
    // Third corner of the first face: big-endian int 5 = 00 00 00 05.
    bytes[faces_at + 1 + 2 * 4 + 3] = 5;
    expect_ply_error(bytes, {"test.ply: byte " + std::to_string(faces_at + 9),
                             "vertex index 5 out of range (5 vertices)"});
}

TEST(LoadPlyErrors, ReportsTheLineOfBadAsciiValues) {
    expect_ply_error(ascii_header + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n",
                     {"test.ply:11:", "bad number 'zero'", "'y'"});
    expect_ply_error(ascii_header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n",
                     {"test.ply:11:", "too few values", "'z'"});
    expect_ply_error(ascii_header + "0 0 0\n1 0 0 1\n0 1 0\n3 0 1 2\n",
                     {"test.ply:11:", "too many values"});
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n",
                     {"test.ply:13:", "bad integer '2.5'"});
    // No room left for the face: caught by the count check, named at the last line.
    EXPECT_EQ(test::input_error_of([&] { ply(ascii_header + "0 0 0\n1 0 0\n0 1 0\n"); }),
              "test.ply:12: ends after 0 of 1 face");
    // Room for the records, but only blank lines: caught when the lines run out.
    EXPECT_EQ(
        test::input_error_of([&] { ply(ascii_header + "0 0 0\n1 0 0\n" + std::string(20, '\n')); }),
        "test.ply:31: ends after 2 of 3 vertices");
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n4 0 1 2 0\n",
                     {"test.ply:14:", "after the last element"});
    expect_ply_error(ascii_header + "0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n",
                     {"test.ply:10:", "not a finite float"});
}

TEST(LoadPlyErrors, SaysAnEmptyFileIsEmpty) {
    EXPECT_EQ(test::input_error_of([] { ply(""); }), "test.ply: is empty");
}

TEST(LoadPlyErrors, SaysAUtf16FileIsUtf16) {
    std::string little = "\xFF\xFE";
    std::string unmarked;
    for (char c : ascii_header) {
        little += std::string{c, '\0'};
        unmarked += std::string{'\0', c};
    }
    for (const std::string& bytes : {little, unmarked}) {
        EXPECT_EQ(test::input_error_of([&] { ply(bytes); }),
                  "test.ply: is UTF-16 text; save it as UTF-8 or ASCII");
    }
    EXPECT_EQ(test::input_error_of([&] { ply(test::gzip(ascii_header)); }),
              "test.ply: is gzip-compressed; name it test.ply.gz to read it");
}

TEST(LoadPlyErrors, SaysWhereAnAsciiFileEndsAndHowManyRecordsItPromised) {
    // 5 vertices promised, 3 given; the face count (1) on its own would fit
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_EQ(test::input_error_of([&] { ply(text); }), "test.ply:12: ends after 3 of 5 vertices");
    // the same with blank lines between records
    text.insert(text.size() - 6, "\n\n");
    EXPECT_EQ(test::input_error_of([&] { ply(text); }), "test.ply:14: ends after 3 of 5 vertices");
    // a last line without its end, cut inside a number or not, is no whole record
    for (size_t cut : {1, 3}) {
        EXPECT_EQ(test::input_error_of([&] { ply(text.substr(0, text.size() - cut)); }),
                  "test.ply:14: ends after 2 of 5 vertices (the last line is cut short)");
    }
    // a bad last record with nothing promised after it is reported as itself
    expect_ply_error(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1",
                     {"test.ply:13:", "too few values"});
    // an element after the faces: its own records and name
    const std::string edges =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
        "element edge 2\nproperty int a\nproperty int b\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 1\n";
    EXPECT_EQ(test::input_error_of([&] { ply(edges); }),
              "test.ply:17: ends after 1 of 2 'edge' records");
}

TEST(LoadPlyErrors, SaysWhereABinaryFileEndsAndHowManyRecordsItPromised) {
    const std::string full = write_ply(Format::big, {plain_vertex, plain_face});
    const size_t faces_at = write_header(Format::big, {plain_vertex, plain_face}).size() + 60;
    // faces of 17, 13 and 21 bytes. Cut after the first face: 3 faces of at least 13 bytes do
    // not fit in 17 + 12, so the whole faces are counted before any is read.
    std::string cut = full.substr(0, faces_at + 17 + 12);
    EXPECT_EQ(test::input_error_of([&] { ply(cut); }),
              "test.ply: byte " + std::to_string(cut.size()) + ": ends after 1 of 3 faces");
    // Cut in the last property of the last face: there is room for 3 faces of the smallest
    // size (17 bytes), so the faces are read until one does not fit.
    std::vector<ElementSpec> elements = layouts()[2].elements;
    elements.pop_back();  // (no edges after the faces)
    const std::string lists = write_ply(Format::little, elements);
    cut = lists.substr(0, lists.size() - 1);
    EXPECT_EQ(test::input_error_of([&] { ply(cut); }),
              "test.ply: byte " + std::to_string(cut.size()) + ": ends after 2 of 3 faces");
    // The file ends inside the header's vertex records: no byte of them is read.
    EXPECT_EQ(test::input_error_of([&] { ply(full.substr(0, faces_at - 1)); }),
              "test.ply: byte " + std::to_string(faces_at - 1) + ": ends after 4 of 5 vertices");
}

TEST(LoadPlyErrors, RejectsNonFiniteBinaryVertices) {
    std::string bytes = write_ply(Format::little, {plain_vertex, plain_face});
    const size_t vertices_at = write_header(Format::little, {plain_vertex, plain_face}).size();
    const float inf = INFINITY;
    std::memcpy(&bytes[vertices_at + 12 + 4], &inf, 4);  // y of vertex 1
    expect_ply_error(bytes, {"test.ply: byte " + std::to_string(vertices_at + 16),
                             "vertex y is not a finite float"});
}

TEST(LoadPlyErrors, NamesAMissingFile) {
    std::string message = test::input_error_of([] { load_ply("/nonexistent/raylane/gone.ply"); });
    EXPECT_NE(message.find("/nonexistent/raylane/gone.ply: cannot read"), std::string::npos)
        << message;
}

// hostile input --------------------------------------------------------------------------

TEST(LoadPlyErrors, SurvivesRandomByteMutations) {
    const Layout layout = layouts()[2];
    std::mt19937 rng(7919u);
    for (Format format : {Format::ascii, Format::little, Format::big}) {
        SCOPED_TRACE(format_name(format));
        const std::string valid = write_ply(format, layout.elements);
        ASSERT_EQ(ply(valid).tris.size(), ref_tris.size());
        int loaded = 0;
        int rejected = 0;
        for (int iteration = 0; iteration < 1500; ++iteration) {
            std::string bytes = valid;
            int edits = 1 + static_cast<int>(rng() % 3);
            for (int e = 0; e < edits; ++e) {
                size_t at = rng() % bytes.size();
                switch (rng() % 4) {
                    case 0:
                        bytes[at] = static_cast<char>(rng() & 0xff);
                        break;
                    case 1:
                        bytes[at] = static_cast<char>(bytes[at] ^ (1 << (rng() % 8)));
                        break;
                    case 2:
                        bytes[at] = "0123456789 -\n"[rng() % 13];
                        break;
                    default:
                        bytes.resize(at + 1);
                        break;
                }
            }
            try {
                MeshData m = ply(bytes);
                for (const uvec3& t : m.tris) {
                    ASSERT_TRUE(t.x < m.positions.size() && t.y < m.positions.size() &&
                                t.z < m.positions.size());
                }
                ++loaded;
            } catch (const InputError& e) {
                ASSERT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
                ++rejected;
            }
        }
        EXPECT_GT(loaded, 0);
        EXPECT_GT(rejected, 0);
    }
}

}  // namespace
}  // namespace raylane
