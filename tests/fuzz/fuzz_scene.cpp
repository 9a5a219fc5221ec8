// fuzz: libFuzzer target for the JSON scene reader (io/load_scene.h), from memory. Seeds:
// tests/fuzz/corpus/scene/; run by scripts/fuzz.sh.
//
// The scene is named as if it lived in tests/fuzz/fixtures/, so the mesh and texture names of
// the seeds (tri.obj, quad.ply, tex_8bit.img, tex.hdr) resolve to those tiny files. Inputs
// naming the large shared models are skipped: loading them is slow and exercises nothing the
// OBJ, PLY and image targets do not.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/error.h"
#include "fuzz_check.h"
#include "io/load_scene.h"

namespace {

using namespace raylane;
using fuzz::finite;
using fuzz::require;

bool names_large_model(std::string_view text) {
    for (std::string_view name : {"shared", "bunny", "dragon", "apple", "ornell"}) {
        if (text.find(name) != std::string_view::npos) return true;
    }
    return false;
}

bool texture_index_ok(int32_t index, const SceneData& scene) {
    return index >= -1 && index < static_cast<int64_t>(scene.textures.size());
}

size_t shape_count(ShapeKind kind, const SceneData& scene) {
    switch (kind) {
        case ShapeKind::sphere:
            return scene.spheres.size();
        case ShapeKind::box:
            return scene.boxes.size();
        case ShapeKind::cylinder:
            return scene.cylinders.size();
        case ShapeKind::plane:
            return scene.planes.size();
        case ShapeKind::triangle:
            return scene.triangles.size();
        case ShapeKind::mesh:
            return scene.meshes.size();
    }
    return 0;
}

/// What the renderer relies on: indices in range, finite numbers, positive sizes.
void check_scene(const SceneData& scene) {
    const Camera& c = scene.camera;
    require(finite(c.position) && finite(c.look_at) && finite(c.up), "non-finite camera vector");
    require(c.fov_deg > 0.0f && c.fov_deg < 180.0f, "camera fov_deg outside (0, 180)");
    require(c.width >= 1 && c.height >= 1 && c.spp >= 1, "camera resolution or spp below 1");
    require(finite(c.lens_radius) && c.lens_radius >= 0.0f && finite(c.focal_distance),
            "bad camera lens");
    require(finite(scene.background), "non-finite background");
    require(texture_index_ok(scene.environment, scene), "environment index out of range");
    for (const Texture& t : scene.textures) fuzz::check_texture(t);
    for (const Material& m : scene.materials) {
        require(texture_index_ok(m.texture, scene) && texture_index_ok(m.env_map, scene) &&
                    texture_index_ok(m.normal_map, scene),
                "material texture index out of range");
        require(finite(m.c_d) && finite(m.c_s) && finite(m.filter) && finite(m.emission),
                "non-finite material colour");
        require(finite(m.k_d) && finite(m.k_a) && finite(m.k_s) && finite(m.exponent) &&
                    finite(m.alpha) && finite(m.reflection) && finite(m.k_a_after) && finite(m.ior),
                "non-finite material coefficient");
        require(m.glossy_samples >= 1, "material glossy_samples below 1");
    }
    for (const Light& l : scene.lights) {
        require(finite(l.position) && finite(l.direction) && finite(l.edge_u) && finite(l.edge_v) &&
                    finite(l.color) && finite(l.radius) && finite(l.intensity),
                "non-finite light");
        require(l.samples >= 1, "light samples below 1");
    }
    for (const Object& o : scene.objects) {
        require(o.shape < shape_count(o.kind, scene), "object shape index out of range");
        require(o.material < scene.materials.size(), "object material index out of range");
        require(finite(o.world_from_object) && finite(o.object_from_world),
                "non-finite object transform");
    }
    for (const Sphere& s : scene.spheres) {
        require(finite(s.center) && finite(s.radius) && s.radius > 0.0f, "bad sphere");
    }
    for (const Box& b : scene.boxes) require(finite(b.lo) && finite(b.hi), "non-finite box");
    for (const Cylinder& cy : scene.cylinders) {
        require(finite(cy.radius) && finite(cy.height) && cy.radius > 0.0f && cy.height > 0.0f,
                "bad cylinder");
    }
    for (const Plane& p : scene.planes) {
        require(finite(p.point) && finite(p.normal), "non-finite plane");
    }
    for (const Triangle& t : scene.triangles) {
        require(finite(t.p0) && finite(t.p1) && finite(t.p2), "non-finite triangle");
    }
    for (const MeshData& m : scene.meshes) fuzz::check_mesh(m);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // model lookup: the fixtures' folder, then the shared models only
    setenv("RAYLANE_MODEL_PATH", RAYLANE_SHARED_DIR "/models:" RAYLANE_SHARED_DIR "/textures", 1);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view json(reinterpret_cast<const char*>(data), size);
    if (names_large_model(json)) return -1;  // -1: not added to the corpus
    static const std::string scene_path = RAYLANE_SOURCE_DIR "/tests/fuzz/fixtures/fuzz.json";
    try {
        check_scene(load_scene_from_string(json, scene_path));
    } catch (const InputError&) {
        // Expected for bad input; any other exception escapes and is a finding.
    }
    return 0;
}
