// Running the raylane binary from a test: its exit code and what it printed.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace raylane::test {

struct CliRun {
    int code = -1;
    std::string out, err;
};

/// The whole text of a file ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream f(path);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

/// Runs a shell command, capturing stdout and stderr.
inline CliRun run_command(const std::string& command) {
    // per test and process: ctest runs the tests of a program in parallel
    const std::filesystem::path dir = std::filesystem::temp_directory_path();
    const std::string tag =
        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
        std::to_string(getpid());
    const std::filesystem::path out = dir / ("raylane_cli_out_" + tag + ".txt");
    const std::filesystem::path err = dir / ("raylane_cli_err_" + tag + ".txt");
    const std::string cmd = command + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

/// Runs the raylane binary with `args` (a shell fragment), capturing stdout and stderr.
inline CliRun run(const std::string& args) { return run_command(RAYLANE_BINARY " " + args); }

/// The number of lines of s (its newlines).
inline size_t lines(const std::string& s) {
    size_t n = 0;
    for (char c : s) n += c == '\n';
    return n;
}

}  // namespace raylane::test
