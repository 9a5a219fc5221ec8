// raylane/scene.h: a scene (a JSON scene file or a model file) loaded with its BVHs, rendered to
// a float image on the packet or the scalar path, the two paths compared, and its statistics.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace raylane {

/// Which of the two renderers (or ray-query paths) runs: the SIMD packet path, or the scalar
/// path, one ray at a time, the reference the packet path is checked against.
enum class TracePath { packet, scalar };

/// What a render writes: colour, or one of the analysis images.
enum class ImageKind {
    color,     ///< linear RGB
    normal,    ///< the shading normal's x, y, z in [-1, 1]; 0 where the ray misses
    depth,     ///< distance along the camera ray in scene units; 0 where it misses
    bvh_cost,  ///< BVH nodes visited by the pixel's camera rays
};

/// How a scene's BVHs are built: the report's median split (the default), or binned SAH, for
/// comparison.
enum class BvhBuild { median, sah };

/// A render's settings; 0 keeps the scene's own value. One of width and height alone keeps the
/// scene's aspect ratio.
struct RenderSettings {
    int width = 0;  ///< pixels, at most 32768 a side and 2^28 in all
    int height = 0;
    int spp = 0;      ///< samples per pixel
    int threads = 0;  ///< worker threads; 0 = all
    TracePath path = TracePath::packet;
    ImageKind image = ImageKind::color;
    uint32_t seed = 0;  ///< of the pixel jitter and the lights' and lobes' samples
};

/// A float image, row 0 at the top: pixel (x, y)'s channel c is
/// pixels[(y * width + x) * channels + c]. Colour is the pixels `raylane render -o FILE.pfm`
/// writes with the same settings.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;  ///< 3 for color and normal, 1 for depth and bvh_cost
    std::vector<float> pixels;
};

/// Settings of Scene::compare; 0 keeps the scene's own value.
struct CompareSettings {
    int width = 0;
    int height = 0;
    int spp = 0;
    int threads = 0;
    int repeats = 3;          ///< timed renders per path, 1 .. 100; the times are medians
    double tolerance = 2e-3;  ///< largest channel difference the paths may show
    size_t id_allowance = 0;  ///< camera-ray hits allowed to name another object or triangle
    bool progress = false;    ///< a progress line per render on stderr, when it is a terminal
};

/// The figures of `raylane compare`: both paths rendered, timed and compared.
struct Comparison {
    int width = 0, height = 0, spp = 0, repeats = 0;
    std::string instruction_set;  ///< the packet path's, e.g. "avx2"
    int packet_width = 0;
    double scalar_ms = 0.0, packet_ms = 0.0;  ///< median render times
    double max_abs_diff = 0.0, mean_abs_diff = 0.0, rmse = 0.0, psnr_db = 0.0;
    size_t pixels = 0;
    size_t pixels_over_1_255 = 0;  ///< pixels with a channel apart by more than 1/255
    size_t hit_id_mismatches = 0;  ///< camera rays whose first hit differs between the paths
    uint64_t scalar_nan_samples = 0, scalar_inf_samples = 0;
    uint64_t packet_nan_samples = 0, packet_inf_samples = 0;
    uint64_t scalar_shadow_rays = 0, packet_shadow_rays = 0;
    bool agree = false;  ///< within tolerance and id_allowance, same shadow rays, no NaN or inf
};

/// A binary BVH's shape.
struct TreeStats {
    size_t nodes = 0, leaves = 0;
    int max_leaf_depth = 0;
    double mean_leaf_depth = 0.0;
    double sah_cost = 0.0;
    size_t bytes = 0;
};

/// The wide BVH the packet path walks (one node per 4, 8 or 16 children).
struct WideTreeStats {
    size_t nodes = 0, leaves = 0;
    double mean_children = 0.0;
    double triangles_per_leaf = 0.0;
    size_t bytes = 0;
};

/// One triangle mesh of a scene and its trees.
struct MeshStats {
    std::string name;
    size_t triangles = 0;
    size_t dropped_triangles = 0;  ///< zero-area faces removed at load
    TreeStats binary;
    size_t binary_bytes_with_vertices = 0;
    WideTreeStats wide;
    size_t wide_bytes_with_ids = 0;
};

/// Milliseconds of each phase of the meshes' BVH builds, summed over the meshes.
struct BuildPhaseTimes {
    double centroids = 0.0, sorts = 0.0, splits = 0.0, vertices = 0.0, boxes = 0.0, collapse = 0.0;
};

/// The figures `raylane info` prints.
struct SceneStats {
    std::string source;  ///< the file loaded, or "<built-in>"
    int width = 0, height = 0, spp = 0;
    int frames = 1;            ///< of the camera's animation (1: a still)
    bool turntable = false;    ///< whether the animation is a turntable (else a camera path)
    bool fov_vertical = true;  ///< whether fov_deg spans the image's height (else its width)
    double fov_deg = 0.0;
    size_t objects = 0, spheres = 0, boxes = 0, cylinders = 0, planes = 0;
    size_t single_triangles = 0, materials = 0, lights = 0, textures = 0;
    size_t triangles = 0;  ///< in all meshes and single triangles
    std::string features;  ///< the shading features the scene uses, e.g. "textures meshes"
    std::vector<MeshStats> meshes;
    TreeStats top_level;      ///< the tree over the scene's objects
    size_t memory_bytes = 0;  ///< of every tree and the meshes' vertices
    double load_ms = 0.0, build_ms = 0.0;
    BvhBuild build = BvhBuild::median;
    BuildPhaseTimes build_phases_ms;  ///< of a median-split build (all 0 for SAH)
};

/// A scene and its BVHs, built once at load. Copies share the scene; renders and comparisons
/// of one scene run one at a time (each uses every thread it is given), from any thread.
class Scene {
  public:
    /// Loads a JSON scene (docs/scene-format.md) or a model file (.obj, .ply, optionally .gz:
    /// the model's own scene, a camera framing it and a light) and builds its BVHs. A model
    /// file's name that is not a file here ("bunny.ply") is looked up on RAYLANE_MODEL_PATH, as
    /// are the models a scene names (beside the scene first). An empty path is the built-in
    /// scene. Throws Error with the file, line and reason when the file is not one.
    static Scene load(const std::string& path, BvhBuild build = BvhBuild::median);

    /// Renders the scene. Throws Error when a setting is out of range.
    Image render(const RenderSettings& settings = {}) const;
    /// Renders with both paths, as `raylane compare` does, and compares the images.
    Comparison compare(const CompareSettings& settings = {}) const;
    SceneStats stats() const;

    const std::string& source() const;
    int width() const;  ///< the scene's own size and samples per pixel
    int height() const;
    int spp() const;
    /// What the loader noticed but accepted (e.g. a light inside an object), one line each.
    const std::vector<std::string>& warnings() const;

    struct State;  ///< the implementation (src/api/), opaque here

  private:
    explicit Scene(std::shared_ptr<State> state);
    std::shared_ptr<State> state_;
};

}  // namespace raylane
