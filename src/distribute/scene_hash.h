// distribute: a hash that names a scene, so that `assemble` can tell parts of different scenes
// apart.
#pragma once

#include <string>

#include "scene/scene.h"

namespace raylane {

/// FNV-1a (64 bits) over what the scene is made of, as 16 lowercase hex digits: the bytes of
/// the file it was loaded from (a scene file, or a model rendered on its own), then what that
/// file brought in from other files: every mesh's vertices, normals, uvs and triangles, every
/// texture's size and texels, every material's name and parameters. The built-in scene hashes
/// its name ("<built-in>"). A scene whose file cannot be read any more hashes its name in its
/// place. The same files give the same hash on any machine; --width, --height and the other
/// command-line settings are not part of it.
std::string scene_hash(const SceneData& scene);

}  // namespace raylane
