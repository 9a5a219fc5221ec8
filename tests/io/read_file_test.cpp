// io: map_file and read_file (read_file.h): a regular file mapped, files of no size (procfs,
// empty files) and pipes read, the bytes unchanged, the errors of one line.
#include "io/read_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "core/error.h"
#include "support/temp_dir.h"

namespace raylane {
namespace {

namespace fs = std::filesystem;

TEST(MapFile, GivesARegularFilesBytesUnchanged) {
    test::TempDir dir("raylane_read_file_");
    std::string bytes = "ply\r\nformat binary_little_endian 1.0\n";
    bytes += std::string("\0\x01\xff\r\n", 5);
    for (int i = 0; i < 5000; ++i) bytes += static_cast<char>(i * 7);  // more than a page
    test::write_bytes(dir.path / "a.bin", bytes);
    const FileBytes mapped = map_file((dir.path / "a.bin").string());
    EXPECT_EQ(mapped.view(), bytes);
    // mapped, not read: the bytes start on a page
    EXPECT_EQ(reinterpret_cast<uintptr_t>(mapped.view().data()) % 4096, 0u);
    EXPECT_EQ(read_file((dir.path / "a.bin").string()), bytes);
    // moved: the new owner keeps the bytes, the old one is empty
    FileBytes moved = map_file((dir.path / "a.bin").string());
    FileBytes owner = std::move(moved);
    EXPECT_EQ(owner.view(), bytes);
    EXPECT_TRUE(moved.view().empty());  // NOLINT(bugprone-use-after-move): what a move leaves
    owner = map_file((dir.path / "a.bin").string());
    EXPECT_EQ(owner.view(), bytes);
}

TEST(MapFile, ReadsFilesOfNoSizeAndPipes) {
    test::TempDir dir("raylane_read_file_");
    test::write_bytes(dir.path / "empty", "");
    EXPECT_TRUE(map_file((dir.path / "empty").string()).view().empty());
    // procfs reports a size of 0 for a file that has bytes
    EXPECT_NE(map_file("/proc/self/status").view().find("Name:"), std::string_view::npos);
    // a pipe, written while it is read, longer than the first read
    const fs::path fifo = dir.path / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string bytes(200000, 'x');
    std::thread writer([&] { test::write_bytes(fifo, bytes); });
    const std::string got = std::string(map_file(fifo.string()).view());
    writer.join();
    EXPECT_EQ(got, bytes);
}

TEST(MapFile, SaysWhyAFileCannotBeRead) {
    test::TempDir dir("raylane_read_file_");
    const std::string missing = (dir.path / "missing.ply").string();
    try {
        map_file(missing);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), missing + ": cannot read: No such file or directory");
    }
    try {
        map_file(dir.path.string());
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), dir.path.string() + ": cannot read: Is a directory");
    }
}

}  // namespace
}  // namespace raylane
