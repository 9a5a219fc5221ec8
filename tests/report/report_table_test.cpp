// Tests of report/report_table.cpp: the table of a made-up sweep, its checks, the fits and the
// speed-up summary, printed to a temporary file.
#include "report/report_table.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "support/sweep_points.h"

namespace raylane {
namespace {

using test::made_up_params;
using test::made_up_sweep;

/// What `print` writes to a FILE*.
std::string printed(const std::function<void(std::FILE*)>& print) {
    std::FILE* f = std::tmpfile();
    if (!f) return "(no temporary file)";
    print(f);
    std::rewind(f);
    std::string text;
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
    std::fclose(f);
    return text;
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t i = text.find(what); i != std::string::npos; i = text.find(what, i + 1)) ++n;
    return n;
}

TEST(SweepTable, ARowPerPointWithTheSpeedUpOnPacketRows) {
    const SweepParams sweep = made_up_params();
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const Speedups speedups = speedups_of(points, sweep);
    bool ok = false;
    const std::string text =
        printed([&](std::FILE* f) { ok = print_sweep_table(f, points, sweep, speedups); });
    EXPECT_TRUE(ok) << text;
    EXPECT_EQ(text.rfind("metrics RMSE; relMSE eps=1e-02; SMAPE in [0,1] eps=1e-03", 0), 0u)
        << text;
    EXPECT_NE(text.find("median of 2 interleaved runs"), std::string::npos) << text;
    EXPECT_EQ(count(text, "\npacket  spp "), 3u) << text;
    EXPECT_EQ(count(text, "\nscalar  spp "), 3u) << text;
    EXPECT_EQ(count(text, "2.00x\n"), 3u) << text;  // the packet rows only
    EXPECT_NE(text.find("packet  spp          4    0.4000"), std::string::npos) << text;
}

TEST(SweepTable, NanSamplesAndDifferentRayCountsFailTheChecks) {
    const SweepParams sweep = made_up_params();
    std::vector<SweepPoint> points = made_up_sweep(sweep);
    const Speedups speedups = speedups_of(points, sweep);
    const auto ok_of = [&] {
        bool ok = true;
        const std::string text =
            printed([&](std::FILE* f) { ok = print_sweep_table(f, points, sweep, speedups); });
        return std::make_pair(ok, text);
    };
    EXPECT_TRUE(ok_of().first);
    points[1].runs[0].nan_samples = 1;
    EXPECT_FALSE(ok_of().first);
    points[1].runs[0].nan_samples = 0;
    points[4].rays_match = false;
    const auto [ok, text] = ok_of();
    EXPECT_FALSE(ok);
    EXPECT_NE(text.find("error   scalar spp 2: ray counts differ from packet at the same seed"),
              std::string::npos)
        << text;
}

TEST(SweepFits, ASlopePerCurveAgainstTimeAndSamples) {
    const SweepParams sweep = made_up_params({SweepKnob::spp, SweepKnob::glossy});
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const std::string text = printed([&](std::FILE* f) { print_fits(f, points, sweep); });
    // RMSE 0.4 / sqrt(samples), time proportional to samples: b = -1/2 against both, R² = 1
    EXPECT_EQ(count(text,
                    "against time: b = -0.500 R2 = 1.0000   against samples: b = -0.500 "
                    "R2 = 1.0000"),
              4u)
        << text;
    EXPECT_NE(text.find("  packet glossy against time"), std::string::npos) << text;
    EXPECT_NE(text.find("  scalar spp    against time"), std::string::npos) << text;
}

TEST(SpeedupSummary, TheMediansOfTheRatios) {
    const SweepParams sweep = made_up_params();
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const Speedups speedups = speedups_of(points, sweep);
    const std::string text =
        printed([&](std::FILE* f) { print_speedup_summary(f, points, speedups); });
    EXPECT_NE(text.find("time scalar/packet: median 2.00x (range 2.00-2.00, 3 points)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("equal RMSE     speed-up packet over scalar (log-log interpolation): "
                        "median 2.00x"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("-> 2.00x"), std::string::npos) << text;  // time to an RMSE, from the fits
    EXPECT_NE(text.find("packet over scalar at equal samples: median 2.00x"), std::string::npos)
        << text;
}

}  // namespace
}  // namespace raylane
