// report: the SVG log-log plot of plot_svg.h.
#include "report/plot_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace raylane {
namespace {

constexpr const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                   "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                // control characters are not allowed in XML 1.0 text
                if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        }
    }
    return out;
}

std::string fmt(const char* format, double a) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, a);
    return buf;
}

bool usable(double v) { return v > 0.0 && std::isfinite(v); }

/// Whole decades [lo, hi] (exponents) around the values; one decade at least.
struct Decades {
    int lo = 0, hi = 1;
};

Decades decades_of(const std::vector<double>& values) {
    double mn = INFINITY, mx = 0.0;
    for (double v : values)
        if (usable(v)) mn = std::min(mn, v), mx = std::max(mx, v);
    Decades d;
    if (!(mx > 0.0)) return d;
    // a hair of tolerance so that exact powers of ten do not open an empty decade
    d.lo = static_cast<int>(std::floor(std::log10(mn) + 1e-9));
    d.hi = static_cast<int>(std::ceil(std::log10(mx) - 1e-9));
    if (d.hi <= d.lo) d.hi = d.lo + 1;
    return d;
}

/// "10" with a superscript exponent.
std::string power_label(int k) {
    return "10<tspan dy=\"-6\" font-size=\"75%\">" + std::to_string(k) + "</tspan>";
}

void marker_svg(std::string& out, PlotMarker m, double x, double y, const std::string& colour) {
    const double r = 4.0;
    switch (m) {
        case PlotMarker::circle:
            out += "<circle cx=\"" + fmt("%.2f", x) + "\" cy=\"" + fmt("%.2f", y) + "\" r=\"" +
                   fmt("%.1f", r) + "\" fill=\"" + colour + "\"/>\n";
            break;
        case PlotMarker::square:
            out += "<rect x=\"" + fmt("%.2f", x - r) + "\" y=\"" + fmt("%.2f", y - r) +
                   "\" width=\"" + fmt("%.1f", 2 * r) + "\" height=\"" + fmt("%.1f", 2 * r) +
                   "\" fill=\"" + colour + "\"/>\n";
            break;
        case PlotMarker::triangle:
            out += "<path d=\"M" + fmt("%.2f", x) + "," + fmt("%.2f", y - 1.2 * r) + " L" +
                   fmt("%.2f", x + r) + "," + fmt("%.2f", y + 0.8 * r) + " L" + fmt("%.2f", x - r) +
                   "," + fmt("%.2f", y + 0.8 * r) + " Z\" fill=\"" + colour + "\"/>\n";
            break;
        case PlotMarker::diamond:
            out += "<path d=\"M" + fmt("%.2f", x) + "," + fmt("%.2f", y - 1.3 * r) + " L" +
                   fmt("%.2f", x + r) + "," + fmt("%.2f", y) + " L" + fmt("%.2f", x) + "," +
                   fmt("%.2f", y + 1.3 * r) + " L" + fmt("%.2f", x - r) + "," + fmt("%.2f", y) +
                   " Z\" fill=\"" + colour + "\"/>\n";
            break;
    }
}

/// The plot's place in the picture (pixels) and the decades its axes span.
struct PlotFrame {
    double width = 0, height = 0;
    double left = 80, right = 20, top = 44, bottom = 56;
    double pw = 0, ph = 0;  ///< the plot area's width and height
    Decades dx, dy;

    /// The picture's x of a value on the horizontal axis.
    double px(double x) const {
        return left + (std::log10(x) - dx.lo) / double(dx.hi - dx.lo) * pw;
    }
    /// The picture's y of a value on the vertical axis.
    double py(double y) const {
        return top + ph - (std::log10(y) - dy.lo) / double(dy.hi - dy.lo) * ph;
    }
};

/// The picture's size and margins, and axes spanning whole decades around every point that can
/// be shown and the ends of its error bar.
PlotFrame plot_frame(const LogLogPlot& plot) {
    PlotFrame f;
    f.width = std::max(200, plot.width), f.height = std::max(150, plot.height);
    f.pw = f.width - f.left - f.right, f.ph = f.height - f.top - f.bottom;
    std::vector<double> xs, ys;
    for (const PlotSeries& s : plot.series) {
        for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            if (!usable(s.x[i]) || !usable(s.y[i])) continue;
            xs.push_back(s.x[i]);
            ys.push_back(s.y[i]);
            if (i < s.y_err.size() && std::isfinite(s.y_err[i])) {
                ys.push_back(s.y[i] + std::fabs(s.y_err[i]));
                ys.push_back(s.y[i] - std::fabs(s.y_err[i]));  // dropped by decades_of if <= 0
            }
        }
    }
    f.dx = decades_of(xs), f.dy = decades_of(ys);
    return f;
}

/// The document's head: the svg element, a white background, the plot area's clip path and the
/// title.
void header_svg(std::string& out, const LogLogPlot& plot, const PlotFrame& f) {
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", f.width) +
           "\" height=\"" + fmt("%.0f", f.height) + "\" viewBox=\"0 0 " + fmt("%.0f", f.width) +
           " " + fmt("%.0f", f.height) + "\" font-family=\"sans-serif\" font-size=\"13\">\n";
    out += "<rect x=\"0\" y=\"0\" width=\"" + fmt("%.0f", f.width) + "\" height=\"" +
           fmt("%.0f", f.height) + "\" fill=\"white\"/>\n";
    out += "<defs><clipPath id=\"plot-area\"><rect x=\"" + fmt("%.2f", f.left) + "\" y=\"" +
           fmt("%.2f", f.top) + "\" width=\"" + fmt("%.2f", f.pw) + "\" height=\"" +
           fmt("%.2f", f.ph) + "\"/></clipPath></defs>\n";
    out += "<text x=\"" + fmt("%.1f", f.width / 2) +
           "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">" +
           escape(plot.title) + "</text>\n";
}

/// A vertical grid line at x and a horizontal one at y, across the plot area.
void vertical_line(std::string& out, const PlotFrame& f, double x) {
    out += "<line x1=\"" + fmt("%.2f", x) + "\" y1=\"" + fmt("%.2f", f.top) + "\" x2=\"" +
           fmt("%.2f", x) + "\" y2=\"" + fmt("%.2f", f.top + f.ph) + "\"/>\n";
}
void horizontal_line(std::string& out, const PlotFrame& f, double y) {
    out += "<line x1=\"" + fmt("%.2f", f.left) + "\" y1=\"" + fmt("%.2f", y) + "\" x2=\"" +
           fmt("%.2f", f.left + f.pw) + "\" y2=\"" + fmt("%.2f", y) + "\"/>\n";
}

/// The grid: light lines at 2..9 x 10^k, darker ones at 10^k.
void grid_svg(std::string& out, const PlotFrame& f) {
    out += "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
    for (int k = f.dx.lo; k < f.dx.hi; ++k)
        for (int m = 2; m <= 9; ++m) vertical_line(out, f, f.px(m * std::pow(10.0, k)));
    for (int k = f.dy.lo; k < f.dy.hi; ++k)
        for (int m = 2; m <= 9; ++m) horizontal_line(out, f, f.py(m * std::pow(10.0, k)));
    out += "</g>\n<g stroke=\"#b0b0b0\" stroke-width=\"1\">\n";
    for (int k = f.dx.lo; k <= f.dx.hi; ++k) vertical_line(out, f, f.px(std::pow(10.0, k)));
    for (int k = f.dy.lo; k <= f.dy.hi; ++k) horizontal_line(out, f, f.py(std::pow(10.0, k)));
    out += "</g>\n";
}

/// The plot area's border, the decade labels of both axes and the axis titles.
void axes_svg(std::string& out, const LogLogPlot& plot, const PlotFrame& f) {
    out += "<rect x=\"" + fmt("%.2f", f.left) + "\" y=\"" + fmt("%.2f", f.top) + "\" width=\"" +
           fmt("%.2f", f.pw) + "\" height=\"" + fmt("%.2f", f.ph) +
           "\" fill=\"none\" stroke=\"black\" stroke-width=\"1\"/>\n";
    out += "<g class=\"x-labels\" text-anchor=\"middle\">\n";
    for (int k = f.dx.lo; k <= f.dx.hi; ++k)
        out += "<text x=\"" + fmt("%.2f", f.px(std::pow(10.0, k))) + "\" y=\"" +
               fmt("%.2f", f.top + f.ph + 20) + "\">" + power_label(k) + "</text>\n";
    out += "</g>\n<g class=\"y-labels\" text-anchor=\"end\">\n";
    for (int k = f.dy.lo; k <= f.dy.hi; ++k)
        out += "<text x=\"" + fmt("%.2f", f.left - 8) + "\" y=\"" +
               fmt("%.2f", f.py(std::pow(10.0, k)) + 5) + "\">" + power_label(k) + "</text>\n";
    out += "</g>\n";
    out += "<text x=\"" + fmt("%.2f", f.left + f.pw / 2) + "\" y=\"" + fmt("%.2f", f.height - 12) +
           "\" text-anchor=\"middle\">" + escape(plot.x_label) + "</text>\n";
    out += "<text x=\"18\" y=\"" + fmt("%.2f", f.top + f.ph / 2) +
           "\" text-anchor=\"middle\" transform=\"rotate(-90 18 " + fmt("%.2f", f.top + f.ph / 2) +
           ")\">" + escape(plot.y_label) + "</text>\n";
}

/// The reference slope, dashed across the whole horizontal axis (when it can be drawn).
void reference_svg(std::string& out, const LogLogPlot& plot, const PlotFrame& f) {
    if (!(plot.reference && usable(plot.reference->x0) && usable(plot.reference->y0) &&
          std::isfinite(plot.reference->slope)))
        return;
    const ReferenceSlope& r = *plot.reference;
    const double x0 = std::pow(10.0, f.dx.lo), x1 = std::pow(10.0, f.dx.hi);
    const double y0 = r.y0 * std::pow(x0 / r.x0, r.slope);
    const double y1 = r.y0 * std::pow(x1 / r.x0, r.slope);
    if (usable(y0) && usable(y1))
        out += "<line class=\"reference\" x1=\"" + fmt("%.2f", f.px(x0)) + "\" y1=\"" +
               fmt("%.2f", f.py(y0)) + "\" x2=\"" + fmt("%.2f", f.px(x1)) + "\" y2=\"" +
               fmt("%.2f", f.py(y1)) +
               "\" stroke=\"#555555\" stroke-width=\"1.5\" stroke-dasharray=\"7,5\"/>\n";
}

/// Each series as a polyline, with an error bar and a marker at each point; returns the series'
/// colours.
std::vector<std::string> series_svg(std::string& out, const LogLogPlot& plot, const PlotFrame& f) {
    std::vector<std::string> colours;
    for (size_t si = 0; si < plot.series.size(); ++si) {
        const PlotSeries& s = plot.series[si];
        const std::string colour =
            s.colour.empty() ? palette[si % std::size(palette)] : escape(s.colour);
        colours.push_back(colour);
        std::string points;
        for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            if (!usable(s.x[i]) || !usable(s.y[i])) continue;
            if (!points.empty()) points += ' ';
            points += fmt("%.2f", f.px(s.x[i])) + "," + fmt("%.2f", f.py(s.y[i]));
        }
        out += "<polyline class=\"series\" points=\"" + points + "\" fill=\"none\" stroke=\"" +
               colour + "\" stroke-width=\"2\"/>\n";
        for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            if (!usable(s.x[i]) || !usable(s.y[i])) continue;
            const double x = f.px(s.x[i]), y = f.py(s.y[i]);
            if (i < s.y_err.size() && usable(std::fabs(s.y_err[i]))) {
                const double e = std::fabs(s.y_err[i]);
                const double hi = f.py(s.y[i] + e);
                const double lo = s.y[i] - e > 0.0 ? f.py(s.y[i] - e) : f.top + f.ph;
                out += "<line x1=\"" + fmt("%.2f", x) + "\" y1=\"" + fmt("%.2f", lo) + "\" x2=\"" +
                       fmt("%.2f", x) + "\" y2=\"" + fmt("%.2f", hi) + "\" stroke=\"" + colour +
                       "\" stroke-width=\"1\"/>\n";
            }
            marker_svg(out, s.marker, x, y, colour);
        }
    }
    return colours;
}

/// The legend, top right inside the plot: one entry per series, then the reference slope.
void legend_svg(std::string& out, const LogLogPlot& plot, const PlotFrame& f,
                const std::vector<std::string>& colours) {
    const size_t entries = plot.series.size() + (plot.reference ? 1 : 0);
    if (entries == 0) return;
    size_t longest = 0;
    for (const PlotSeries& s : plot.series) longest = std::max(longest, s.label.size());
    if (plot.reference) longest = std::max(longest, plot.reference->label.size());
    const double lw = 48 + 7.5 * static_cast<double>(longest), lh = 20;
    const double lx = f.left + f.pw - lw - 10, ly = f.top + 10;
    out += "<g class=\"legend\">\n<rect x=\"" + fmt("%.2f", lx) + "\" y=\"" + fmt("%.2f", ly) +
           "\" width=\"" + fmt("%.2f", lw) + "\" height=\"" +
           fmt("%.2f", lh * static_cast<double>(entries) + 8) +
           "\" fill=\"white\" fill-opacity=\"0.9\" stroke=\"#999999\"/>\n";
    for (size_t i = 0; i < entries; ++i) {
        const double y = ly + 4 + lh * (static_cast<double>(i) + 0.5);
        const bool ref = i == plot.series.size();
        const std::string colour = ref ? "#555555" : colours[i];
        out += "<line x1=\"" + fmt("%.2f", lx + 8) + "\" y1=\"" + fmt("%.2f", y) + "\" x2=\"" +
               fmt("%.2f", lx + 36) + "\" y2=\"" + fmt("%.2f", y) + "\" stroke=\"" + colour +
               "\" stroke-width=\"" + (ref ? "1.5" : "2") + "\"" +
               (ref ? " stroke-dasharray=\"7,5\"" : "") + "/>\n";
        if (!ref) marker_svg(out, plot.series[i].marker, lx + 22, y, colour);
        out += "<text x=\"" + fmt("%.2f", lx + 42) + "\" y=\"" + fmt("%.2f", y + 4.5) + "\">" +
               escape(ref ? plot.reference->label : plot.series[i].label) + "</text>\n";
    }
    out += "</g>\n";
}

}  // namespace

std::string loglog_svg(const LogLogPlot& plot) {
    const PlotFrame f = plot_frame(plot);
    std::string out;
    header_svg(out, plot, f);
    grid_svg(out, f);
    axes_svg(out, plot, f);
    // data, clipped to the plot area
    out += "<g clip-path=\"url(#plot-area)\">\n";
    reference_svg(out, plot, f);
    const std::vector<std::string> colours = series_svg(out, plot, f);
    out += "</g>\n";
    legend_svg(out, plot, f, colours);
    out += "</svg>\n";
    return out;
}

void write_text_file(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".partial";
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        f.flush();
        if (!f) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw std::runtime_error(path + ": cannot write");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw std::runtime_error(path + ": cannot write: " + ec.message());
    }
}

}  // namespace raylane
