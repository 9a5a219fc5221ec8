// numerics.md §16 : extreme fields of view and lens radii for the camera
// (render/camera_rays.h, camera_rays_packet.h) and the scene loader's validation of them
// (io/load_scene.cpp): distinct rays at 1e-3 degrees, forward rays up to the widest accepted
// fov, invalid values rejected, lens radius 0 bitwise the pinhole.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/error.h"
#include "io/load_scene.h"
#include "render/camera_rays.h"
#include "render/camera_rays_packet.h"
#include "support/geometry_support.h"

namespace raylane {
namespace {

using namespace geometry_test;

/// Camera rays of a packet at width W for the given image positions and lens samples.
template <int W>
std::vector<Ray> packet_camera_rays(const CameraFrame& f, const std::vector<vec2>& xy,
                                    const std::vector<vec2>& lens) {
    std::vector<Ray> out;
    for (size_t first = 0; first < xy.size(); first += W) {
        vfloat<W> x(0.5f), y(0.5f), lu(0.5f), lv(0.5f);
        for (int i = 0; i < W && first + size_t(i) < xy.size(); ++i) {
            set(x, i, xy[first + size_t(i)].x);
            set(y, i, xy[first + size_t(i)].y);
            set(lu, i, lens[first + size_t(i)].x);
            set(lv, i, lens[first + size_t(i)].y);
        }
        const RayPacket<W> p = camera_ray<W>(f, x, y, lu, lv);
        for (int i = 0; i < W && first + size_t(i) < xy.size(); ++i) out.push_back(get_ray(p, i));
    }
    return out;
}

bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool same_bits(const Ray& a, const Ray& b) {
    return std::memcmp(&a.org, &b.org, sizeof(vec3)) == 0 &&
           std::memcmp(&a.dir, &b.dir, sizeof(vec3)) == 0;
}

/// Row P for camera rays: the packet rays equal the scalar ones bit for bit at every width.
void expect_packet_rays_match(const CameraFrame& f, const std::vector<vec2>& xy,
                              const std::vector<vec2>& lens) {
    std::vector<Ray> scalar;
    for (size_t i = 0; i < xy.size(); ++i)
        scalar.push_back(camera_ray(f, xy[i].x, xy[i].y, lens[i].x, lens[i].y));
    for_each_width([&](auto w) {
        constexpr int W = decltype(w)::value;
        const std::vector<Ray> packet = packet_camera_rays<W>(f, xy, lens);
        size_t differ = 0;
        for (size_t i = 0; i < xy.size(); ++i) differ += !same_bits(scalar[i], packet[i]);
        EXPECT_EQ(differ, 0u) << "W = " << W;
    });
}

/// fov = 1e-3 degrees across 640 pixels (2.7e-8 rad a pixel), looking down an axis and
/// obliquely: adjacent pixels still get distinct directions, in order, and the row spans the
/// field of view (a magnified view, not one ray): the directions are built in camera space,
/// never as differences of world-space points.
TEST(CameraExtremes, TinyFieldOfViewGivesDistinctMagnifiedRays) {
    for (bool oblique : {false, true}) {
        SCOPED_TRACE(oblique ? "oblique camera" : "camera along -z");
        Camera cam;
        cam.position = oblique ? vec3(1.3f, 2.1f, -4.7f) : vec3(0.0f, 0.0f, 5.0f);
        cam.look_at = oblique ? vec3(0.2f, -0.3f, 0.4f) : vec3(0.0f);
        cam.fov_deg = 1e-3f;
        cam.fov_axis = FovAxis::horizontal;
        cam.width = 640;
        cam.height = 480;
        const CameraFrame f = make_camera_frame(cam);
        std::vector<vec2> xy, lens;
        for (int y : {0, 240, 479}) {
            size_t same = 0;
            Ray prev;
            for (int x = 0; x < cam.width; ++x) {
                const Ray r = camera_ray(f, float(x) + 0.5f, float(y) + 0.5f);
                ASSERT_TRUE(finite(r.dir));
                if (x > 0) {
                    same += r.dir == prev.dir;
                    EXPECT_GT(glm::dot(r.dir - prev.dir, f.u), 0.0f) << "x " << x;
                }
                prev = r;
                xy.push_back(vec2(float(x) + 0.5f, float(y) + 0.5f));
                lens.push_back(vec2(0.5f));
            }
            EXPECT_EQ(same, 0u) << "adjacent pixels with the same direction, row " << y;
            // the angle between the first and last pixel centres: fov (w - 1) / w
            const glm::dvec3 a(camera_ray(f, 0.5f, float(y) + 0.5f).dir);
            const glm::dvec3 b(camera_ray(f, float(cam.width) - 0.5f, float(y) + 0.5f).dir);
            const double span = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
            const double want = glm::radians(1e-3) * (cam.width - 1) / cam.width;
            // within two pixels' angle: a unit float direction resolves ~6e-8 rad, about a pixel
            EXPECT_NEAR(span / want, 1.0, 2.0 / (cam.width - 1)) << "row " << y;
        }
        expect_packet_rays_match(f, xy, lens);
    }
}

/// 179 degrees, and the largest float below 180 (which the loader accepts): every ray of the
/// image, corners included, points forward (dot(dir, w) > 0) and is finite, in both paths.
TEST(CameraExtremes, WideFieldsOfViewPointForward) {
    for (float fov : {170.0f, 179.0f, 179.9f, std::nextafter(180.0f, 0.0f)}) {
        for (FovAxis axis : {FovAxis::vertical, FovAxis::horizontal}) {
            SCOPED_TRACE("fov " + std::to_string(fov) +
                         (axis == FovAxis::vertical ? " vertical" : " horizontal"));
            Camera cam;
            cam.position = vec3(1.0f, 2.0f, 3.0f);
            cam.look_at = vec3(0.3f, -0.4f, 0.1f);
            cam.fov_deg = fov;
            cam.fov_axis = axis;
            cam.width = 64;
            cam.height = 48;
            const CameraFrame f = make_camera_frame(cam);
            EXPECT_TRUE(f.half_width > 0.0f && std::isfinite(f.half_width)) << f.half_width;
            EXPECT_TRUE(f.half_height > 0.0f && std::isfinite(f.half_height)) << f.half_height;
            size_t backward = 0, non_finite = 0;
            std::vector<vec2> xy, lens;
            for (int y = 0; y <= cam.height; ++y) {
                for (int x = 0; x <= cam.width; ++x) {
                    const Ray r = camera_ray(f, float(x), float(y));  // pixel corners
                    non_finite += !finite(r.dir);
                    backward += !(glm::dot(r.dir, f.w) > 0.0f);
                    xy.push_back(vec2(float(x), float(y)));
                    lens.push_back(vec2(0.5f));
                }
            }
            EXPECT_EQ(non_finite, 0u);
            EXPECT_EQ(backward, 0u) << "rays pointing backwards";
            expect_packet_rays_match(f, xy, lens);
        }
    }
}

std::string scene_json(const std::string& camera_extra) {
    return R"({"version": 1,
  "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0], "resolution": [32, 24])" +
           camera_extra + R"(},
  "materials": {"m": {}},
  "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
}

/// The loader rejects a fov of 0 or 180 (and beyond, and values that round to them in float),
/// a negative lens radius and a focal distance <= 0, each with one line naming the value.
TEST(CameraExtremes, LoaderRejectsInvalidFieldOfViewAndLens) {
    const SceneData ok = load_scene_from_string(
        scene_json(R"(, "fov_deg": 179, "lens_radius": 0, "focal_distance": 1e-3)"), "ok.json");
    EXPECT_EQ(ok.camera.fov_deg, 179.0f);
    EXPECT_EQ(ok.camera.lens_radius, 0.0f);
    const char* bad[] = {
        R"(, "fov_deg": 0)",
        R"(, "fov_deg": 180)",
        R"(, "fov_deg": -30)",
        R"(, "fov_deg": 200)",
        R"(, "fov_deg": 1e-50)",
        R"(, "fov_deg": 179.9999999999)",
        R"(, "fov_deg": 60, "lens_radius": -0.1)",
        R"(, "fov_deg": 60, "lens_radius": 0.1, "focal_distance": 0)",
        R"(, "fov_deg": 60, "lens_radius": 0.1, "focal_distance": -2)",
    };
    for (const char* extra : bad) {
        SCOPED_TRACE(extra);
        try {
            load_scene_from_string(scene_json(extra), "bad.json");
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind("bad.json: $.camera.", 0), 0u) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

/// Lens radius 0: every lens sample gives the pinhole ray bit for bit (the renderers then draw
/// no lens numbers at all, so their sample sequences are the pinhole's too). Lens radius 1e-9:
/// within a hair of the pinhole. The disc centre (0.5, 0.5): a finite ray from the eye.
TEST(CameraExtremes, ZeroAndTinyLensRadiiMatchThePinhole) {
    Camera cam;
    cam.position = vec3(0.5f, 1.5f, -6.0f);
    cam.look_at = vec3(0.0f, 0.2f, 0.0f);
    cam.width = 320;
    cam.height = 240;
    cam.focal_distance = 6.0f;
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> s01(0.0f, 1.0f);
    std::vector<vec2> xy, lens;
    for (int i = 0; i < 4000; ++i) {
        xy.push_back(vec2(320.0f * s01(rng), 240.0f * s01(rng)));
        lens.push_back(i % 10 == 0 ? vec2(0.5f) : vec2(s01(rng), s01(rng)));
    }
    for (float radius : {0.0f, 1e-9f, 0.05f}) {
        SCOPED_TRACE("lens radius " + std::to_string(radius));
        cam.lens_radius = radius;
        const CameraFrame f = make_camera_frame(cam);
        size_t differ = 0, non_finite = 0, far_from_pinhole = 0;
        for (size_t i = 0; i < xy.size(); ++i) {
            const Ray pin = camera_ray(f, xy[i].x, xy[i].y);
            const Ray r = camera_ray(f, xy[i].x, xy[i].y, lens[i].x, lens[i].y);
            non_finite += !finite(r.org) || !finite(r.dir);
            differ += !same_bits(pin, r);
            const double off = glm::length(glm::dvec3(r.org) - glm::dvec3(pin.org));
            const double angle = glm::length(glm::dvec3(r.dir) - glm::dvec3(pin.dir));
            far_from_pinhole +=
                off > 1.01 * double(radius) || angle > 2.0 * double(radius) / 6.0 + 4e-7;
            if (lens[i] == vec2(0.5f)) {  // the disc centre: the eye itself
                EXPECT_EQ(r.org, cam.position);
            }
        }
        EXPECT_EQ(non_finite, 0u);
        EXPECT_EQ(far_from_pinhole, 0u);
        if (radius == 0.0f) {
            EXPECT_EQ(differ, 0u) << "lens radius 0 differs from the pinhole";
        }
        if (radius == 0.05f) {
            EXPECT_GT(differ, xy.size() / 2) << "the lens does nothing";
        }
        expect_packet_rays_match(f, xy, lens);
    }
}

}  // namespace
}  // namespace raylane
