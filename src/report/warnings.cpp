// report: warnings about a scene or a render (warnings.h).
#include "report/warnings.h"

#include <algorithm>

#include "render/camera_rays.h"
#include "traverse/intersect_scalar.h"

namespace raylane {

namespace {

/// Camera rays on a grid of this many columns and rows look for an object.
constexpr int probe_columns = 32, probe_rows = 18;

bool camera_sees_an_object(const SceneData& scene, const Accel& accel) {
    const CameraFrame frame = make_camera_frame(scene.camera);
    for (int j = 0; j < probe_rows; ++j) {
        for (int i = 0; i < probe_columns; ++i) {
            const float x = (float(i) + 0.5f) / probe_columns * float(scene.camera.width);
            const float y = (float(j) + 0.5f) / probe_rows * float(scene.camera.height);
            if (intersect_closest(scene, accel, camera_ray(frame, x, y)).hit()) return true;
        }
    }
    return false;
}

}  // namespace

std::vector<std::string> scene_warnings(const SceneData& scene, const Accel& accel) {
    std::vector<std::string> w;
    if (scene.lights.empty())
        w.push_back(
            "the scene has no lights: surfaces show only their ambient term, emission "
            "and what they reflect");
    if (scene.objects.empty())
        w.push_back("the scene has no objects: the image is the background");
    else if (!camera_sees_an_object(scene, accel))
        w.push_back("the camera sees no object: check its position, look_at and fov_deg");
    return w;
}

std::vector<std::string> render_warnings(const Film& film, const RenderStats& stats,
                                         uint64_t samples) {
    std::vector<std::string> w;
    if (samples > 0 && stats.nan_samples == samples)
        w.push_back("every sample was NaN: the image is black");
    else if (std::all_of(film.pixels.begin(), film.pixels.end(),
                         [](const vec3& c) { return c == vec3(0.0f); }))
        w.push_back("every pixel is black");
    return w;
}

}  // namespace raylane
