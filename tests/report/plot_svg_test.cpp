// Tests of report/plot_svg.cpp: well-formed SVG, both series drawn, log axes, escaping.
#include "report/plot_svg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace raylane {
namespace {

/// Minimal XML check: every start tag closed in order (or self-closing), quotes balanced inside
/// tags, one root element. Returns an empty string when well-formed, else what is wrong.
std::string check_xml(const std::string& s, std::string* root = nullptr) {
    std::vector<std::string> stack;
    int roots = 0;
    size_t i = 0;
    while ((i = s.find('<', i)) != std::string::npos) {
        if (s.compare(i, 2, "<?") == 0) {
            const size_t e = s.find("?>", i);
            if (e == std::string::npos) return "unterminated <?";
            i = e + 2;
            continue;
        }
        if (s.compare(i, 4, "<!--") == 0) {
            const size_t e = s.find("-->", i);
            if (e == std::string::npos) return "unterminated comment";
            i = e + 3;
            continue;
        }
        // the end of the tag, outside quoted attribute values
        size_t e = i + 1;
        char quote = 0;
        for (; e < s.size(); ++e) {
            if (quote) {
                if (s[e] == quote) quote = 0;
            } else if (s[e] == '"' || s[e] == '\'') {
                quote = s[e];
            } else if (s[e] == '<') {
                return "'<' inside a tag at " + std::to_string(e);
            } else if (s[e] == '>') {
                break;
            }
        }
        if (e >= s.size()) return "unterminated tag at " + std::to_string(i);
        const bool closing = s[i + 1] == '/';
        const bool self_closing = s[e - 1] == '/';
        size_t n = i + (closing ? 2 : 1);
        std::string name;
        while (n < e &&
               (std::isalnum(static_cast<unsigned char>(s[n])) || s[n] == '-' || s[n] == ':'))
            name += s[n++];
        if (name.empty()) return "tag without a name at " + std::to_string(i);
        if (closing) {
            if (stack.empty() || stack.back() != name) return "unbalanced </" + name + ">";
            stack.pop_back();
        } else if (!self_closing) {
            if (stack.empty()) {
                ++roots;
                if (root) *root = name;
            }
            stack.push_back(name);
        }
        i = e + 1;
    }
    if (!stack.empty()) return "unclosed <" + stack.back() + ">";
    if (roots != 1) return std::to_string(roots) + " root elements";
    return "";
}

size_t count(const std::string& s, const std::string& what) {
    size_t n = 0;
    for (size_t i = s.find(what); i != std::string::npos; i = s.find(what, i + 1)) ++n;
    return n;
}

/// The (x, y) pairs of the index-th polyline's points attribute.
std::vector<std::pair<double, double>> polyline_points(const std::string& svg, size_t index) {
    size_t at = 0;
    for (size_t k = 0; k <= index; ++k) {
        at = svg.find("<polyline", k == 0 ? 0 : at + 1);
        if (at == std::string::npos) return {};
    }
    const size_t p = svg.find("points=\"", at) + 8;
    std::istringstream in(svg.substr(p, svg.find('"', p) - p));
    std::vector<std::pair<double, double>> out;
    double x, y;
    char comma;
    while (in >> x >> comma >> y) out.emplace_back(x, y);
    return out;
}

LogLogPlot two_series() {
    LogLogPlot plot;
    plot.title = "bunny: RMSE against render time";
    plot.x_label = "render time [s]";
    plot.y_label = "RMSE";
    PlotSeries a{"packet", {0.02, 0.04, 0.08, 0.16}, {0.1, 0.07, 0.05, 0.035}, {},
                 "",       PlotMarker::circle};
    PlotSeries b{"scalar", {0.1, 0.2, 0.4, 0.8}, {0.1, 0.07, 0.05, 0.035}, {0.01, 0.005, 0, 0},
                 "",       PlotMarker::square};
    plot.series = {a, b};
    plot.reference = ReferenceSlope{-0.5, 0.04, 0.07, "slope -1/2"};
    return plot;
}

TEST(PlotSvg, IsWellFormedWithBothPolylinesAndTheDashedSlope) {
    const std::string svg = loglog_svg(two_series());
    std::string root;
    EXPECT_EQ(check_xml(svg, &root), "");
    EXPECT_EQ(root, "svg");
    EXPECT_EQ(count(svg, "<polyline"), 2u);
    EXPECT_EQ(polyline_points(svg, 0).size(), 4u);
    EXPECT_EQ(polyline_points(svg, 1).size(), 4u);
    EXPECT_EQ(count(svg, "class=\"reference\""), 1u);
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
    EXPECT_NE(svg.find("bunny: RMSE against render time"), std::string::npos);
    EXPECT_NE(svg.find(">packet<"), std::string::npos);
    EXPECT_NE(svg.find(">scalar<"), std::string::npos);
    EXPECT_NE(svg.find(">slope -1/2<"), std::string::npos);
    EXPECT_EQ(count(svg, "<circle"), 4u + 1u);  // the points and the legend
    // squares: the points and the legend, besides background, clip area, frame and legend box
    EXPECT_EQ(count(svg, "<rect x=\"") - 4u, 4u + 1u);
}

TEST(PlotSvg, WellFormedCheckerRejectsBrokenDocuments) {
    // the checker itself must be able to fail
    EXPECT_NE(check_xml("<svg><g></svg>"), "");
    EXPECT_NE(check_xml("<svg><line x=\"1></svg>"), "");
    EXPECT_NE(check_xml("<svg/><svg/>"), "");
    EXPECT_EQ(check_xml("<?xml version=\"1.0\"?><svg><g a=\"x>y\"/></svg>"), "");
}

TEST(PlotSvg, AxesSpanWholeDecadesAroundTheData) {
    const std::string svg = loglog_svg(two_series());
    // x from 0.02 to 0.8: decades 10^-2 .. 10^0; y from 0.035 to 0.11: 10^-2 .. 10^0
    const size_t xl = svg.find("class=\"x-labels\""), yl = svg.find("class=\"y-labels\"");
    ASSERT_NE(xl, std::string::npos);
    ASSERT_NE(yl, std::string::npos);
    const std::string xlabels = svg.substr(xl, yl - xl);
    for (int k : {-2, -1, 0})
        EXPECT_NE(xlabels.find(">" + std::to_string(k) + "<"), std::string::npos) << k;
    EXPECT_EQ(xlabels.find(">-3<"), std::string::npos);
    EXPECT_EQ(xlabels.find(">1<"), std::string::npos);
}

TEST(PlotSvg, MapsLargerValuesRightAndUpOnLogScales) {
    const std::string svg = loglog_svg(two_series());
    const auto p = polyline_points(svg, 0);
    ASSERT_EQ(p.size(), 4u);
    for (size_t i = 1; i < p.size(); ++i) {
        EXPECT_GT(p[i].first, p[i - 1].first);    // time grows to the right
        EXPECT_GT(p[i].second, p[i - 1].second);  // smaller error is lower (SVG y grows down)
    }
    // equal ratios give equal steps on a log axis: x doubles at every point
    const double step1 = p[1].first - p[0].first, step2 = p[2].first - p[1].first;
    EXPECT_NEAR(step1, step2, 0.02);
    // both series have the same errors, so the same heights
    const auto q = polyline_points(svg, 1);
    ASSERT_EQ(q.size(), 4u);
    for (size_t i = 0; i < 4; ++i) EXPECT_NEAR(p[i].second, q[i].second, 0.01);
}

TEST(PlotSvg, LeavesOutPointsThatLogAxesCannotShow) {
    LogLogPlot plot = two_series();
    plot.series[0].y[1] = 0.0;
    plot.series[0].x[2] = std::nan("");
    const std::string svg = loglog_svg(plot);
    EXPECT_EQ(check_xml(svg), "");
    EXPECT_EQ(polyline_points(svg, 0).size(), 2u);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
}

TEST(PlotSvg, EscapesTextAndStaysWellFormedWithoutData) {
    LogLogPlot plot;
    plot.title = "a<b & \"c\"";
    plot.series.push_back(PlotSeries{"x<y", {}, {}, {}, "", PlotMarker::diamond});
    const std::string svg = loglog_svg(plot);
    EXPECT_EQ(check_xml(svg), "");
    EXPECT_NE(svg.find("a&lt;b &amp; &quot;c&quot;"), std::string::npos);
    EXPECT_NE(svg.find("x&lt;y"), std::string::npos);
    EXPECT_EQ(svg.find("a<b"), std::string::npos);
}

TEST(PlotSvg, WriteTextFileReplacesTheFile) {
    const std::string path =
        (std::filesystem::temp_directory_path() / "raylane_plot_svg_test.svg").string();
    write_text_file(path, "first");
    write_text_file(path, "second");
    std::ifstream f(path);
    const std::string text((std::istreambuf_iterator<char>(f)), {});
    EXPECT_EQ(text, "second");
    EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
    std::filesystem::remove(path);
    EXPECT_THROW(write_text_file("/no/such/dir/plot.svg", "x"), std::runtime_error);
}

}  // namespace
}  // namespace raylane
