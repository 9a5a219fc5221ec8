// io: the scene format's reader behind load_scene.h, one class whose parts are defined by concept
// in load_scene.cpp (top level, camera), load_scene_materials.cpp, load_scene_lights.cpp and
// load_scene_objects.cpp. Not a public header: load_scene.h is.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "io/json_reader.h"
#include "io/load_image.h"
#include "io/load_mtl.h"
#include "scene/scene.h"
#include "scene/transform.h"

namespace raylane {

/// The scene format on top of JsonReader's strict typed reads (every error names the JSON path).
class SceneReader : JsonReader {
  public:
    /// `loaded`: meshes already read, by the path find_model gives for their file name.
    SceneReader(std::string file, std::string dir, std::map<std::string, MeshData> loaded = {})
        : JsonReader(std::move(file)), dir_(std::move(dir)), meshes_(std::move(loaded)) {}

    SceneData read(const Json& root);

  private:
    using Node = JsonNode;

    std::string dir_;
    glm::dvec3 world_origin_{0.0};  ///< the world point stored as (0, 0, 0); set by read_camera
    std::map<std::string, MeshData> meshes_;   ///< loaded meshes by resolved path, before baking,
                                               ///< until their last object takes them
    std::map<std::string, int> mesh_uses_;     ///< objects still to read, by resolved path
    std::map<std::string, int32_t> textures_;  ///< texture index by file and options
    /// MTL libraries by resolved path (nullopt: missing, warned about once).
    std::map<std::string, std::optional<MtlLibrary>> libraries_;
    /// Material index by name, the first material of a name (objects name their material; a
    /// search of the list made 100,000 objects of 100,000 materials quadratic).
    std::unordered_map<std::string, uint32_t> material_ids_;

    /// A world-space point, moved so that world_origin_ becomes Raylane's origin (in double,
    /// rounded to float once).
    vec3 point(const Node& n) const { return vec3(dvec3(n) - world_origin_); }

    // top level (load_scene.cpp)
    Camera read_camera(const Node& n);
    CameraPath read_camera_path(const Node& camera, const Camera& still) const;
    CameraKey read_camera_key(const Node& n, const Camera& still) const;
    ShadingOptions read_shading(const Node& n) const;

    // materials and textures (load_scene_materials.cpp)
    uint32_t add_material(SceneData& scene, Material m);
    int32_t read_texture(const Node& n, SceneData& scene);
    void read_materials(const Node& n, SceneData& scene);
    Material read_material(const Node& m, const std::string& name, SceneData& scene);
    void read_brdf(const Node& m, Material& mat) const;
    void read_refraction(const Node& r, Material& mat) const;
    uint32_t material_index(const Node& object, SceneData& scene);
    int32_t texture_from_file(const std::string& resolved, ImageEncoding encoding,
                              TextureFilter filter, bool repeat, SceneData& scene);

    // a model file's own materials (load_scene_model_materials.cpp)
    uint32_t model_material(const std::string& name, const std::string& model_path,
                            const std::vector<std::string>& libraries, uint32_t fallback,
                            SceneData& scene);
    const MtlLibrary* material_library(const std::string& model_path, const std::string& name,
                                       SceneData& scene);
    Material mtl_material(const MtlMaterial& m, const std::string& library_path, SceneData& scene);

    // lights (load_scene_lights.cpp)
    Light read_light(const Node& n, SceneData& scene);
    void check_area_light(const Node& n, const Light& light) const;
    void add_emitter(const Light& light, SceneData& scene);

    // objects (load_scene_objects.cpp)
    Transform read_transform(const Node& n) const;
    glm::dmat4 read_fit(const Node& n, const Aabb& bounds) const;
    void read_object(const Node& n, SceneData& scene);
    void expect_shape_keys(const Node& n, ShapeKind kind) const;
    void read_shape(const Node& n, bool own_space, Object& object, SceneData& scene) const;
    void read_mesh(const Node& n, const Transform& t, Object object, SceneData& scene);
};

}  // namespace raylane
