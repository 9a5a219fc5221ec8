// image: the SVG log-log plot of plot_svg.h.
#include "image/plot_svg.h"

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

}  // namespace

std::string loglog_svg(const LogLogPlot& plot) {
    const double width = std::max(200, plot.width), height = std::max(150, plot.height);
    const double left = 80, right = 20, top = 44, bottom = 56;
    const double pw = width - left - right, ph = height - top - bottom;

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
    const Decades dx = decades_of(xs), dy = decades_of(ys);
    auto px = [&](double x) { return left + (std::log10(x) - dx.lo) / double(dx.hi - dx.lo) * pw; };
    auto py = [&](double y) {
        return top + ph - (std::log10(y) - dy.lo) / double(dy.hi - dy.lo) * ph;
    };

    std::string out;
    out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", width) +
           "\" height=\"" + fmt("%.0f", height) + "\" viewBox=\"0 0 " + fmt("%.0f", width) + " " +
           fmt("%.0f", height) + "\" font-family=\"sans-serif\" font-size=\"13\">\n";
    out += "<rect x=\"0\" y=\"0\" width=\"" + fmt("%.0f", width) + "\" height=\"" +
           fmt("%.0f", height) + "\" fill=\"white\"/>\n";
    out += "<defs><clipPath id=\"plot-area\"><rect x=\"" + fmt("%.2f", left) + "\" y=\"" +
           fmt("%.2f", top) + "\" width=\"" + fmt("%.2f", pw) + "\" height=\"" + fmt("%.2f", ph) +
           "\"/></clipPath></defs>\n";
    out += "<text x=\"" + fmt("%.1f", width / 2) +
           "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">" +
           escape(plot.title) + "</text>\n";

    // grid and ticks
    out += "<g stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
    for (int k = dx.lo; k < dx.hi; ++k)
        for (int m = 2; m <= 9; ++m) {
            const double x = px(m * std::pow(10.0, k));
            out += "<line x1=\"" + fmt("%.2f", x) + "\" y1=\"" + fmt("%.2f", top) + "\" x2=\"" +
                   fmt("%.2f", x) + "\" y2=\"" + fmt("%.2f", top + ph) + "\"/>\n";
        }
    for (int k = dy.lo; k < dy.hi; ++k)
        for (int m = 2; m <= 9; ++m) {
            const double y = py(m * std::pow(10.0, k));
            out += "<line x1=\"" + fmt("%.2f", left) + "\" y1=\"" + fmt("%.2f", y) + "\" x2=\"" +
                   fmt("%.2f", left + pw) + "\" y2=\"" + fmt("%.2f", y) + "\"/>\n";
        }
    out += "</g>\n<g stroke=\"#b0b0b0\" stroke-width=\"1\">\n";
    for (int k = dx.lo; k <= dx.hi; ++k) {
        const double x = px(std::pow(10.0, k));
        out += "<line x1=\"" + fmt("%.2f", x) + "\" y1=\"" + fmt("%.2f", top) + "\" x2=\"" +
               fmt("%.2f", x) + "\" y2=\"" + fmt("%.2f", top + ph) + "\"/>\n";
    }
    for (int k = dy.lo; k <= dy.hi; ++k) {
        const double y = py(std::pow(10.0, k));
        out += "<line x1=\"" + fmt("%.2f", left) + "\" y1=\"" + fmt("%.2f", y) + "\" x2=\"" +
               fmt("%.2f", left + pw) + "\" y2=\"" + fmt("%.2f", y) + "\"/>\n";
    }
    out += "</g>\n";
    out += "<rect x=\"" + fmt("%.2f", left) + "\" y=\"" + fmt("%.2f", top) + "\" width=\"" +
           fmt("%.2f", pw) + "\" height=\"" + fmt("%.2f", ph) +
           "\" fill=\"none\" stroke=\"black\" stroke-width=\"1\"/>\n";
    out += "<g class=\"x-labels\" text-anchor=\"middle\">\n";
    for (int k = dx.lo; k <= dx.hi; ++k)
        out += "<text x=\"" + fmt("%.2f", px(std::pow(10.0, k))) + "\" y=\"" +
               fmt("%.2f", top + ph + 20) + "\">" + power_label(k) + "</text>\n";
    out += "</g>\n<g class=\"y-labels\" text-anchor=\"end\">\n";
    for (int k = dy.lo; k <= dy.hi; ++k)
        out += "<text x=\"" + fmt("%.2f", left - 8) + "\" y=\"" +
               fmt("%.2f", py(std::pow(10.0, k)) + 5) + "\">" + power_label(k) + "</text>\n";
    out += "</g>\n";
    out += "<text x=\"" + fmt("%.2f", left + pw / 2) + "\" y=\"" + fmt("%.2f", height - 12) +
           "\" text-anchor=\"middle\">" + escape(plot.x_label) + "</text>\n";
    out += "<text x=\"18\" y=\"" + fmt("%.2f", top + ph / 2) +
           "\" text-anchor=\"middle\" transform=\"rotate(-90 18 " + fmt("%.2f", top + ph / 2) +
           ")\">" + escape(plot.y_label) + "</text>\n";

    // data, clipped to the plot area
    out += "<g clip-path=\"url(#plot-area)\">\n";
    if (plot.reference && usable(plot.reference->x0) && usable(plot.reference->y0) &&
        std::isfinite(plot.reference->slope)) {
        const ReferenceSlope& r = *plot.reference;
        const double x0 = std::pow(10.0, dx.lo), x1 = std::pow(10.0, dx.hi);
        const double y0 = r.y0 * std::pow(x0 / r.x0, r.slope);
        const double y1 = r.y0 * std::pow(x1 / r.x0, r.slope);
        if (usable(y0) && usable(y1))
            out += "<line class=\"reference\" x1=\"" + fmt("%.2f", px(x0)) + "\" y1=\"" +
                   fmt("%.2f", py(y0)) + "\" x2=\"" + fmt("%.2f", px(x1)) + "\" y2=\"" +
                   fmt("%.2f", py(y1)) +
                   "\" stroke=\"#555555\" stroke-width=\"1.5\" stroke-dasharray=\"7,5\"/>\n";
    }
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
            points += fmt("%.2f", px(s.x[i])) + "," + fmt("%.2f", py(s.y[i]));
        }
        out += "<polyline class=\"series\" points=\"" + points + "\" fill=\"none\" stroke=\"" +
               colour + "\" stroke-width=\"2\"/>\n";
        for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            if (!usable(s.x[i]) || !usable(s.y[i])) continue;
            const double x = px(s.x[i]), y = py(s.y[i]);
            if (i < s.y_err.size() && usable(std::fabs(s.y_err[i]))) {
                const double e = std::fabs(s.y_err[i]);
                const double hi = py(s.y[i] + e);
                const double lo = s.y[i] - e > 0.0 ? py(s.y[i] - e) : top + ph;
                out += "<line x1=\"" + fmt("%.2f", x) + "\" y1=\"" + fmt("%.2f", lo) + "\" x2=\"" +
                       fmt("%.2f", x) + "\" y2=\"" + fmt("%.2f", hi) + "\" stroke=\"" + colour +
                       "\" stroke-width=\"1\"/>\n";
            }
            marker_svg(out, s.marker, x, y, colour);
        }
    }
    out += "</g>\n";

    // legend, top right inside the plot
    const size_t entries = plot.series.size() + (plot.reference ? 1 : 0);
    if (entries > 0) {
        size_t longest = 0;
        for (const PlotSeries& s : plot.series) longest = std::max(longest, s.label.size());
        if (plot.reference) longest = std::max(longest, plot.reference->label.size());
        const double lw = 48 + 7.5 * static_cast<double>(longest), lh = 20;
        const double lx = left + pw - lw - 10, ly = top + 10;
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
