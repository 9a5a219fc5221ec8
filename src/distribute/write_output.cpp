// distribute: a render's films to PNG, PFM or EXR (write_output.h).
#include "distribute/write_output.h"

#include <tbb/task_arena.h>

#include <stdexcept>
#include <utility>

namespace raylane {

ExrLayer exr_layer(Aov aov, Film film) {
    switch (aov) {
        case Aov::color:
            return {"", {"R", "G", "B"}, std::move(film)};
        case Aov::normal:
            return {"normal", {"X", "Y", "Z"}, std::move(film)};
        case Aov::depth:
            return {"depth", {"Z"}, std::move(film)};
        case Aov::bvh_cost:
            return {"bvh_cost", {"Y"}, std::move(film)};
    }
    throw std::invalid_argument("exr_layer: unknown AOV");
}

bool aov_of_exr_layer(const std::string& name, Aov& aov) {
    for (Aov a : {Aov::color, Aov::normal, Aov::depth, Aov::bvh_cost}) {
        if (exr_layer(a, Film{}).name == name) {
            aov = a;
            return true;
        }
    }
    return false;
}

std::string write_render_output(const std::string& path, std::vector<AovFilm> films,
                                const OutputOptions& options) {
    if (films.empty()) throw std::invalid_argument("write_render_output: no film");
    const ImageFormat format = image_format(path);
    if (format == ImageFormat::exr) {
        ExrImage image = make_exr_image(films[0].film.width, films[0].film.height);
        image.attributes = options.attributes;
        image.full_float = options.exr_float;
        for (AovFilm& f : films) image.layers.push_back(exr_layer(f.aov, std::move(f.film)));
        write_exr(path, image);
        return {};
    }
    if (films.size() != 1)
        throw std::invalid_argument(path + ": several outputs are written to an EXR only");
    const Aov aov = films[0].aov;
    const bool colour = aov == Aov::color;
    const bool report_look = colour && options.tonemap == Tonemap::report;
    // in place: the film is not needed afterwards (a copy is 25 MB of fresh pages).
    // A PFM holds an AOV's raw values (scene units, counts); a PNG its mapping, named by `scale`.
    const bool raw = !colour && format == ImageFormat::pfm;
    std::string scale;
    Film film;
    if (report_look) {
        film = hue_preserving_clamp(std::move(films[0].film));
    } else if (raw) {
        film = std::move(films[0].film);
    } else {
        AovView view = visualise_aov(std::move(films[0].film), aov);
        film = std::move(view.film);
        scale = std::move(view.scale);
    }
    // the bytes and the PNG's stream are made in parallel: on the threads options.threads allows
    tbb::task_arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic)
        .execute([&] {
            write_image(path, film, colour && !report_look ? Encoding::srgb : Encoding::linear);
        });
    return scale;
}

std::string write_render_output(const std::string& path, Film film, Aov aov,
                                const OutputOptions& options) {
    std::vector<AovFilm> films;
    films.push_back({aov, std::move(film)});
    return write_render_output(path, std::move(films), options);
}

}  // namespace raylane
