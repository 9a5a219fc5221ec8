// Tests of the `raylane` command line: exit codes, one-line errors, outputs.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/isa.h"
#include "support/cli_run.h"
#include "support/gzip.h"
#include "support/temp_dir.h"

namespace {

using raylane::test::CliRun;
using raylane::test::lines;
using raylane::test::run;
using raylane::test::run_command;
using namespace raylane;  // Isa, isa_name, runnable_isas (core/isa.h)

std::string temp_file(const std::string& name, const std::string& text) {
    const std::string path = (std::filesystem::temp_directory_path() / name).string();
    std::ofstream(path) << text;
    return path;
}

TEST(Cli, HelpWorksForEveryCommand) {
    for (const char* cmd :
         {"--help", "render --help", "info --help", "compare --help", "scene --help"}) {
        const CliRun r = run(cmd);
        EXPECT_EQ(r.code, 0) << cmd;
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
    }
}

TEST(Cli, VersionNamesTheInstructionSetsCompiledRunnableAndInUse) {
    const CliRun r = run("--version");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("raylane ", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("sse4.2 avx2 avx512 (compiled)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" (this CPU), "), std::string::npos) << r.out;
    const std::string widest = isa_name(runnable_isas().back());
    EXPECT_NE(
        r.out.find(widest + " in use (W = " + std::to_string(isa_width(runnable_isas().back()))),
        std::string::npos)
        << r.out;
    EXPECT_EQ(lines(r.out), 2u) << r.out;
}

TEST(Cli, IsaForcesEveryRunnableSetAndTheRenderSaysWhichItUsed) {
    for (Isa isa : runnable_isas()) {
        const std::string name = isa_name(isa);
        const std::string png =
            (std::filesystem::temp_directory_path() / "raylane_cli_isa.png").string();
        const CliRun r = run("render --width 32 --isa " + name + " -o " + png);
        EXPECT_EQ(r.code, 0) << r.err;
        const std::string want =
            "path       packet (" + name + ", W = " + std::to_string(isa_width(isa)) + ")";
        EXPECT_NE(r.out.find(want), std::string::npos) << r.out;
        const CliRun env = run_command("RAYLANE_ISA=" + name + " " RAYLANE_BINARY " info");
        EXPECT_EQ(env.code, 0) << env.err;
        EXPECT_NE(env.out.find(", " + name + " in use"), std::string::npos) << env.out;
    }
}

TEST(Cli, UnknownOrUnrunnableIsaIsOneLineNamingTheRunnableSets) {
    for (const std::string args : {"render --isa avx9", "info --isa neon"}) {
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find("--isa: unknown instruction set"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("this machine runs: " + runnable_isa_names()), std::string::npos)
            << r.err;
    }
    const CliRun env = run_command("RAYLANE_ISA=mmx " RAYLANE_BINARY " info");
    EXPECT_EQ(env.code, 2);
    EXPECT_EQ(lines(env.err), 1u) << env.err;
    EXPECT_NE(env.err.find("RAYLANE_ISA: unknown instruction set 'mmx'"), std::string::npos)
        << env.err;
    for (Isa isa : all_isas) {
        if (cpu_runs(isa)) continue;  // on a CPU without AVX-512: the set it cannot run
        const CliRun r = run(std::string("info --isa ") + isa_name(isa));
        EXPECT_EQ(r.code, 2);
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find("this CPU does not run"), std::string::npos) << r.err;
    }
}

TEST(Cli, IntegerOptionsSayWhetherTheValueIsNotWholeOrOutOfRange) {
    const std::pair<std::string, std::string> cases[] = {
        {"render --spp 4.5", "--spp: must be a whole number from 1 to 1048576, not '4.5'"},
        {"render --spp 0", "--spp: must be from 1 to 1048576, not 0"},
        {"render --width -3", "--width: must be a whole number from 1 to"},
        {"compare --repeats 1e3", "--repeats: must be a whole number from 1 to 100, not '1e3'"},
        {"render --threads 2000", "--threads: must be from 1 to 1024, not 2000"},
    };
    for (const auto& [args, text] : cases) {
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
        EXPECT_NE(r.err.find(text), std::string::npos) << args << ": " << r.err;
    }
}

TEST(Cli, AnUnknownOptionIsNamedWithTheNearestKnownOne) {
    const std::pair<std::string, std::string> cases[] = {
        {"render --sp 4 scene.json", "render: unknown option '--sp' (did you mean --spp?"},
        {"compare --tolerence=1",
         "compare: unknown option '--tolerence' (did you mean --tolerance?"},
        {"render --xyzzy", "render: unknown option '--xyzzy' (see raylane render --help)"},
    };
    for (const auto& [args, text] : cases) {
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
        EXPECT_NE(r.err.find(text), std::string::npos) << args << ": " << r.err;
    }
    // a known option written --name=value is not unknown
    EXPECT_EQ(run("info --bvh=sah").code, 0);
}

TEST(Cli, BadCommandLineGivesOneLineAndExitCodeTwo) {
    for (const char* args : {"render --spp 0",
                             "render --aov shiny",
                             "render --path fast",
                             "frobnicate",
                             "render /no/such/scene.json",
                             "render --width -3",
                             "render --bvh octree",
                             "info --bvh",
                             "compare --tolerance nan",
                             "compare --tolerance -1",
                             "compare --tolerance inf",
                             "compare --tolerance 1e-3x",
                             "compare --id-allowance -1",
                             "compare --id-allowance 1.5",
                             "compare --id-allowance 010x",
                             "compare --id-allowance 99999999999999999999",
                             "render -o image.jpg",
                             "render -o /no/such/dir/image.png",
                             "render -o /",
                             "render --width 32768 --height 8193",
                             "compare --width 32768",
                             "render --threads 5000",
                             "render --threads 3x"}) {
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
    }
    EXPECT_NE(run("frobnicate").err.find("unknown command 'frobnicate'"), std::string::npos);
    // an output path that is a directory is refused before the render, not after it
    const auto dir = std::filesystem::temp_directory_path() / "raylane_cli_dir.png";
    std::filesystem::create_directories(dir);
    const CliRun r = run("render -o " + dir.string());
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
    std::filesystem::remove_all(dir);
}

TEST(Cli, MalformedSceneNamesFileAndPath) {
    const std::string scene = temp_file(
        "raylane_bad_scene.json",
        R"({"camera": {"position": [0,0,0], "look_at": [0,0,1], "fov_deg": 60, "resolution": [8,8]},
            "objects": [{"shape": "sphere", "center": [0,0,3], "radius": 1, "material": "gold"}]})");
    const CliRun r = run("render " + scene + " -o " + temp_file("raylane_bad_scene.png", ""));
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("raylane_bad_scene.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("$.objects[0].material"), std::string::npos) << r.err;
}

/// A scene file `name` of one mesh object read from `obj`, seen by an 8x8 camera.
std::string mesh_scene(const std::string& name, const std::string& obj) {
    return temp_file(
        name,
        R"({"camera": {"position": [0,0,-2], "look_at": [0,0,0], "fov_deg": 60, "resolution": [8,8]},
            "objects": [{"shape": "mesh", "file": ")" +
            obj + R"("}]})");
}

TEST(Cli, MalformedModelNamesFileAndLine) {
    const std::string obj =
        temp_file("raylane_bad_model.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    const std::string scene = mesh_scene("raylane_bad_model_scene.json", obj);
    const CliRun r = run("info " + scene);
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("raylane_bad_model.obj:4"), std::string::npos) << r.err;
}

TEST(Cli, InfoReadsAGzipCompressedModel) {
    const std::string obj =
        temp_file("raylane_info_gzip.obj.gz",
                  raylane::test::gzip("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nv 1 1 0\r\nusemtl\r\n"
                                      "f 1/ 2/ 3/\r\nf 2// 4// 3//\r\n"));
    const std::string scene = mesh_scene("raylane_info_gzip_scene.json", obj);
    const CliRun r = run("info " + scene);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("raylane_info_gzip.obj.gz: 2 triangles\n"), std::string::npos) << r.out;
}

TEST(Cli, ModelFilesThatAreNoTextModelsGiveOneLine) {
    struct Case {
        const char* name;
        std::string bytes;
        const char* reason;
    };
    const Case cases[] = {
        {"raylane_form_empty.obj", "", ": is empty"},
        {"raylane_form_utf16.obj",
         std::string("\xFF\xFEv\0 \0"
                     "0\0",
                     8),
         ": is UTF-16 text; save it as UTF-8 or ASCII"},
        {"raylane_form_binary.obj", std::string("v 0\0\1\2", 6),
         ": is a binary file, not a text OBJ (byte 3 is 0x00)"},
        {"raylane_form_cut.ply",
         "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
         "end_header\n0 0 0\n1 0 0\n",
         ":11: ends after 2 of 4 vertices"},
    };
    for (const Case& c : cases) {
        const std::string model = temp_file(c.name, c.bytes);
        const CliRun r = run("info " + mesh_scene(std::string(c.name) + ".json", model));
        EXPECT_EQ(r.code, 2) << c.name;
        EXPECT_EQ(lines(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find(model + c.reason + "\n"), std::string::npos) << r.err;
    }
}

TEST(Cli, InfoPrintsTheMeshBuildsPhasesForTheMedianSplitOnly) {
    const std::string obj = temp_file("raylane_info_phases.obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    const std::string scene = mesh_scene("raylane_info_phases_scene.json", obj);
    const CliRun median = run("info " + scene);
    EXPECT_EQ(median.code, 0) << median.err;
    const size_t line = median.out.find("mesh builds: centroids ");
    ASSERT_NE(line, std::string::npos) << median.out;
    const std::string phases = median.out.substr(line, median.out.find('\n', line) - line);
    for (const char* key : {", sorts ", ", splits ", ", vertices ", ", boxes ",
                            "; wide trees collapsed and leaves packed in "})
        EXPECT_NE(phases.find(key), std::string::npos) << key << "\n" << phases;
    const CliRun sah = run("info --bvh sah " + scene);
    EXPECT_EQ(sah.code, 0) << sah.err;
    EXPECT_EQ(sah.out.find("mesh builds"), std::string::npos) << sah.out;
    const CliRun builtin = run("info");  // no mesh
    EXPECT_EQ(builtin.code, 0) << builtin.err;
    EXPECT_EQ(builtin.out.find("mesh builds"), std::string::npos) << builtin.out;
}

TEST(Cli, InfoPrintsBothTreesOfEveryMesh) {
    const std::string obj = temp_file("raylane_info_trees.obj",
                                      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 2 1\n"
                                      "f 1 2 3\nf 2 4 3\nf 3 4 5\n");
    const std::string scene = mesh_scene("raylane_info_trees_scene.json", obj);
    for (const char* bvh : {"", "--bvh sah "}) {
        const CliRun r = run(std::string("info ") + bvh + scene);
        EXPECT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.out.find("binary tree (scalar path):"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("bytes per triangle (nodes, ids, vertices)"), std::string::npos);
        const size_t wide = r.out.find("wide tree (packet path): ");
        ASSERT_NE(wide, std::string::npos) << r.out;
        const std::string line = r.out.substr(wide, r.out.find('\n', wide) - wide);
        EXPECT_NE(line.find(" nodes, "), std::string::npos) << line;
        EXPECT_NE(line.find(" children per node, "), std::string::npos) << line;
        EXPECT_NE(line.find(" triangles per leaf"), std::string::npos) << line;
        EXPECT_NE(r.out.find("bytes per triangle (wide nodes, leaf triangles, ids)"),
                  std::string::npos);
    }
}

TEST(Cli, RenderWritesTheImageAndReportsTiming) {
    const std::string png =
        (std::filesystem::temp_directory_path() / "raylane_cli_builtin.png").string();
    std::filesystem::remove(png);
    const CliRun r = run("render --width 64 -o " + png);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(png));
    EXPECT_GT(std::filesystem::file_size(png), 100u);
    for (const char* key : {"resolution", "rays", "load", "build", "render", "Mrays/s"})
        EXPECT_NE(r.out.find(key), std::string::npos) << key;
    EXPECT_FALSE(std::filesystem::exists(png + ".partial"));
}

/// -q: nothing but warnings and errors, for a still, frames, parts and a scene with a warning.
TEST(Cli, QuietPrintsOnlyWarningsAndErrors) {
    const test::TempDir dir("raylane_cli_quiet_");
    const std::string still = (dir.path / "q.png").string();
    CliRun r = run("render --width 32 -q -o " + still);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(still));
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
    r = run("render " RAYLANE_SOURCE_DIR
            "/scenes/dragon_turntable.json --width 24 --frames 0..1 "
            "-q -o " +
            (dir.path / "f_%02d.png").string());
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
    // a scene without lights still says so
    test::write_file(dir.path / "dark.json",
                     R"({"version": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0],
                         "fov_deg": 40, "resolution": [16, 16]},
                         "materials": {"m": {"c_d": [1, 1, 1]}},
                         "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                                      "material": "m"}]})");
    r = run("render " + (dir.path / "dark.json").string() + " -q -o " + still);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("warning"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("resolution"), std::string::npos) << r.out;
}

/// A part of a frame may be black (all sky) while the frame is not: only the whole frame warns
/// that every pixel is black.
TEST(Cli, OnlyTheWholeFrameWarnsThatEveryPixelIsBlack) {
    const test::TempDir dir("raylane_cli_black_");
    test::write_file(dir.path / "night.json",
                     R"({"version": 1, "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0],
                         "fov_deg": 40, "resolution": [32, 32]},
                         "materials": {"m": {"c_d": [0, 0, 0]}},
                         "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                                      "material": "m"}],
                         "lights": [{"type": "point", "position": [0, 5, -5]}]})");
    const std::string scene = (dir.path / "night.json").string();
    const CliRun whole = run("render " + scene + " -o " + (dir.path / "n.png").string());
    EXPECT_EQ(whole.code, 0) << whole.err;
    EXPECT_NE(whole.out.find("every pixel is black"), std::string::npos) << whole.out;
    for (const char* part : {"--tile 1/4", "--crop 0 0 8 8"}) {
        const CliRun r =
            run("render " + scene + " " + part + " -o " + (dir.path / "p.exr").string());
        EXPECT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(r.out.find("is black"), std::string::npos) << part << ": " << r.out;
    }
}

TEST(Cli, MoreThreadsThanCoresRunOnTheCoresWithoutWarnings) {
    const std::string png =
        (std::filesystem::temp_directory_path() / "raylane_cli_threads.png").string();
    const CliRun r = run("render --width 16 -q --threads 1000 -o " + png);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err, "");  // oneTBB's two lines of warning, before
    EXPECT_EQ(r.out.find("1000 threads"), std::string::npos) << r.out;
    std::filesystem::remove(png);
}

/// Reads the floats of a PFM written by raylane (little-endian, 3 channels).
std::vector<float> read_pfm_values(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::string magic;
    int w = 0, h = 0;
    double scale = 0;
    f >> magic >> w >> h >> scale;
    f.get();  // the single whitespace before the data
    std::vector<float> v(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
    f.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * 4));
    if (!f || magic != "PF") v.clear();
    return v;
}

TEST(Cli, StrictRenderFailsOnInfiniteSamplesButWritesACleanImage) {
    // c_d * k_d * intensity = 1e90 overflows float: every lit sample is infinite
    const std::string scene = temp_file("raylane_cli_inf.json", R"({
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 60,
                   "resolution": [24, 24], "spp": 2},
        "materials": {"hot": {"c_d": [1e30, 1, 1], "k_d": 1e30}},
        "objects": [{"shape": "sphere", "center": [0, 0, 5], "radius": 2, "material": "hot"}],
        "lights": [{"type": "point", "position": [0, 5, 0], "intensity": 1e30}]})");
    const std::string pfm =
        (std::filesystem::temp_directory_path() / "raylane_cli_inf.pfm").string();
    for (const char* path : {"packet", "scalar"}) {
        std::filesystem::remove(pfm);
        const CliRun lax =
            run("render " + scene + " -q --path " + std::string(path) + " -o " + pfm);
        EXPECT_EQ(lax.code, 0) << lax.err;
        EXPECT_NE(lax.out.find("infinite samples were left out"), std::string::npos) << lax.out;

        std::filesystem::remove(pfm);
        const CliRun strict =
            run("render " + scene + " -q --strict --path " + std::string(path) + " -o " + pfm);
        EXPECT_EQ(strict.code, 3) << path;
        EXPECT_EQ(lines(strict.err), 1u) << strict.err;
        EXPECT_NE(strict.err.find("infinite samples (--strict)"), std::string::npos) << strict.err;
        const std::vector<float> values = read_pfm_values(pfm);
        ASSERT_EQ(values.size(), 24u * 24u * 3u) << path;
        for (float v : values) ASSERT_TRUE(std::isfinite(v)) << path;
    }
    // a clean scene passes --strict
    EXPECT_EQ(run("render --width 32 -q --strict -o " + pfm).code, 0);
}

/// Waits up to 30 s for the raylane process `pid` (the name in /proc/PID/status: not the forked
/// test before its exec) to catch signal `sig` (bit sig - 1 of SigCgt there); false if it never
/// does or exits first (a zombie).
bool catches_signal(pid_t pid, int sig) {
    const std::string status = "/proc/" + std::to_string(pid) + "/status";
    for (int tries = 0; tries < 3000; ++tries) {
        std::ifstream f(status);
        bool raylane = false, catches = false, zombie = false;
        for (std::string line; std::getline(f, line);) {
            if (line.rfind("Name:", 0) == 0) raylane = line.find("raylane") != std::string::npos;
            if (line.rfind("State:", 0) == 0) zombie = line.find('Z') != std::string::npos;
            if (line.rfind("SigCgt:", 0) == 0)
                catches = (std::stoull(line.substr(7), nullptr, 16) >> (sig - 1) & 1u) != 0;
        }
        if (zombie) return false;
        if (raylane && catches) return true;
        usleep(10 * 1000);
    }
    return false;
}

TEST(Cli, InterruptedRenderWritesNothingAndLeavesTheOldImage) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("raylane_cli_int_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const std::string png = (dir / "image.png").string();
    std::ofstream(png) << "the previous image";
    for (int sig : {SIGINT, SIGTERM}) {
        const pid_t pid = fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {  // a render of many seconds
            execl(RAYLANE_BINARY, RAYLANE_BINARY, "render", "--width", "1600", "--spp", "4096",
                  "-q", "-o", png.c_str(), static_cast<char*>(nullptr));
            _exit(127);
        }
        // into the render: once the child catches the signal (its handlers are installed at
        // the start of main, which a loaded machine may reach late), and a little more
        if (!catches_signal(pid, sig)) {
            kill(pid, SIGKILL);  // nothing left running or writing
            int status = 0;
            waitpid(pid, &status, 0);
            FAIL() << "the render exited or never installed its handler, status " << status;
        }
        usleep(300 * 1000);  // most likely mid-render; any time after the handler stops it
        kill(pid, sig);
        int status = 0;
        ASSERT_EQ(waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
        EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
        std::ifstream f(png);
        EXPECT_EQ(std::string(std::istreambuf_iterator<char>(f), {}), "the previous image");
        size_t files = 0;  // no temporary left beside it
        for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
        EXPECT_EQ(files, 1u);
    }
    std::filesystem::remove_all(dir);
}

TEST(Cli, InfoPrintsBvhStatistics) {
    const CliRun r = run("info");
    EXPECT_EQ(r.code, 0) << r.err;
    for (const char* key :
         {"objects", "triangles", "nodes", "leaves", "SAH cost", "memory", "build"})
        EXPECT_NE(r.out.find(key), std::string::npos) << key;
}

TEST(Cli, CompareAgreesOnTheBuiltinScene) {
    const CliRun r = run("compare --width 64");
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("agree"), std::string::npos);
    EXPECT_NE(r.out.find("PSNR"), std::string::npos);
}

TEST(Cli, CompareTimesLikeReportAndNamesTheBvh) {
    const CliRun r = run("compare --width 64 -q");
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("bvh          median split\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("timing       median of 3 runs per path, after an untimed warm-up\n"),
              std::string::npos)
        << r.out;
    const CliRun one = run("compare --width 64 -q --bvh sah --repeats 1");
    EXPECT_EQ(one.code, 0) << one.out << one.err;
    EXPECT_NE(one.out.find("bvh          binned SAH\n"), std::string::npos) << one.out;
    EXPECT_NE(one.out.find("median of 1 run per path"), std::string::npos) << one.out;
    EXPECT_EQ(run("compare --repeats 0").code, 2);
}

TEST(Cli, CompareReadsItsAllowanceInDecimal) {
    // CLI11 alone reads "010" as octal 8
    const CliRun r = run("compare --width 16 --id-allowance 010 --tolerance 0.5");
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("tolerance 0.5, id allowance 10)"), std::string::npos) << r.out;
}

TEST(Cli, SahBuildIsAnOptionOfInfoRenderAndCompare) {
    const CliRun info = run("info --bvh sah");
    EXPECT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("binned SAH"), std::string::npos) << info.out;
    EXPECT_NE(run("info").out.find("median split"), std::string::npos);
    const CliRun compare = run("compare --width 64 --bvh sah");
    EXPECT_EQ(compare.code, 0) << compare.out << compare.err;
    EXPECT_NE(compare.out.find("agree"), std::string::npos);
    const std::string png =
        (std::filesystem::temp_directory_path() / "raylane_cli_sah.png").string();
    const CliRun render = run("render --width 48 --bvh sah -o " + png);
    EXPECT_EQ(render.code, 0) << render.err;
    EXPECT_NE(render.out.find("bvh        sah"), std::string::npos) << render.out;
    std::filesystem::remove(png);
}

}  // namespace
