// distribute: writing, reading and joining the parts of a frame (part.h).
#include "distribute/part.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>

#include "core/error.h"
#include "distribute/scene_hash.h"

namespace raylane {

PartInfo make_part_info(const SceneData& scene, const RenderParams& params, const std::string& path,
                        const std::string& bvh) {
    PartInfo info;
    info.scene = scene_hash(scene);
    info.settings = {{"aov", aov_name(params.aov)},
                     {"tonemap", scene.tonemap == Tonemap::report ? "report" : "srgb"},
                     {"spp", std::to_string(params.spp)},
                     {"seed", std::to_string(params.seed)},
                     {"path", path},
                     {"bvh", bvh},
                     {"light_samples", std::to_string(params.light_samples)},
                     {"glossy_samples", std::to_string(params.glossy_samples)}};
    return info;
}

std::string part_setting(const PartInfo& info, const std::string& name) {
    for (const auto& [key, value] : info.settings)
        if (key == name) return value;
    return {};
}

void set_part_setting(PartInfo& info, const std::string& name, const std::string& value) {
    for (auto& [key, v] : info.settings) {
        if (key == name) {
            v = value;
            return;
        }
    }
    info.settings.emplace_back(name, value);
}

namespace {

constexpr const char* scene_key = "raylane:scene";
constexpr const char* settings_key = "raylane:settings";

std::string settings_text(const PartInfo& info) {
    std::string text;
    for (const auto& [key, value] : info.settings) {
        if (!text.empty()) text += "; ";
        text += key;
        text += '=';
        text += value;
    }
    return text;
}

/// The settings of settings_text; false when the text is not of that form.
bool parse_settings(const std::string& text, PartInfo& info) {
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find(';', start);
        if (end == std::string::npos) end = text.size();
        const std::string item = text.substr(start, end - start);
        const size_t eq = item.find('=');
        if (eq == std::string::npos || eq == 0) return false;
        info.settings.emplace_back(item.substr(0, eq), item.substr(eq + 1));
        start = end + 1;
        while (start < text.size() && text[start] == ' ') ++start;
    }
    return true;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> frame_attributes(const PartInfo& info) {
    return {{scene_key, info.scene}, {settings_key, settings_text(info)}};
}

void write_part(const std::string& path, std::vector<AovFilm> films, int x0, int y0,
                int frame_width, int frame_height, const PartInfo& info) {
    if (films.empty()) throw std::invalid_argument("write_part: no film");
    ExrImage image;
    image.width = frame_width;
    image.height = frame_height;
    image.x0 = x0;
    image.y0 = y0;
    image.x1 = x0 + films[0].film.width;
    image.y1 = y0 + films[0].film.height;
    image.attributes = frame_attributes(info);
    image.full_float = true;
    for (AovFilm& f : films) image.layers.push_back(exr_layer(f.aov, std::move(f.film)));
    write_exr(path, image);
}

void write_part(const std::string& path, const Film& part_film, int x0, int y0, int frame_width,
                int frame_height, const PartInfo& info) {
    Aov aov = Aov::color;
    if (!parse_aov(part_setting(info, "aov"), aov))
        throw std::invalid_argument("write_part: the settings name no single aov");
    std::vector<AovFilm> films;
    films.push_back({aov, part_film});
    write_part(path, std::move(films), x0, y0, frame_width, frame_height, info);
}

Part read_part(const std::string& path) {
    Part part;
    part.path = path;
    part.image = read_exr(path);
    part.info.scene = exr_attribute(part.image, scene_key);
    const std::string settings = exr_attribute(part.image, settings_key);
    if (part.info.scene.empty() || settings.empty())
        throw InputError(path + ": not a Raylane part (its header has no " + scene_key + " and " +
                         settings_key + ")");
    if (!parse_settings(settings, part.info))
        throw InputError(path + ": " + settings_key + " is not of the form \"name=value; ...\"");
    if (!part.image.full_float)
        throw InputError(path +
                         ": holds 16-bit halves; a part holds 32-bit floats, as render writes it");
    return part;
}

namespace {

/// "x 16-31, y 0-15": the pixels [x0, x1) x [y0, y1), ends included.
std::string pixels_text(int x0, int y0, int x1, int y1) {
    std::string s = "x ";
    s += std::to_string(x0);
    if (x1 - 1 > x0) s.append("-").append(std::to_string(x1 - 1));
    s += ", y ";
    s += std::to_string(y0);
    if (y1 - 1 > y0) s.append("-").append(std::to_string(y1 - 1));
    return s;
}

std::string size_text(const ExrImage& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

/// "R, G, B; normal.X, normal.Y, normal.Z": the channels of every layer.
std::string channels_text(const ExrImage& image) {
    std::string s;
    for (const ExrLayer& layer : image.layers) {
        if (!s.empty()) s += "; ";
        for (size_t c = 0; c < layer.channels.size(); ++c) {
            if (c > 0) s += ", ";
            if (!layer.name.empty()) s.append(layer.name).append(".");
            s += layer.channels[c];
        }
    }
    return s;
}

/// Throws when `part` does not belong with `first`: frame size, scene, settings, channels.
void check_same_frame(const Part& first, const Part& part) {
    const std::string& a = first.path;
    const std::string& b = part.path;
    if (part.image.width != first.image.width || part.image.height != first.image.height)
        throw InputError(b + ": a part of a " + size_text(part.image) + " frame, " + a + " of a " +
                         size_text(first.image) + " frame");
    if (part.info.scene != first.info.scene)
        throw InputError(b + ": rendered from another scene than " + a + " (scene hash " +
                         part.info.scene + ", not " + first.info.scene + ")");
    for (const auto& [name, value] : first.info.settings) {
        const std::string other = part_setting(part.info, name);
        if (other.empty())
            throw InputError(b + ": gives no " + name + "; " + a + " has " + name + " " + value);
        if (other != value)
            throw InputError(b + ": " + name + " " + other + ", but " + a + " has " + name + " " +
                             value);
    }
    for (const auto& [name, value] : part.info.settings)
        if (part_setting(first.info, name).empty())
            throw InputError(b + ": " + name + " " + value + ", but " + a + " gives no " + name);
    if (channels_text(part.image) != channels_text(first.image))
        throw InputError(b + ": channels " + channels_text(part.image) + ", but " + a + " has " +
                         channels_text(first.image));
}

bool intersect(const ExrImage& p, const ExrImage& q, int& x0, int& y0, int& x1, int& y1) {
    x0 = std::max(p.x0, q.x0), y0 = std::max(p.y0, q.y0);
    x1 = std::min(p.x1, q.x1), y1 = std::min(p.y1, q.y1);
    return x0 < x1 && y0 < y1;
}

/// Throws, naming pixels no part holds, when the parts (which do not overlap) leave a gap.
void check_no_gap(const std::vector<Part>& parts) {
    const ExrImage& frame = parts[0].image;
    int64_t covered = 0;
    for (const Part& p : parts)
        covered += int64_t(p.image.x1 - p.image.x0) * (p.image.y1 - p.image.y0);
    if (covered == int64_t(frame.width) * frame.height) return;
    std::vector<bool> held(size_t(frame.width) * size_t(frame.height), false);
    const auto at = [&](int x, int y) { return size_t(y) * size_t(frame.width) + size_t(x); };
    for (const Part& p : parts)
        for (int y = p.image.y0; y < p.image.y1; ++y)
            for (int x = p.image.x0; x < p.image.x1; ++x) held[at(x, y)] = true;
    for (int y = 0; y < frame.height; ++y) {
        for (int x = 0; x < frame.width; ++x) {
            if (held[at(x, y)]) continue;
            // the run of missing pixels from (x, y) to the right, then the rows below it missing
            // that whole run
            int x1 = x + 1, y1 = y + 1;
            while (x1 < frame.width && !held[at(x1, y)]) ++x1;
            const auto row_missing = [&](int row) {
                for (int i = x; i < x1; ++i)
                    if (held[at(i, row)]) return false;
                return true;
            };
            while (y1 < frame.height && row_missing(y1)) ++y1;
            throw InputError("no part holds the pixels " + pixels_text(x, y, x1, y1) + " of the " +
                             size_text(frame) + " frame (" + std::to_string(parts.size()) +
                             " parts)");
        }
    }
}

Tonemap parse_tonemap(const Part& part) {
    const std::string t = part_setting(part.info, "tonemap");
    if (t == "srgb" || t.empty()) return Tonemap::srgb;
    if (t == "report") return Tonemap::report;
    throw InputError(part.path + ": unknown tonemap \"" + t + "\" in " + settings_key);
}

}  // namespace

JoinedFrame join_parts(std::vector<Part> parts) {
    if (parts.empty()) throw InputError("assemble: no parts");
    const Part& first = parts[0];
    for (const Part& p : parts) check_same_frame(first, p);
    JoinedFrame frame;
    for (const ExrLayer& layer : first.image.layers) {
        Aov aov = Aov::color;
        if (!aov_of_exr_layer(layer.name, aov) || exr_layer(aov, Film{}).channels != layer.channels)
            throw InputError(first.path + ": channels " + channels_text(first.image) +
                             " are no Raylane output (R, G, B; normal.X, normal.Y, normal.Z; "
                             "depth.Z; bvh_cost.Y)");
        frame.films.push_back({aov, make_film(first.image.width, first.image.height)});
    }
    for (size_t i = 0; i < parts.size(); ++i) {
        for (size_t j = i + 1; j < parts.size(); ++j) {
            int x0, y0, x1, y1;
            if (intersect(parts[i].image, parts[j].image, x0, y0, x1, y1))
                throw InputError(parts[i].path + " and " + parts[j].path +
                                 " overlap: both hold the pixels " + pixels_text(x0, y0, x1, y1));
        }
    }
    check_no_gap(parts);
    frame.tonemap = parse_tonemap(first);
    frame.info = first.info;
    for (Part& p : parts) {
        const ExrImage& image = p.image;
        for (size_t l = 0; l < image.layers.size(); ++l) {
            const Film& part = image.layers[l].film;
            Film& film = frame.films[l].film;
            for (int y = 0; y < part.height; ++y)
                std::copy_n(&part.at(0, y), part.width, &film.at(image.x0, image.y0 + y));
        }
        p.image.layers.clear();  // its memory back before the next part's copy
    }
    return frame;
}

}  // namespace raylane
