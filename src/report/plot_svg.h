// report: a small dependency-free log-log line plot written as SVG (the plots of `raylane
// report`, report_plot.h). Tested by tests/report/plot_svg_test.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace raylane {

enum class PlotMarker : uint8_t { circle, square, triangle, diamond };

/// One line of the plot. Points with a non-positive or non-finite coordinate cannot be shown on
/// log axes and are left out.
struct PlotSeries {
    std::string label;
    std::vector<double> x, y;
    std::vector<double> y_err;  ///< symmetric error bars (same size as y), or empty
    std::string colour;         ///< SVG colour; empty = the next colour of the palette
    PlotMarker marker = PlotMarker::circle;
};

/// The dashed guide y = y0 (x / x0)^slope across the whole plot.
struct ReferenceSlope {
    double slope = -0.5;
    double x0 = 1.0, y0 = 1.0;
    std::string label = "slope -1/2";
};

struct LogLogPlot {
    std::string title, x_label, y_label;
    std::vector<PlotSeries> series;
    std::optional<ReferenceSlope> reference;
    int width = 720, height = 480;  ///< pixels (the SVG's width and height)
};

/// The plot as a standalone SVG document: axes spanning whole decades around the data (10^k
/// labelled, 2..9 x 10^k as minor ticks), a grid, each series as a polyline with markers and
/// error bars, the reference slope dashed, a legend and the title. Text is XML-escaped.
std::string loglog_svg(const LogLogPlot& plot);

/// Writes `text` to `path` through a temporary file and a rename. Throws std::runtime_error.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace raylane
