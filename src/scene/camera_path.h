// scene: camera animation: the camera of each frame of a CameraPath (scene.h).
#pragma once

#include "scene/scene.h"

namespace raylane {

/// Frames in the scene's animation: 1 for a still; for keys, every frame whose time is at most
/// the last key's.
int frame_count(const CameraPath& path);

/// The camera of frame `frame` (0 to frame_count - 1; later frames of a path hold the last key):
/// `still` (the scene's camera: resolution, samples, lens) with the path's position, look-at,
/// up and field of view at the frame's time.
Camera camera_at_frame(const Camera& still, const CameraPath& path, int frame);

}  // namespace raylane
