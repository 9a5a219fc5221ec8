// Tests of report/report_csv.cpp: the header, a row per point with as many fields, the speed-up
// on packet rows only, the quoted scene name and the reference's columns.
#include "report/report_csv.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "support/sweep_points.h"

namespace raylane {
namespace {

using test::made_up_params;
using test::made_up_sweep;

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

/// The fields of a row without quoted commas.
std::vector<std::string> fields_of(const std::string& line) {
    std::vector<std::string> fields;
    std::istringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    return fields;
}

Reference converged(int spp, double variance) {
    Reference ref;
    ref.kind = "converged";
    ref.spp = spp;
    ref.variance = variance;
    return ref;
}

TEST(SweepCsv, AHeaderAndARowPerPointWithTheSameFields) {
    const SweepParams sweep = made_up_params({SweepKnob::spp, SweepKnob::light});
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const std::string csv = sweep_csv(SweepLabel{"bunny", 32, 24, 2}, sweep, converged(400, 1e-4),
                                      points, speedups_of(points, sweep));
    ASSERT_FALSE(csv.empty());
    EXPECT_EQ(csv.back(), '\n');
    const std::vector<std::string> lines = lines_of(csv);
    ASSERT_EQ(lines.size(), 1 + points.size());
    const std::vector<std::string> header = fields_of(lines[0]);
    EXPECT_EQ(header.size(), 34u);
    EXPECT_EQ(header[0], "scene");
    EXPECT_EQ(header[30], "speedup_over_scalar");
    for (size_t i = 1; i < lines.size(); ++i) {
        const std::vector<std::string> row = fields_of(lines[i]);
        ASSERT_EQ(row.size(), header.size()) << lines[i];
        EXPECT_EQ(row[0], "\"bunny\"");
        EXPECT_EQ(row[1], path_name(points[i - 1].path));
        EXPECT_EQ(row[2], knob_name(points[i - 1].knob));
        EXPECT_EQ(row[3], std::to_string(points[i - 1].samples));
        EXPECT_EQ(row[4] + "x" + row[5] + " " + row[6] + " " + row[7], "32x24 2 2");
        EXPECT_EQ(row[12], "1000");  // primary rays of the first run
        // the speed-up at equal RMSE on packet rows, empty on scalar rows
        EXPECT_EQ(row[30], points[i - 1].path == RenderPath::packet ? "2.000000" : "") << lines[i];
        EXPECT_EQ(row[31] + "," + row[32] + "," + row[33], "\"converged\",400,0.0001");
    }
}

TEST(SweepCsv, TheSceneNameIsQuotedWithItsQuotesDoubled) {
    const SweepParams sweep = made_up_params();
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const std::string csv = sweep_csv(SweepLabel{"a,b\"c", 8, 8, 1}, sweep, converged(64, 0.0),
                                      points, speedups_of(points, sweep));
    const std::vector<std::string> lines = lines_of(csv);
    ASSERT_EQ(lines.size(), 7u);
    EXPECT_EQ(lines[1].rfind("\"a,b\"\"c\",packet,spp,1,8,8,1,2,", 0), 0u) << lines[1];
}

TEST(SweepCsv, NoSpeedUpWithOnePath) {
    SweepParams sweep = made_up_params();
    sweep.paths = {RenderPath::packet};
    const std::vector<SweepPoint> points = made_up_sweep(sweep);
    const std::vector<std::string> lines = lines_of(sweep_csv(
        SweepLabel{"s", 8, 8, 1}, sweep, converged(64, 0.0), points, speedups_of(points, sweep)));
    ASSERT_EQ(lines.size(), 4u);
    for (size_t i = 1; i < lines.size(); ++i) EXPECT_EQ(fields_of(lines[i])[30], "") << lines[i];
}

}  // namespace
}  // namespace raylane
