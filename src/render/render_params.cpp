// render: AOV names and display mappings.
#include "render/render_params.h"

#include <algorithm>
#include <cmath>

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

Film visualise_aov(Film film, Aov aov) {
    if (aov == Aov::color) return film;
    float max_value = 0.0f;
    for (const vec3& p : film.pixels)
        if (std::isfinite(p.x)) max_value = std::max(max_value, p.x);
    for (vec3& p : film.pixels) {
        switch (aov) {
            case Aov::color:
                break;
            case Aov::normal:
                p = p * 0.5f + 0.5f;
                break;
            case Aov::depth:
                p = vec3(max_value > 0.0f ? p.x / max_value : 0.0f);
                break;
            case Aov::bvh_cost:
                p = false_colour(max_value > 0.0f ? p.x / max_value : 0.0f);
                break;
        }
    }
    return film;
}

}  // namespace raylane
