// Tests of the instruction sets through the command line: every scene in scenes/ renders to the
// same PNG bytes under every set this CPU runs, and to the same 32-bit floats of colour, normal,
// depth and BVH cost on every scene but two (docs/building.md, "Instruction sets"), parts rendered
// under different sets assemble to the whole frame, and an mpirun whose ranks use different sets
// writes the image of one process.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/isa.h"
#include "support/cli_run.h"
#include "support/temp_dir.h"

namespace {

using raylane::Isa;
using raylane::isa_name;
using raylane::runnable_isas;
using raylane::test::CliRun;
using raylane::test::run;
using raylane::test::run_command;
using raylane::test::slurp;
using raylane::test::TempDir;

/// The scenes, small: a model scene's models and textures come from the shared folder.
std::vector<std::filesystem::path> scene_files() {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(RAYLANE_SOURCE_DIR "/scenes"))
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(IsaCli, EverySceneIsTheSameImageUnderEverySet) {
    const std::vector<Isa> sets = runnable_isas();
    ASSERT_FALSE(sets.empty());
    if (sets.size() == 1) GTEST_SKIP() << "this CPU runs one set: " << isa_name(sets[0]);
    TempDir dir("raylane_isa_");
    const std::vector<std::filesystem::path> scenes = scene_files();
    ASSERT_GE(scenes.size(), 30u);
    for (const std::filesystem::path& scene : scenes) {
        for (const std::string format : {".png", ".exr"}) {
            std::string first;
            for (Isa isa : sets) {
                const std::string out = (dir.path / (std::string(isa_name(isa)) + format)).string();
                const std::string aov = format == ".exr" ? " --aov all --exr-float" : "";
                const CliRun r =
                    run("render -q " + scene.string() + " --width 48 --spp 2" + " --frames 0" +
                        aov + " --isa " + isa_name(isa) + " -o " + out);
                ASSERT_EQ(r.code, 0) << scene << " " << isa_name(isa) << ": " << r.err;
                const std::string bytes = slurp(out);
                ASSERT_GT(bytes.size(), 100u) << out;
                if (first.empty())
                    first = bytes;
                else
                    EXPECT_TRUE(bytes == first)
                        << scene.filename() << format << ": " << isa_name(isa) << " differs from "
                        << isa_name(sets[0]);
            }
        }
    }
}

TEST(IsaCli, PartsRenderedUnderDifferentSetsAssembleToTheWholeFrame) {
    const std::vector<Isa> sets = runnable_isas();
    TempDir dir("raylane_isa_parts_");
    const std::string args =
        "render -q " RAYLANE_SOURCE_DIR "/scenes/fig10_glass_bunny.json --width 64 --spp 2";
    const std::string whole = (dir.path / "whole.pfm").string();
    ASSERT_EQ(run(args + " -o " + whole).code, 0);
    const int n = 4;
    std::string parts;
    for (int i = 0; i < n; ++i) {
        const std::string part = (dir.path / ("part" + std::to_string(i) + ".exr")).string();
        const Isa isa = sets[size_t(i) % sets.size()];
        const CliRun r = run(args + " --isa " + isa_name(isa) + " --tile " + std::to_string(i) +
                             "/" + std::to_string(n) + " -o " + part);
        ASSERT_EQ(r.code, 0) << r.err;
        parts += " " + part;
    }
    const std::string joined = (dir.path / "joined.pfm").string();
    const CliRun a = run("assemble" + parts + " -o " + joined);
    ASSERT_EQ(a.code, 0) << a.err;
    EXPECT_TRUE(slurp(joined) == slurp(whole));
}

#ifdef RAYLANE_MPIEXEC
TEST(IsaCli, MpiRanksOnDifferentSetsWriteTheImageOfOneProcess) {
    const std::vector<Isa> sets = runnable_isas();
    TempDir dir("raylane_isa_mpi_");
    const std::string args =
        " render -q " RAYLANE_SOURCE_DIR "/scenes/fig10_glass_bunny.json --width 64 --spp 2";
    const std::string one = (dir.path / "one.png").string();
    ASSERT_EQ(run(args + " -o " + one).code, 0);
    // mpirun -n 1 raylane render ... --isa avx2 : -n 1 raylane render ... --isa sse4.2
    std::string command =
        "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
        "OMPI_MCA_rmaps_base_oversubscribe=1 " RAYLANE_MPIEXEC " -q";
    const std::string mixed = (dir.path / "mixed.png").string();
    for (size_t k = 0; k < 2; ++k) {
        const Isa isa = sets[sets.size() - 1 - k % sets.size()];
        command += std::string(k ? " :" : "") + " -n 1 " RAYLANE_BINARY + args +
                   " --threads 1 --isa " + isa_name(isa) + " -o " + mixed;
    }
    const CliRun r = run_command(command);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(mixed) == slurp(one));
}
#endif

}  // namespace
