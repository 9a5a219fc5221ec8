// render: the camera frame shared by both paths' primary rays.
#include "render/camera_rays.h"

#include <cmath>

namespace raylane {

CameraFrame make_camera_frame(const Camera& camera) {
    CameraFrame f;
    f.origin = camera.position;
    f.w = glm::normalize(camera.look_at - camera.position);
    f.u = glm::normalize(glm::cross(camera.up, f.w));
    f.v = glm::cross(f.w, f.u);
    const float aspect = static_cast<float>(camera.width) / static_cast<float>(camera.height);
    const float half = std::tan(glm::radians(camera.fov_deg) * 0.5f);
    if (camera.fov_axis == FovAxis::vertical) {
        f.half_height = half;
        f.half_width = half * aspect;
    } else {
        f.half_width = half;
        f.half_height = half / aspect;
    }
    f.inv_width = 1.0f / static_cast<float>(camera.width);
    f.inv_height = 1.0f / static_cast<float>(camera.height);
    f.lens_radius = camera.lens_radius;
    f.focal_distance = camera.focal_distance;
    return f;
}

}  // namespace raylane
