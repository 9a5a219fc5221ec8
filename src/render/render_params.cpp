// render: AOV names and display mappings.
#include "render/render_params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace raylane {

bool parse_aov(const std::string& name, Aov& aov) {
    for (Aov a : {Aov::color, Aov::normal, Aov::depth, Aov::bvh_cost}) {
        if (name == aov_name(a)) {
            aov = a;
            return true;
        }
    }
    return false;
}

const char* aov_name(Aov aov) {
    switch (aov) {
        case Aov::color:
            return "color";
        case Aov::normal:
            return "normal";
        case Aov::depth:
            return "depth";
        case Aov::bvh_cost:
            return "bvh-cost";
    }
    return "?";
}

namespace {

/// "%.4g" of x.
std::string short_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}

/// The depth film from white at the nearest hit to black at the 98th percentile of the hit
/// distances; misses (0) black.
std::string map_depth(Film& film) {
    std::vector<float> hits;
    for (const vec3& p : film.pixels)
        if (p.x > 0.0f && std::isfinite(p.x)) hits.push_back(p.x);
    if (hits.empty()) {
        for (vec3& p : film.pixels) p = vec3(0.0f);
        return "depth: no ray hit anything; the image is black";
    }
    const size_t at = (hits.size() - 1) * 98 / 100;
    std::nth_element(hits.begin(), hits.begin() + std::ptrdiff_t(at), hits.end());
    const float far = hits[at];
    const float near = *std::min_element(hits.begin(), hits.begin() + std::ptrdiff_t(at) + 1);
    // a log scale: a subject near the camera keeps its shades beside a floor to the horizon
    const double span = far > near ? std::log(double(far) / double(near)) : 1.0;
    for (vec3& p : film.pixels) {
        const bool hit = p.x > 0.0f && std::isfinite(p.x);
        const double v = hit ? std::log(double(far) / double(p.x)) / span : 0.0;
        p = vec3(float(std::clamp(v, 0.0, 1.0)));
    }
    return "depth: log scale, white at " + short_number(near) + ", black at " + short_number(far) +
           " and beyond (scene units along the ray); misses black";
}

/// Nodes visited in false colour from 0 to the image's maximum.
std::string map_cost(Film& film) {
    float most = 0.0f;
    for (const vec3& p : film.pixels)
        if (std::isfinite(p.x)) most = std::max(most, p.x);
    for (vec3& p : film.pixels) p = false_colour(most > 0.0f ? p.x / most : 0.0f);
    return "bvh-cost: false colour from 0 (dark blue) through green and yellow to " +
           short_number(most) + " nodes visited (white)";
}

}  // namespace

AovView visualise_aov(Film film, Aov aov) {
    std::string scale;
    switch (aov) {
        case Aov::color:
            break;
        case Aov::normal:
            for (vec3& p : film.pixels) p = p * 0.5f + 0.5f;
            scale = "normal: rgb = normal * 0.5 + 0.5";
            break;
        case Aov::depth:
            scale = map_depth(film);
            break;
        case Aov::bvh_cost:
            scale = map_cost(film);
            break;
    }
    return {std::move(film), std::move(scale)};
}

}  // namespace raylane
