// scene: camera animation (camera_path.h).
#include "scene/camera_path.h"

#include <algorithm>
#include <cmath>

namespace raylane {
namespace {

/// Uniform Catmull-Rom between b (s = 0) and c (s = 1), with a and d the keys around them.
glm::dvec3 catmull_rom(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d, double s) {
    const double s2 = s * s, s3 = s2 * s;
    return 0.5 * ((2.0 * b) + (c - a) * s + (2.0 * a - 5.0 * b + 4.0 * c - d) * s2 +
                  (3.0 * b - a - 3.0 * c + d) * s3);
}

double catmull_rom(double a, double b, double c, double d, double s) {
    return catmull_rom(glm::dvec3(a), glm::dvec3(b), glm::dvec3(c), glm::dvec3(d), s).x;
}

/// The point of a turn by `radians` about the axis through `centre` along unit `axis`.
glm::dvec3 rotate_about(glm::dvec3 p, glm::dvec3 centre, glm::dvec3 axis, double radians) {
    const glm::dvec3 v = p - centre;
    const double c = std::cos(radians), s = std::sin(radians);
    return centre + v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

}  // namespace

int frame_count(const CameraPath& path) {
    if (path.turntable_frames > 0) return path.turntable_frames;
    if (path.keys.size() < 2) return 1;
    const double span = double(path.keys.back().time) - double(path.keys.front().time);
    // a whisker over the last key's time still counts it (24 frames of 1/24 s end at 1 s)
    return static_cast<int>(std::floor(span * double(path.fps) + 1e-6)) + 1;
}

Camera camera_at_frame(const Camera& still, const CameraPath& path, int frame) {
    Camera c = still;
    if (path.turntable_frames > 0) {
        const double turn = double(path.turntable_degrees) * (3.14159265358979323846 / 180.0) *
                            double(frame) / double(path.turntable_frames);
        const glm::dvec3 axis = glm::normalize(glm::dvec3(still.up));
        c.position =
            vec3(rotate_about(glm::dvec3(still.position), glm::dvec3(still.look_at), axis, turn));
        return c;
    }
    if (path.keys.size() < 2) return c;
    const std::vector<CameraKey>& k = path.keys;
    const double time = double(k.front().time) + double(frame) / double(path.fps);
    // the segment [k[i], k[i + 1]] holding `time`, and where in it
    size_t i = 0;
    while (i + 2 < k.size() && time >= double(k[i + 1].time)) ++i;
    const double t0 = k[i].time, t1 = k[i + 1].time;
    const double s = std::clamp((time - t0) / (t1 - t0), 0.0, 1.0);
    const CameraKey& a = k[i > 0 ? i - 1 : i];
    const CameraKey& b = k[i];
    const CameraKey& cc = k[i + 1];
    const CameraKey& d = k[std::min(i + 2, k.size() - 1)];
    auto at = [&](auto field) {
        if (path.interpolation == Interpolation::linear)
            return glm::mix(glm::dvec3(b.*field), glm::dvec3(cc.*field), s);
        return catmull_rom(glm::dvec3(a.*field), glm::dvec3(b.*field), glm::dvec3(cc.*field),
                           glm::dvec3(d.*field), s);
    };
    c.position = vec3(at(&CameraKey::position));
    c.look_at = vec3(at(&CameraKey::look_at));
    c.up = vec3(glm::normalize(at(&CameraKey::up)));
    const double fov = path.interpolation == Interpolation::linear
                           ? std::lerp(double(b.fov_deg), double(cc.fov_deg), s)
                           : catmull_rom(a.fov_deg, b.fov_deg, cc.fov_deg, d.fov_deg, s);
    c.fov_deg = static_cast<float>(std::clamp(fov, 1e-3, 179.0));
    if (path.focus_at_look_at) c.focal_distance = glm::length(c.look_at - c.position);
    return c;
}

}  // namespace raylane
