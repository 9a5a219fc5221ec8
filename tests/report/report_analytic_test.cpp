// Tests of report/report_analytic.cpp: the lit sphere against a converged render, the mirror
// furnace, and scenes that have no analytic reference.
#include "report/report_analytic.h"

#include <gtest/gtest.h>

#include <string>

#include "report/report_cache.h"
#include "report/report_metrics.h"

namespace raylane {
namespace {

/// One sphere, a directional and a point light, ambient and Phong terms, black background.
SceneData lit_sphere_scene(int w, int h) {
    SceneData s;
    s.source = "<test>";
    s.camera.position = vec3(0.0f, 0.0f, -4.0f);
    s.camera.look_at = vec3(0.0f);
    s.camera.fov_deg = 40.0f;
    s.camera.width = w;
    s.camera.height = h;
    Material m;
    m.c_d = vec3(0.8f, 0.6f, 0.4f);
    m.k_d = 0.7f;
    m.k_a = 0.05f;
    m.k_s = 0.3f;
    m.exponent = 20.0f;
    s.materials.push_back(m);
    s.spheres.push_back(Sphere{vec3(0.1f, 0.0f, 0.0f), 1.0f});
    Object o;
    o.kind = ShapeKind::sphere;
    s.objects.push_back(o);
    Light d;
    d.kind = LightKind::directional;
    d.direction = glm::normalize(vec3(1.0f, 1.0f, -1.0f));
    d.intensity = 0.8f;
    s.lights.push_back(d);
    Light p;
    p.kind = LightKind::point;
    p.position = vec3(-2.0f, 1.0f, -2.0f);
    p.intensity = 6.0f;
    s.lights.push_back(p);
    return s;
}

TEST(AnalyticReference, LitSphereAgreesWithAConvergedRender) {
    const SceneData scene = lit_sphere_scene(40, 30);
    const auto a = analytic_reference(scene, 32);
    ASSERT_TRUE(a.has_value());
    EXPECT_NE(a->name.find("lit sphere"), std::string::npos);
    const Accel accel = build_accel(scene, BuildParams{});
    ReferenceParams p;
    p.spp = 256;
    const Reference r = render_converged_reference(scene, accel, p);
    // a render differs from the exact pixel integral by its own variance only (plus float
    // rounding and the 32x32 grid's error on silhouette pixels)
    const ErrorMetrics e = compute_error(r.film, a->film);
    EXPECT_LT(e.mse, 2.0 * r.variance + 1e-7) << "Var(render) " << r.variance;
    EXPECT_NEAR(e.mean, e.ref_mean, 1e-3);
    // and the picture is not trivial: lit, unlit and background pixels
    int lit = 0, black = 0;
    for (const vec3& v : a->film.pixels) {
        lit += v.x > 0.3f;
        black += v.x == 0.0f;
    }
    EXPECT_GT(lit, 50);
    EXPECT_GT(black, 50);
}

TEST(AnalyticReference, IsNotClaimedForOtherScenes) {
    EXPECT_FALSE(analytic_reference(make_builtin_scene()).has_value());
    SceneData s = lit_sphere_scene(8, 6);
    s.objects[0].has_transform = true;
    EXPECT_FALSE(analytic_reference(s).has_value());
    s = lit_sphere_scene(8, 6);
    s.lights[1].position = vec3(0.1f, 0.0f, 0.0f);  // a point light inside the sphere
    EXPECT_FALSE(analytic_reference(s).has_value());
    s = lit_sphere_scene(8, 6);
    s.materials[0].model = SpecularModel::glossy_phong;
    EXPECT_FALSE(analytic_reference(s).has_value());
}

TEST(AnalyticReference, MirrorFurnaceIsTheBackgroundEverywhere) {
    SceneData s = lit_sphere_scene(8, 6);
    s.lights.clear();
    s.background = vec3(0.3f, 0.4f, 0.5f);
    Material& m = s.materials[0];
    m.reflection = 1.0f;
    m.fresnel = false;
    m.c_s = vec3(1.0f);
    const auto a = analytic_reference(s);
    ASSERT_TRUE(a.has_value());
    EXPECT_NE(a->name.find("mirror furnace"), std::string::npos);
    for (const vec3& v : a->film.pixels) EXPECT_EQ(v, s.background);
    m.fresnel = true;  // Schlick makes the mirror angle-dependent: no closed form
    EXPECT_FALSE(analytic_reference(s).has_value());
}

}  // namespace
}  // namespace raylane
