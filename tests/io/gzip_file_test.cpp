// io: gzip-compressed models (gzip_file.h): inflated bytes equal the original, members one after
// another, a size the trailer does not give, OBJ and PLY files read through load_mesh, and the
// one-line refusals of broken gzip files. Every .gz is made here with zlib (support/gzip.h).
#include "io/gzip_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>

#include "io/load_mesh.h"
#include "io/load_obj.h"
#include "io/load_ply.h"
#include "support/gzip.h"
#include "support/input_error.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

/// A text of `lines` OBJ vertex lines, different from line to line (so it compresses, but not
/// to nothing).
std::string gz_vertex_lines(int lines) {
    std::string text;
    for (int i = 0; i < lines; ++i) {
        text += "v " + std::to_string(i) + " " + std::to_string(i % 7) + " 0.5\n";
    }
    return text;
}

const char* const gz_square_obj =
    "# a unit square\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nvt 0 0\r\nvt 1 1\r\n"
    "f 1/1 2/1 3/2\r\nf 1/1 3/2 4/2\r\n";

TEST(InflateFile, GivesTheBytesThatWereCompressed) {
    test::TempDir dir("raylane_gzip_");
    const std::string text = gz_vertex_lines(20000);  // about 300 KB: several input chunks
    const std::string path = (dir.path / "lines.obj.gz").string();
    test::write_bytes(path, test::gzip(text));
    EXPECT_EQ(inflate_file(path).view(), text);
    EXPECT_EQ(read_model_file(path).view(), text);
    // a plain file is mapped as it is
    test::write_bytes(dir.path / "lines.obj", text);
    EXPECT_EQ(read_model_file((dir.path / "lines.obj").string()).view(), text);
}

TEST(InflateFile, ReadsMembersOneAfterAnother) {
    test::TempDir dir("raylane_gzip_");
    // the trailer's length is the last member's, far short of the whole: the block grows
    const std::string first = gz_vertex_lines(50000);
    const std::string second = "v 9 9 9\n";
    const std::string path = (dir.path / "joined.obj.gz").string();
    test::write_bytes(path, test::gzip(first) + test::gzip(second, 9));
    EXPECT_EQ(inflate_file(path).view(), first + second);
}

TEST(InflateFile, ReadsAPipeWhoseSizeIsUnknown) {
    test::TempDir dir("raylane_gzip_");
    const std::string text = gz_vertex_lines(120000);  // past the first guess of 1 MiB
    const std::filesystem::path fifo = dir.path / "pipe.obj.gz";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string compressed = test::gzip(text, 1);
    std::thread writer([&] { test::write_bytes(fifo, compressed); });
    const std::string got(inflate_file(fifo.string()).view());
    writer.join();
    EXPECT_GT(text.size(), size_t{1} << 20);
    EXPECT_EQ(got, text);
}

TEST(InflateFile, TellsGzipNamesApartInAnyCase) {
    EXPECT_TRUE(has_gzip_extension("models/bunny.ply.gz"));
    EXPECT_TRUE(has_gzip_extension("BUNNY.PLY.GZ"));
    EXPECT_TRUE(has_gzip_extension(".gz"));
    EXPECT_FALSE(has_gzip_extension("bunny.ply"));
    EXPECT_FALSE(has_gzip_extension("bunny.tgz"));
    EXPECT_FALSE(has_gzip_extension("gz"));
}

TEST(LoadMeshGzip, ReadsAnObjGzLikeThePlainObj) {
    test::TempDir dir("raylane_gzip_");
    test::write_bytes(dir.path / "square.obj", gz_square_obj);
    test::write_bytes(dir.path / "square.OBJ.GZ", test::gzip(gz_square_obj));
    const MeshData plain = load_mesh((dir.path / "square.obj").string());
    const MeshData packed = load_mesh((dir.path / "square.OBJ.GZ").string());
    EXPECT_EQ(packed.name, "square.OBJ.GZ");
    ASSERT_EQ(packed.positions.size(), 4u);
    EXPECT_EQ(packed.positions[2], vec3(1, 1, 0));
    ASSERT_EQ(packed.tris.size(), 2u);
    EXPECT_EQ(packed.tris[1], uvec3(0, 2, 3));
    ASSERT_EQ(packed.uv_tris.size(), 2u);
    EXPECT_EQ(packed.uv_tris[1], uvec3(0, 1, 1));
    EXPECT_EQ(packed.positions, plain.positions);
    EXPECT_EQ(packed.tris, plain.tris);
    EXPECT_EQ(packed.uvs, plain.uvs);
}

TEST(LoadMeshGzip, ReadsAsciiAndBinaryPlyGz) {
    test::TempDir dir("raylane_gzip_");
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n2 0 0\n0 3 0.5\n3 0 1 2\n";
    std::string binary =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 2, 0, 0, 0, 3, 0.5f};
    binary.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const int32_t face[3] = {0, 1, 2};
    binary += '\3';
    binary.append(reinterpret_cast<const char*>(face), sizeof face);
    test::write_bytes(dir.path / "ascii.ply.gz", test::gzip(ascii));
    test::write_bytes(dir.path / "binary.ply.gz", test::gzip(binary));
    for (const char* name : {"ascii.ply.gz", "binary.ply.gz"}) {
        SCOPED_TRACE(name);
        const MeshData m = load_mesh((dir.path / name).string());
        EXPECT_EQ(m.name, name);
        ASSERT_EQ(m.positions.size(), 3u);
        EXPECT_EQ(m.positions[2], vec3(0, 3, 0.5f));
        ASSERT_EQ(m.tris.size(), 1u);
        EXPECT_EQ(m.tris[0], uvec3(0, 1, 2));
    }
    // the readers themselves take .gz names too
    EXPECT_EQ(load_ply((dir.path / "binary.ply.gz").string()).tris.size(), 1u);
}

TEST(LoadMeshGzip, CountsLinesAndBytesInTheDecompressedData) {
    test::TempDir dir("raylane_gzip_");
    const std::string path = (dir.path / "bad.obj.gz").string();
    test::write_bytes(path, test::gzip("v 0 0 0\nv 1 0 0\nv 0 one 0\nf 1 2 3\n"));
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }), path + ":3: bad number 'one' for y");
}

TEST(LoadMeshGzip, RefusesOtherCompressedFormats) {
    EXPECT_EQ(test::input_error_of([] { load_mesh("models/teapot.stl.gz"); }),
              "models/teapot.stl.gz: unsupported mesh format '.stl.gz'; expected .obj or .ply, "
              "or either with .gz");
    EXPECT_EQ(test::input_error_of([] { load_mesh("models/teapot.gz"); }),
              "models/teapot.gz: unsupported mesh format '.gz'; expected .obj or .ply, or "
              "either with .gz");
}

// broken gzip files ----------------------------------------------------------------------

TEST(InflateFileErrors, SaysAGzipFileThatEndsEarlyEndsEarly) {
    test::TempDir dir("raylane_gzip_");
    const std::string packed = test::gzip(gz_vertex_lines(2000));
    const std::string path = (dir.path / "cut.obj.gz").string();
    test::write_bytes(path, packed.substr(0, packed.size() / 2));
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }),
              path + ": gzip data ends early, after " + std::to_string(packed.size() / 2) +
                  " compressed bytes");
    // only the trailer missing
    test::write_bytes(path, packed.substr(0, packed.size() - 8));
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }),
              path + ": gzip data ends early, after " + std::to_string(packed.size() - 8) +
                  " compressed bytes");
}

TEST(InflateFileErrors, SaysCorruptDataIsCorrupt) {
    test::TempDir dir("raylane_gzip_");
    std::string packed = test::gzip(gz_square_obj);
    packed[packed.size() - 8] = static_cast<char>(packed[packed.size() - 8] ^ 1);  // the CRC-32
    const std::string path = (dir.path / "crc.obj.gz").string();
    test::write_bytes(path, packed);
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }),
              path + ": gzip data is corrupt at compressed byte " +
                  std::to_string(packed.size() - 4) + " (zlib: incorrect data check)");
}

TEST(InflateFileErrors, SaysAPlainFileWithAGzipNameIsNotGzip) {
    test::TempDir dir("raylane_gzip_");
    const std::string path = (dir.path / "plain.obj.gz").string();
    test::write_bytes(path, gz_square_obj);
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }),
              path + ": is not gzip data (it does not start with 1f 8b)");
}

TEST(InflateFileErrors, SaysWhatFollowsTheGzipDataIsNotGzip) {
    test::TempDir dir("raylane_gzip_");
    const std::string packed = test::gzip(gz_square_obj);
    const std::string path = (dir.path / "tail.obj.gz").string();
    test::write_bytes(path, packed + "tail");
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }),
              path + ": data after the end of the gzip data at compressed byte " +
                  std::to_string(packed.size()));
}

TEST(InflateFileErrors, SaysAnEmptyGzipFileOrContentIsEmpty) {
    test::TempDir dir("raylane_gzip_");
    const std::string path = (dir.path / "empty.obj.gz").string();
    test::write_bytes(path, "");
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }), path + ": is empty");
    test::write_bytes(path, test::gzip(""));
    EXPECT_TRUE(inflate_file(path).view().empty());
    EXPECT_EQ(test::input_error_of([&] { load_mesh(path); }), path + ": is empty");
}

TEST(InflateFileErrors, RefusesMoreThanTheLimitOnceDecompressed) {
    test::TempDir dir("raylane_gzip_");
    const std::string path = (dir.path / "bomb.obj.gz").string();
    test::write_bytes(path, test::gzip(std::string(100000, '#')));
    EXPECT_EQ(inflate_file(path, 100000).view().size(), 100000u);
    EXPECT_EQ(test::input_error_of([&] { inflate_file(path, 99999); }),
              path + ": decompresses to more than 99999 bytes, over the limit for a mesh");
}

TEST(InflateFileErrors, NamesAMissingFileAndAFolder) {
    test::TempDir dir("raylane_gzip_");
    const std::string missing = (dir.path / "gone.ply.gz").string();
    EXPECT_EQ(test::input_error_of([&] { load_mesh(missing); }),
              missing + ": cannot read: No such file or directory");
    const std::string folder = (dir.path / "folder.ply.gz").string();
    std::filesystem::create_directories(folder);
    EXPECT_EQ(test::input_error_of([&] { load_mesh(folder); }),
              folder + ": cannot read: Is a directory");
}

}  // namespace
}  // namespace raylane
