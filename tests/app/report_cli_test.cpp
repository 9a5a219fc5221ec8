// Tests of `raylane report` (app/report_command.cpp) through the binary: one-line errors, the
// cached reference, the analytic reference. report/report_*.cpp: tests/report/report_*_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli_run.h"
#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;
using raylane::test::CliRun;
using raylane::test::lines;
using raylane::test::run;
using raylane::test::slurp;
using raylane::test::write_file;

fs::path temp_dir() { return raylane::test::fresh_temp_dir("raylane_report_cli_"); }

TEST(ReportCli, BadArgumentsExitTwoWithOneLine) {
    const std::string scene = RAYLANE_SOURCE_DIR "/scenes/builtin.json";
    for (const std::string& args :
         {std::string("report"), std::string("report /no/such/scene.json"),
          "report " + scene + " --spp-list 0", "report " + scene + " --spp-list 1,x",
          "report " + scene + " --paths fast", "report " + scene + " --repeats 0",
          "report " + scene + " --reference-spp 2", "report " + scene + " --width -4",
          "report " + scene + " --out-dir /proc/raylane"}) {
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(lines(r.err), 1u) << args << ": " << r.err;
        EXPECT_TRUE(r.out.empty()) << args;
    }
}

TEST(ReportCli, ReusesTheCachedReferenceUntilTheSceneChanges) {
    const fs::path dir = temp_dir();
    const std::string text = slurp(RAYLANE_SOURCE_DIR "/scenes/builtin.json");
    write_file(dir / "scene.json", text);
    const std::string args = "report " + (dir / "scene.json").string() + " --out-dir " +
                             (dir / "out").string() +
                             " --width 32 --height 24 --reference-spp 16 --spp-list 1,4 "
                             "--repeats 1 --threads 1 -q";
    const CliRun first = run(args);
    ASSERT_EQ(first.code, 0) << first.out << first.err;
    EXPECT_NE(first.out.find("saved to"), std::string::npos) << first.out;
    for (const char* key : {"RMSE", "relMSE", "Var(ref)", "speed-up", "against time"})
        EXPECT_NE(first.out.find(key), std::string::npos) << key;
    const CliRun second = run(args);
    ASSERT_EQ(second.code, 0) << second.err;
    EXPECT_NE(second.out.find("reused from"), std::string::npos) << second.out;
    // CSV: a header and one row per (path, samples); the SVG is there
    const std::string csv = slurp(dir / "out" / "scene.csv");
    EXPECT_EQ(lines(csv), 1u + 2u * 2u);
    EXPECT_EQ(csv.rfind("scene,path,knob,samples", 0), 0u);
    EXPECT_NE(slurp(dir / "out" / "scene.svg").find("<polyline"), std::string::npos);
    // a changed scene renders a new reference next to the old one
    write_file(dir / "scene.json", text + "\n");
    const CliRun third = run(args);
    ASSERT_EQ(third.code, 0) << third.err;
    EXPECT_NE(third.out.find("saved to"), std::string::npos) << third.out;
    size_t references = 0;
    for (const auto& e : fs::directory_iterator(dir / "out"))
        references += e.path().extension() == ".pfm";
    EXPECT_EQ(references, 2u);
    fs::remove_all(dir);
}

TEST(ReportCli, QuotesTheSceneNameInTheCsv) {
    const fs::path dir = temp_dir();
    write_file(dir / "a,b\"c.json", slurp(RAYLANE_SOURCE_DIR "/scenes/builtin.json"));
    const CliRun r =
        run("report '" + (dir / "a,b\"c.json").string() + "' --out-dir " + (dir / "out").string() +
            " --width 16 --height 12 --reference-spp 16 --spp-list 1 --repeats 1 "
            "--paths packet --threads 1 -q");
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const std::string csv = slurp(dir / "out" / "a,b\"c.csv");
    const size_t row = csv.find('\n') + 1;
    EXPECT_EQ(csv.compare(row, 16, "\"a,b\"\"c\",packet,"), 0) << csv;
    fs::remove_all(dir);
}

TEST(ReportCli, UsesTheAnalyticReferenceWhenTheSceneHasOne) {
    const fs::path dir = temp_dir();
    write_file(dir / "lit_sphere.json",
               R"({"camera": {"position": [0, 0, -4], "look_at": [0, 0, 0], "fov_deg": 40},
              "materials": {"m": {"c_d": [0.8, 0.6, 0.4], "k_d": 0.7, "k_s": 0.3}},
              "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}],
              "lights": [{"type": "directional", "direction": [1, 1, -1], "intensity": 0.8}]})");
    const CliRun r = run("report " + (dir / "lit_sphere.json").string() + " --out-dir " +
                         (dir / "out").string() +
                         " --width 32 --height 24 --spp-list 1,4,16 --repeats 1 --paths packet -q");
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("analytic (lit sphere"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("Var(ref)"), std::string::npos);
    size_t references = 0;
    for (const auto& e : fs::directory_iterator(dir / "out"))
        references += e.path().extension() == ".pfm";
    EXPECT_EQ(references, 0u);  // nothing to cache
    fs::remove_all(dir);
}

}  // namespace
