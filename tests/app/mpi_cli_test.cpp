// Tests of `raylane render` under mpirun: the image of one process, byte for byte, whatever the
// number of ranks and threads; one error line when a rank cannot load the scene; one line and no
// image when a rank dies, or when rank 0 cannot write the frame. In a build without MPI: one line
// saying so instead of N renders.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "support/cli_run.h"
#include "support/temp_dir.h"

namespace {

using raylane::test::CliRun;
using raylane::test::lines;
using raylane::test::run;
using raylane::test::run_command;
using raylane::test::slurp;
using raylane::test::TempDir;

const std::string scenes = RAYLANE_SOURCE_DIR "/scenes/";

#ifdef RAYLANE_MPIEXEC

/// mpirun with N ranks (more than the cores, and as root where CI runs as root), quiet.
std::string mpirun(int ranks) {
    return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
           "OMPI_MCA_rmaps_base_oversubscribe=1 " RAYLANE_MPIEXEC " -q -n " +
           std::to_string(ranks) + " ";
}

/// The dragon small, the glass bunny (secondary rays: tiles of uneven cost) and three frames
/// of the dragon turntable: 1, 2 and 3 ranks of 1 or 2 threads write the bytes one process does.
TEST(MpiCli, EveryRankCountWritesTheImageOfOneProcess) {
    TempDir dir("raylane_mpi_");
    struct Case {
        std::string args, file;
        int frames;
    };
    const Case cases[] = {
        {scenes + "dragon.json --width 96", "dragon.png", 1},
        {scenes + "fig10_glass_bunny.json --width 40 --spp 4", "bunny.pfm", 1},
        {scenes + "dragon_turntable.json --width 64 --frames 10..12", "turn_%02d.png", 3},
        {"--width 64 --height 48 --aov all", "all.exr", 1},
        {"--width 64 --height 48 --tile 3/5", "part.exr", 1},
    };
    for (const Case& c : cases) {
        auto file = [&](const std::string& who, int frame) {
            std::string name = who + "_" + c.file;
            if (c.frames > 1) name.replace(name.find("%02d"), 4, std::to_string(frame));
            return (dir.path / name).string();
        };
        const CliRun one =
            run("render -q " + c.args + " -o " + (dir.path / ("one_" + c.file)).string());
        ASSERT_EQ(one.code, 0) << one.err;
        for (const auto& [ranks, threads] : {std::pair{1, 2}, {2, 1}, {3, 1}, {2, 2}}) {
            const std::string who = std::to_string(ranks) + "x" + std::to_string(threads);
            const CliRun r = run_command(mpirun(ranks) + RAYLANE_BINARY + " render " + c.args +
                                         " --threads " + std::to_string(threads) + " -o " +
                                         (dir.path / (who + "_" + c.file)).string());
            ASSERT_EQ(r.code, 0) << c.args << ", " << who << ": " << r.err;
            if (ranks > 1) {
                EXPECT_NE(r.out.find(std::to_string(ranks) + " ranks"), std::string::npos) << r.out;
            }
            for (int f = 10; f < 10 + c.frames; ++f) {
                const std::string mine = slurp(file(who, f)), theirs = slurp(file("one", f));
                EXPECT_FALSE(theirs.empty()) << file("one", f);
                EXPECT_TRUE(mine == theirs) << c.args << ", " << who << ", " << file(who, f);
            }
        }
    }
}

/// Rank 1 is given a scene it cannot read: every rank stops, one line names the file and the
/// reason, exit code 2, no image.
TEST(MpiCli, ARankThatCannotLoadTheSceneStopsEveryRank) {
    TempDir dir("raylane_mpi_");
    const std::string bad = (dir.path / "bad.json").string();
    raylane::test::write_file(bad, R"({"camera": 3})");
    const std::string out = (dir.path / "out.png").string();
    const std::string cmd = mpirun(3) + "sh -c 'if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then exec " +
                            RAYLANE_BINARY + " render -q " + bad + " -o " + out + "; else exec " +
                            RAYLANE_BINARY + " render -q -o " + out + "; fi'";
    const CliRun r = run_command(cmd);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(bad + ": $.camera: must be an object"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

/// Runs `command` in the background, kills the rank-`rank` child of mpirun with `signal` once
/// rank 0 has begun rendering (its header is out), and waits: the script's output and status.
CliRun kill_rank_during(const TempDir& dir, const std::string& command, int rank,
                        const std::string& signal) {
    const std::string script = (dir.path / "kill.sh").string();
    const std::string out = (dir.path / "stdout.txt").string();
    raylane::test::write_file(
        script, command + " > " + out +
                    " &\n"
                    "pid=$!\n"
                    "for i in $(seq 300); do\n"
                    "  sleep 0.1\n"
                    "  grep -q '^path ' " +
                    out +
                    " 2>/dev/null || continue\n"
                    "  for p in $(pgrep -P $pid); do\n"
                    "    if tr '\\0' '\\n' < /proc/$p/environ | grep -qx OMPI_COMM_WORLD_RANK=" +
                    std::to_string(rank) +
                    "; then\n"
                    "      sleep 0.5; kill -" +
                    signal + " $p; echo killed rank " + std::to_string(rank) +
                    "; break 2\n"
                    "    fi\n"
                    "  done\n"
                    "done\n"
                    "wait $pid\n");
    CliRun r = run_command("bash " + script);
    std::filesystem::remove(script);
    std::filesystem::remove(out);
    return r;
}

/// A worker killed (SIGKILL, or SIGTERM) in the middle of a frame: the job ends non-zero, rank 0
/// says in one line which rank was lost, on which host, and what it held; no image (or half of
/// one) is left.
TEST(MpiCli, ALostRankEndsTheJobInOneLineAndLeavesNoImage) {
    for (const std::string signal : {"KILL", "TERM"}) {
        TempDir dir("raylane_mpi_");
        const std::string out = (dir.path / "out.png").string();
        const CliRun r = kill_rank_during(dir,
                                          mpirun(3) + RAYLANE_BINARY + " render " + scenes +
                                              "fig10_glass_bunny.json --width 320 --spp 64 "
                                              "--threads 1 -o " +
                                              out,
                                          2, signal);
        EXPECT_NE(r.out.find("killed rank 2"), std::string::npos) << r.out << r.err;
        EXPECT_NE(r.code, 0) << r.out << r.err;
        EXPECT_EQ(lines(r.err), 1u) << signal << ": " << r.err;
        EXPECT_NE(r.err.find("raylane: rank 2 (host "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(") was lost while it held rows "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("no image was written"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
        for (const auto& entry : std::filesystem::directory_iterator(dir.path))
            ADD_FAILURE() << "left behind: " << entry.path();
    }
}

/// Rank 0 cannot write the frame (its folder is gone by then): the workers finish what they
/// hold and end, and rank 0 says why in one line, exit code 1.
TEST(MpiCli, RankZerosOwnFailureEndsTheJobInOneLine) {
    TempDir dir("raylane_mpi_");
    const std::filesystem::path folder = dir.path / "frames";
    std::filesystem::create_directory(folder);
    const std::string out = (folder / "out.png").string();
    const std::string script = (dir.path / "gone.sh").string();
    const std::string header = (dir.path / "stdout.txt").string();
    raylane::test::write_file(script, mpirun(3) + RAYLANE_BINARY + " render " + scenes +
                                          "fig10_glass_bunny.json --width 320 --spp 64 "
                                          "--threads 1 -o " +
                                          out + " > " + header +
                                          " &\n"
                                          "pid=$!\n"
                                          "until grep -q '^path ' " +
                                          header +
                                          " 2>/dev/null; do sleep 0.1; done\n"
                                          "rmdir " +
                                          folder.string() +
                                          "\n"
                                          "wait $pid\n");
    const CliRun r = run_command("bash " + script);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("raylane: " + out + ": cannot open for writing"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("no image was written"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(folder));
}

#else

TEST(MpiCli, WithoutMpiAnMpiLaunchGetsOneLine) {
    const CliRun zero = run_command("OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0 " RAYLANE_BINARY
                                    " render -q -o /tmp/never.png");
    EXPECT_EQ(zero.code, 2);
    EXPECT_EQ(lines(zero.err), 1u) << zero.err;
    EXPECT_NE(zero.err.find("built without MPI"), std::string::npos) << zero.err;
    // the other ranks meet the same error and leave the line to rank 0
    const CliRun one = run_command("OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=1 " RAYLANE_BINARY
                                   " render -q -o /tmp/never.png");
    EXPECT_EQ(one.code, 2);
    EXPECT_EQ(one.err, "");
    EXPECT_FALSE(std::filesystem::exists("/tmp/never.png"));
}

#endif

}  // namespace
