// io: a model file (.obj, .ply) as a scene of its own: the model on a floor, a camera framing it
// from a three-quarter view, two lights with shadows, the model's own materials (a neutral
// "default" for the faces without one). The scene is JSON text
// (model_scene_json), so `raylane scene MODEL` prints exactly what `raylane render MODEL` renders.
#pragma once

#include <string>

#include "core/aabb.h"
#include "scene/scene.h"

namespace raylane {

/// Whether `path` names a model file by its extension (.obj, .ply, .obj.gz or .ply.gz, any
/// case).
bool is_model_file(const std::string& path);

/// The scene of a model alone, in the model's own units and its +y up: `fit` with scale 1 puts
/// the bottom centre of `bounds` (the model's bounding box) at the origin, on the floor plane
/// y = 0; the camera looks at the box's centre from 35 degrees to the right and 20 degrees above
/// its front (+z), at 0.9 of the distance where the box's bounding sphere would just fill the
/// vertical field of view (the sphere bounds the box loosely, so the box stays in the frame); a
/// key light and a fill light, with shadows, sit at distances in proportion, their intensities
/// by the square of the distance (intensity / d^2 at the model stays the same whatever the
/// units). `file` is the model file as the scene names it (found from the scene file's folder,
/// then the model search path). Throws InputError "FILE: the model has no extent to frame" for
/// an empty or single-point box.
std::string model_scene_json(const std::string& file, const Aabb& bounds);

/// Reads the model at `path` once and loads model_scene_json of it (errors name `path`).
SceneData load_model_scene(const std::string& path);

}  // namespace raylane
