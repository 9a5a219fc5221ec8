// app: `raylane scene MODEL`: prints the scene `raylane render MODEL` renders, as JSON to edit.
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "core/error.h"
#include "io/load_mesh.h"
#include "io/model_scene.h"
#include "scene/transform.h"

namespace raylane {
namespace {

int run_scene(const std::string& model) {
    if (!is_model_file(model))
        throw InputError(model + ": not a model: expected an .obj or .ply file");
    // the file as given: found from the folder the scene is saved in, or the model search path
    std::fputs(model_scene_json(model, mesh_bounds(load_mesh(model))).c_str(), stdout);
    return 0;
}

}  // namespace

void add_scene_command(CLI::App& app, int& exit_code) {
    auto model = std::make_shared<std::string>();
    CLI::App* cmd = app.add_subcommand(
        "scene",
        "print a model's scene (what `render MODEL` renders) as JSON: raylane scene bunny.ply > "
        "bunny.json; the model is named as given, so save the scene in the current folder or "
        "edit its \"file\"");
    cmd->add_option("model", *model, "model file (.obj, .ply)")
        ->required()
        ->check(existing_scene_file());
    cmd->callback([model, &exit_code] { exit_code = run_scene(*model); });
}

}  // namespace raylane
