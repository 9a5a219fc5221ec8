// app: `raylane assemble PARTS... -o FRAME` joins the parts of a frame (part.h) into the image
// `raylane render` writes for the whole frame.
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "core/error.h"
#include "distribute/part.h"
#include "distribute/write_output.h"

namespace raylane {
namespace {

struct AssembleOptions {
    std::vector<std::string> parts;
    std::string output;
    int threads = 0;
    bool exr_float = false;
};

int run_assemble(const AssembleOptions& o) {
    std::vector<Part> parts;
    parts.reserve(o.parts.size());
    for (const std::string& path : o.parts) parts.push_back(read_part(path));
    JoinedFrame frame = join_parts(std::move(parts));
    const bool exr = image_format(o.output) == ImageFormat::exr;
    if (!exr && frame.films.size() != 1)
        throw InputError(o.output + ": the parts hold " + std::to_string(frame.films.size()) +
                         " outputs (aov " + part_setting(frame.info, "aov") +
                         "), which only an EXR holds together: use -o FILE.exr");
    const int width = frame.films[0].film.width, height = frame.films[0].film.height;
    OutputOptions options;
    options.tonemap = frame.tonemap;
    options.threads = worker_threads(o.threads);
    options.exr_float = o.exr_float;
    options.attributes = frame_attributes(frame.info);
    const std::string scale = write_render_output(o.output, std::move(frame.films), options);
    std::printf("frame      %dx%d from %zu parts\n", width, height, o.parts.size());
    if (!scale.empty()) std::printf("scale      %s\n", scale.c_str());
    std::printf("image      %s\n", o.output.c_str());
    return 0;
}

}  // namespace

void add_assemble_command(CLI::App& app, int& exit_code) {
    auto o = std::make_shared<AssembleOptions>();
    CLI::App* cmd = app.add_subcommand(
        "assemble",
        "join the parts of a frame (EXR files render wrote for regions) into its image");
    cmd->add_option("parts", o->parts, "the part files (.exr), together the whole frame")
        ->required();
    cmd->add_option("-o,--output", o->output, "image to write (.png, .pfm or .exr)")
        ->required()
        ->check(image_output());
    cmd->add_flag("--exr-float", o->exr_float,
                  "EXR output: 32-bit floats (default: 16-bit halves)");
    add_threads_option(cmd, o->threads);
    cmd->callback([o, &exit_code] { exit_code = run_assemble(*o); });
}

}  // namespace raylane
