// scene: the plain data every stage reads. Loaded by io/load_scene.cpp or made by
// scene/builtin_scene.cpp; the BVHs over it live in accel/ (Accel).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/ray.h"

namespace raylane {

using glm::mat4;
using glm::uvec3;

/// Which image-plane extent the field of view spans.
enum class FovAxis : uint8_t { vertical, horizontal };

struct Camera {
    vec3 position{0.0f, 0.0f, 0.0f};
    vec3 look_at{0.0f, 0.0f, 1.0f};
    vec3 up{0.0f, 1.0f, 0.0f};
    float fov_deg = 60.0f;
    FovAxis fov_axis = FovAxis::vertical;
    int width = 640;
    int height = 480;
    int spp = 1;  ///< samples per pixel; 1 = pixel centre, more = stratified jitter
    /// Thin lens (depth of field): radius of the lens disc; 0 is a pinhole. The plane of focus is
    /// at focal_distance along the view axis.
    float lens_radius = 0.0f;
    float focal_distance = 1.0f;
};

/// One keyframe of a camera path: where the camera is at `time` (seconds).
struct CameraKey {
    float time = 0.0f;
    vec3 position{0.0f}, look_at{0.0f, 0.0f, 1.0f}, up{0.0f, 1.0f, 0.0f};
    float fov_deg = 60.0f;
};

enum class Interpolation : uint8_t { linear, catmull_rom };

/// How the camera moves: `keys` (two or more, times increasing) sampled at `fps`, frame k at
/// keys[0].time + k / fps; or, when turntable_frames > 0, an orbit of the scene's camera about
/// the axis through its look-at point along its up direction, turntable_degrees in
/// turntable_frames frames (frame k at k / turntable_frames of the turn). No keys and no
/// turntable: a still.
struct CameraPath {
    std::vector<CameraKey> keys;
    Interpolation interpolation = Interpolation::catmull_rom;
    float fps = 24.0f;
    int turntable_frames = 0;
    float turntable_degrees = 360.0f;
    /// The focal distance follows each frame's look-at point (the scene gave none).
    bool focus_at_look_at = true;
};

/// The specular lobe of a material (brdf-reference.md; the formulas are in shade/brdf_*.h).
enum class SpecularModel : uint8_t { phong, glossy_phong, blinn_phong, ward, ward_duer };

/// How a normal map's texel changes the shading normal: `tangent` = tangent-space map
/// (RGB * 2 - 1 in the frame of dp/du, dp/dv, n), `replace` = the report's object-space mode
/// (the normal becomes RGB - 1/2 in the mesh's object space; report-scenes.md 1.6).
enum class NormalMapMode : uint8_t { tangent, replace };

/// Object appearance. Local shading (every material that is not refractive or emissive):
///   k_a c_d + sum over lights of k_d c_light F c_d cos(theta) + specular lobe,
/// then, when `reflection` > 0, (1 - R) local + R c_s L_mirror + k_a_after c_d with
/// R = Schlick(reflection, cos) (or `reflection` when fresnel is off). Refractive materials
/// shade by Fresnel-weighted reflection and refraction only, with Beer's law inside.
struct Material {
    std::string name;
    // diffuse
    vec3 c_d{0.8f};
    float k_d = 1.0f;
    float k_a = 0.0f;
    int32_t texture = -1;           ///< SceneData::textures index replacing c_d; -1 = none
    bool texture_specular = false;  ///< the texture also replaces c_s (the report's textures)
    // specular lobe
    SpecularModel model = SpecularModel::phong;
    vec3 c_s{1.0f};
    float k_s = 0.0f;
    float exponent = 32.0f;  ///< Phong / glossy Phong e, Blinn-Phong n
    float alpha = 0.1f;      ///< Ward and Ward-Duer roughness
    int glossy_samples = 10;
    // mirror reflection
    float reflection = 0.0f;  ///< Schlick r0 (> 1 amplifies, as in the fractal); 0 = no mirror
    float k_a_after = 0.0f;   ///< the report's ka_after: adds k_a_after c_d after the mirror term
    bool fresnel = true;      ///< false: angle-independent (R = r0 for mirrors, R = 0 for glass)
    // refraction
    bool refractive = false;
    float ior = 1.5f;
    vec3 filter{1.0f};  ///< Beer's law: radiance *= filter^distance travelled inside
    // maps and emission
    int32_t env_map =
        -1;  ///< SceneData::textures index: reflection map for this object's mirror rays
    int32_t normal_map = -1;
    NormalMapMode normal_map_mode = NormalMapMode::tangent;
    vec3 emission{0.0f};  ///< emitters (visible area lights) show this radiance and nothing else
    bool emissive() const { return emission != vec3(0.0f); }
};

/// point: factor intensity / d^2. directional: factor intensity, `direction` towards the light.
/// Area lights are `samples` point lights of factor intensity / d^2 each, averaged (the report's
/// "blurred point light", report-scenes.md 1.4), placed by stratified samples on a rectangle
/// (`position` + s edge_u + t edge_v), a disc (centre `position`, normal `direction`, `radius`)
/// or inside a box (`position` = min corner, `edge_u` = size).
enum class LightKind : uint8_t { point, directional, rect, disk, box };

struct Light {
    LightKind kind = LightKind::point;
    vec3 position{0.0f};
    vec3 direction{0.0f, 1.0f, 0.0f};
    vec3 edge_u{1.0f, 0.0f, 0.0f};
    vec3 edge_v{0.0f, 0.0f, 1.0f};
    float radius = 1.0f;
    int samples = 1;
    vec3 color{1.0f};
    float intensity = 1.0f;
    bool shadows = true;
    bool is_area() const { return kind >= LightKind::rect; }
};

/// Image or procedural texture. Images are linear RGB floats, row 0 = top row of the file;
/// uv (0, 0) is the bottom-left corner (v = 1 the top row, as in the report).
enum class TextureKind : uint8_t { image, checker };
enum class TextureFilter : uint8_t { nearest, bilinear };

struct Texture {
    std::string source;  ///< file name, or "checker"
    TextureKind kind = TextureKind::image;
    int width = 0, height = 0;
    std::vector<float> texels;  ///< width * height * 3
    TextureFilter filter = TextureFilter::bilinear;
    bool repeat = true;  ///< wrap uv (repeat) or clamp to the edge
    vec3 color_a{1.0f}, color_b{0.0f};
    float checks = 8.0f;  ///< checker squares per unit of u and of v
};

// Shapes in object space. Each object refers to one by (kind, index).
struct Sphere {
    vec3 center{0.0f};
    float radius = 1.0f;
};
struct Box {
    vec3 lo{-1.0f};
    vec3 hi{1.0f};
};
/// Finite cylinder around +y from y = 0 to y = height, with caps (the report's convention).
struct Cylinder {
    float radius = 1.0f;
    float height = 1.0f;
};
/// Infinite plane through `point` with unit `normal`. Planes live outside the BVH.
struct Plane {
    vec3 point{0.0f};
    vec3 normal{0.0f, 1.0f, 0.0f};
};
struct Triangle {
    vec3 p0{0.0f}, p1{1.0f, 0.0f, 0.0f}, p2{0.0f, 1.0f, 0.0f};
};

/// A triangle mesh in world space (object transforms are applied at load; the public
/// raylane::Mesh holds one with its BVHs).
/// Positions, normals and uvs have their own index triples, as in OBJ; normal_tris and uv_tris
/// are empty when the mesh has no normals or uvs, else they have one entry per triangle.
struct MeshData {
    std::string name;
    std::vector<vec3> positions;
    std::vector<vec3> normals;
    std::vector<vec2> uvs;
    std::vector<uvec3> tris;
    std::vector<uvec3> normal_tris;
    std::vector<uvec3> uv_tris;
    glm::mat3 normal_to_world{1.0f};  ///< inverse transpose of the baked transform (normal maps)
    size_t dropped_triangles = 0;     ///< zero-area faces the loader removed
    /// Materials the file names (an OBJ's `usemtl`), and per triangle the index of its own in
    /// material_names; both empty when the file names none. The scene loader splits the mesh
    /// by them (split_by_material) before it is traced.
    std::vector<std::string> material_names;
    std::vector<uint32_t> tri_material;
    std::vector<std::string> material_libraries;  ///< an OBJ's `mtllib` files, as written
    size_t triangle_count() const { return tris.size(); }
};

enum class ShapeKind : uint8_t { sphere, box, cylinder, plane, triangle, mesh };

/// Object = shape + material + transform. Analytic shapes are intersected in object space
/// (the ray is moved there by object_from_world); meshes are already in world space.
struct Object {
    ShapeKind kind = ShapeKind::sphere;
    uint32_t shape = 0;         ///< index into the SceneData array of that kind
    uint32_t material = 0;      ///< index into SceneData::materials
    bool casts_shadows = true;  ///< false for the visible boxes of area lights
    bool has_transform = false;
    mat4 world_from_object{1.0f};
    mat4 object_from_world{1.0f};
};

/// Fitted lobes (Ward, Ward-Duer, Blinn-Phong) and glossy Phong: `physical` is
/// brdf-reference.md section 2 with the cos(theta_i) factor on every lobe and 1/pi on diffuse;
/// `report` reproduces the original code's scaling (section 1).
enum class BrdfScaling : uint8_t { physical, report };

/// Film to 8 bits: `srgb` = clamp and sRGB encode; `report` = the report's hue-preserving clamp
/// (divide by the largest channel when it exceeds 1), no gamma (report-scenes.md 1.3).
enum class Tonemap : uint8_t { srgb, report };

/// The largest rendered image: each side at most max_film_side pixels, and at most
/// max_film_pixels in all (a film of 3.2 GB; a PNG's rows stay under stb_image_write's 2^31-byte
/// limit).
inline constexpr int max_film_side = 32768;
inline constexpr int64_t max_film_pixels = int64_t(1) << 28;

/// Deepest recursion a scene may ask for (reflection or refraction).
inline constexpr int max_path_depth = 64;

/// Glass interactions after which a path stops forking: where both a reflected and a refracted
/// ray would be traced, only the larger of the two (by Fresnel weight; the reflection on a tie)
/// goes on. Nested glass otherwise doubles the rays of a sample at every interaction (2^64 at
/// max_refraction_depth 64); this keeps a sample's tree at most 2^glass_fork_depth paths wide,
/// and a path longer than it is linear. Scenes with max_refraction_depth <= glass_fork_depth
/// never reach it.
inline constexpr int glass_fork_depth = 10;

/// SceneData-wide shading switches, including the report's analysis images (Figures 4 and 6).
struct ShadingOptions {
    BrdfScaling brdf = BrdfScaling::physical;
    int max_reflection_depth = 5;     ///< mirror rays allowed along a path
    int max_refraction_depth = 4;     ///< glass interactions along a path; deeper returns black
    bool local = true;                ///< the local (direct) term of mirrors
    bool reflection = true;           ///< mirror and glass reflected terms
    bool refraction = true;           ///< glass refracted term
    bool fresnel = true;              ///< false: every material angle-independent
    bool override_reflected = false;  ///< reflected radiance replaced by `reflected_color`
    vec3 reflected_color{1.0f, 0.0f, 1.0f};
};

/// Everything a scene file describes, in world space: the camera, the objects and their shapes,
/// materials, lights, textures and meshes (the public raylane::Scene holds one with its BVHs).
struct SceneData {
    std::string source;  ///< file the scene came from ("<built-in>" otherwise)
    /// The world point stored as (0, 0, 0): every position in the scene is relative to it
    /// (load_scene picks it at the camera's position, rounded; numerics.md section 17).
    glm::dvec3 world_origin{0.0};
    Camera camera;
    CameraPath camera_path;  ///< the camera's animation (scene/camera_path.h); none for a still
    vec3 background{0.0f};
    int32_t environment = -1;  ///< SceneData::textures index (latitude-longitude); -1 = background
    ShadingOptions shading;
    Tonemap tonemap = Tonemap::srgb;
    std::vector<Texture> textures;
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<Object> objects;
    std::vector<Sphere> spheres;
    std::vector<Box> boxes;
    std::vector<Cylinder> cylinders;
    std::vector<Plane> planes;
    std::vector<Triangle> triangles;
    std::vector<MeshData> meshes;
    /// What the loader let pass but a user should hear (a missing material library, a material
    /// no library defines, MTL keywords Raylane does not use): one line each.
    std::vector<std::string> warnings;
};

/// The scene that needs no model file: sphere, box, cylinder, plane and a triangle, two lights.
SceneData make_builtin_scene();

/// Number of triangles over all meshes and single triangles.
size_t count_triangles(const SceneData& scene);

}  // namespace raylane
