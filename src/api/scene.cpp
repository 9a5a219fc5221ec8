// api: raylane::Scene (raylane/scene.h): a scene opened as the command line opens it, its BVHs,
// renders on either path, the two paths compared as `raylane compare` does, its statistics.
#include "raylane/scene.h"

#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>
#include <utility>

#include "accel/bvh.h"
#include "api/guard.h"
#include "core/clock.h"
#include "core/float_modes.h"
#include "core/isa.h"
#include "core/threads.h"
#include "image/film.h"
#include "io/model_path.h"
#include "io/model_scene.h"
#include "io/open_scene.h"
#include "render/primary_ids.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "report/compare.h"
#include "report/report_metrics.h"
#include "scene/camera_path.h"
#include "scene/features.h"
#include "scene/resolution.h"

namespace raylane {

struct Scene::State {
    SceneData scene;
    Accel accel;
    Camera camera;  ///< the file's camera; a render sets scene.camera to its own size
    double load_ms = 0.0, build_ms = 0.0;
    BvhBuild build = BvhBuild::median;
    std::mutex mutex;  ///< one render or comparison at a time (each sets scene.camera)
};

namespace {

/// The scene's camera at the requested size, and the render parameters, as `raylane render`
/// sets them from its options (0 = the scene's own value). Called with the state's mutex held.
RenderParams prepare(Scene::State& s, int spp, int threads, int width, int height) {
    check_range("spp", spp, 0, 1 << 20);
    check_range("threads", threads, 0, 1024);
    check_range("width", width, 0, max_film_side);
    check_range("height", height, 0, max_film_side);
    s.scene.camera = s.camera;
    apply_resolution(s.scene.camera, width, height);
    RenderParams params;
    params.spp = spp > 0 ? spp : s.camera.spp;
    params.threads = worker_threads(threads);
    return params;
}

Aov internal_aov(ImageKind kind) {
    switch (kind) {
        case ImageKind::normal:
            return Aov::normal;
        case ImageKind::depth:
            return Aov::depth;
        case ImageKind::bvh_cost:
            return Aov::bvh_cost;
        case ImageKind::color:
            break;
    }
    return Aov::color;
}

Image to_image(const Film& film, bool one_channel) {
    Image image;
    image.width = film.width;
    image.height = film.height;
    image.channels = one_channel ? 1 : 3;
    if (one_channel) {
        image.pixels.resize(film.pixels.size());
        for (size_t i = 0; i < film.pixels.size(); ++i) image.pixels[i] = film.pixels[i].x;
    } else {
        static_assert(sizeof(vec3) == 3 * sizeof(float));
        image.pixels.resize(3 * film.pixels.size());
        if (!film.pixels.empty())
            std::memcpy(image.pixels.data(), film.pixels.data(), film.pixels.size() * sizeof(vec3));
    }
    return image;
}

TreeStats tree_stats(const BvhStats& b) {
    TreeStats t;
    t.nodes = b.nodes, t.leaves = b.leaves, t.max_leaf_depth = b.max_leaf_depth;
    t.mean_leaf_depth = b.mean_leaf_depth, t.sah_cost = b.sah_cost, t.bytes = b.bytes;
    return t;
}

}  // namespace

/// A model file's name that is not a file here (e.g. "bunny.ply") is looked up on
/// RAYLANE_MODEL_PATH, as Mesh::load does; any other path is opened as it is.
std::string model_or_path(const std::string& path) {
    std::error_code ec;
    if (path.empty() || !is_model_file(path) || std::filesystem::exists(path, ec) ||
        std::filesystem::path(path).is_absolute())
        return path;
    return find_model(path, ".");
}

Scene::Scene(std::shared_ptr<State> state) : state_(std::move(state)) {}

Scene Scene::load(const std::string& path, BvhBuild build) {
    return guarded([&] {
        auto s = std::make_shared<State>();
        const double t_load = now_seconds();
        s->scene = open_scene(model_or_path(path));
        s->load_ms = elapsed_ms(t_load);
        const double t_build = now_seconds();
        s->build = build;
        BuildParams params;
        params.method = build;
        s->accel = build_accel(s->scene, params);
        s->build_ms = elapsed_ms(t_build);
        s->camera = s->scene.camera;
        return Scene(std::move(s));
    });
}

Image Scene::render(const RenderSettings& settings) const {
    return guarded([&] {
        State& s = *state_;
        std::lock_guard<std::mutex> lock(s.mutex);
        RenderParams params =
            prepare(s, settings.spp, settings.threads, settings.width, settings.height);
        params.aov = internal_aov(settings.image);
        params.seed = settings.seed;
        KeepFloatModes keep;
        RenderResult r = settings.path == TracePath::scalar
                             ? render_scalar(s.scene, s.accel, params)
                             : render_packet(s.scene, s.accel, params);
        // as the command line writes a PFM: colour in the report's look is clamped (the report's
        // tone mapping); the analysis images are raw
        const bool color = settings.image == ImageKind::color;
        const Film film = color && s.scene.tonemap == Tonemap::report
                              ? hue_preserving_clamp(std::move(r.film))
                              : std::move(r.film);
        return to_image(
            film, settings.image == ImageKind::depth || settings.image == ImageKind::bvh_cost);
    });
}

Comparison Scene::compare(const CompareSettings& settings) const {
    return guarded([&] {
        check_range("repeats", settings.repeats, 1, 100);
        if (!(settings.tolerance >= 0.0) || !std::isfinite(settings.tolerance))
            throw Error("tolerance: must be a finite number >= 0");
        State& s = *state_;
        std::lock_guard<std::mutex> lock(s.mutex);
        RenderParams params =
            prepare(s, settings.spp, settings.threads, settings.width, settings.height);
        KeepFloatModes keep;
        // as `raylane report` times: an untimed 1-spp render per path, then the paths in turn
        RenderParams warm = params;
        warm.spp = 1;
        (void)render_scalar(s.scene, s.accel, warm);
        (void)render_packet(s.scene, s.accel, warm);
        RenderResult scalar, packet;
        std::vector<double> scalar_s, packet_s;
        params.progress = settings.progress;
        for (int r = 0; r < settings.repeats; ++r) {
            params.progress_label = "scalar";
            RenderResult a = render_scalar(s.scene, s.accel, params);
            params.progress_label = "packet";
            RenderResult b = render_packet(s.scene, s.accel, params);
            scalar_s.push_back(a.stats.seconds), packet_s.push_back(b.stats.seconds);
            if (r == 0) scalar = std::move(a), packet = std::move(b);
        }
        const ImageDiff diff = diff_images(scalar.film, packet.film);
        Comparison c;
        c.width = s.scene.camera.width;
        c.height = s.scene.camera.height;
        c.spp = params.spp;
        c.repeats = settings.repeats;
        c.instruction_set = isa_name(active_isa());
        c.packet_width = isa_width(active_isa());
        c.scalar_ms = 1000.0 * median(scalar_s);
        c.packet_ms = 1000.0 * median(packet_s);
        c.max_abs_diff = diff.max_abs;
        c.mean_abs_diff = diff.mean_abs;
        c.rmse = diff.rmse;
        c.psnr_db = diff.psnr_db;
        c.pixels = scalar.film.pixels.size();
        c.pixels_over_1_255 = diff.pixels_over_8bit;
        c.hit_id_mismatches = primary_id_mismatches(s.scene, s.accel);
        c.scalar_nan_samples = scalar.stats.nan_samples;
        c.scalar_inf_samples = scalar.stats.inf_samples;
        c.packet_nan_samples = packet.stats.nan_samples;
        c.packet_inf_samples = packet.stats.inf_samples;
        c.scalar_shadow_rays = scalar.stats.shadow_rays;
        c.packet_shadow_rays = packet.stats.shadow_rays;
        c.agree = diff.max_abs <= settings.tolerance &&
                  c.hit_id_mismatches <= settings.id_allowance &&
                  c.scalar_shadow_rays == c.packet_shadow_rays && scalar.stats.bad_samples() == 0 &&
                  packet.stats.bad_samples() == 0;
        return c;
    });
}

SceneStats Scene::stats() const {
    const State& st = *state_;
    const SceneData& s = st.scene;
    const Camera& c = st.camera;
    SceneStats d;
    d.source = s.source;
    d.width = c.width, d.height = c.height, d.spp = c.spp;
    d.frames = frame_count(s.camera_path);
    d.turntable = s.camera_path.turntable_frames > 0;
    d.fov_vertical = c.fov_axis == FovAxis::vertical;
    d.fov_deg = c.fov_deg;
    d.objects = s.objects.size(), d.spheres = s.spheres.size(), d.boxes = s.boxes.size();
    d.cylinders = s.cylinders.size(), d.planes = s.planes.size();
    d.single_triangles = s.triangles.size(), d.materials = s.materials.size();
    d.lights = s.lights.size(), d.textures = s.textures.size();
    d.triangles = count_triangles(s);
    d.features = feature_names(scene_features(s));
    size_t total = 0;
    for (size_t i = 0; i < st.accel.meshes.size(); ++i) {
        const MeshAccel& m = st.accel.meshes[i];
        const size_t vert_bytes = m.verts.size() * sizeof(TriangleVerts);
        const BvhStats b = compute_stats(m.bvh);
        const WideStats w = compute_wide_stats(m.wide);
        MeshStats ms;
        ms.name = s.meshes[i].name;
        ms.triangles = m.verts.size();
        ms.dropped_triangles = s.meshes[i].dropped_triangles;
        ms.binary = tree_stats(b);
        ms.binary_bytes_with_vertices = b.bytes + vert_bytes;
        ms.wide.nodes = w.nodes, ms.wide.leaves = w.leaves, ms.wide.bytes = w.bytes;
        ms.wide.mean_children = w.mean_children;
        ms.wide.triangles_per_leaf = w.leaves ? double(w.prims) / double(w.leaves) : 0.0;
        ms.wide_bytes_with_ids = w.bytes + m.bvh.prim_ids.size() * sizeof(uint32_t);
        d.meshes.push_back(std::move(ms));
        total += b.bytes + vert_bytes + w.bytes;
    }
    const BvhStats top = compute_stats(st.accel.top);
    d.top_level = tree_stats(top);
    d.memory_bytes = total + top.bytes;
    d.load_ms = st.load_ms, d.build_ms = st.build_ms;
    d.build = st.build;
    BuildPhases sum;  // the meshes' builds, phase by phase (ms)
    for (const MeshAccel& m : st.accel.meshes) sum += m.phases;
    d.build_phases_ms = {sum.centroids, sum.sorts, sum.splits,
                         sum.vertices,  sum.boxes, sum.collapse};
    return d;
}

const std::string& Scene::source() const { return state_->scene.source; }
int Scene::width() const { return state_->camera.width; }
int Scene::height() const { return state_->camera.height; }
int Scene::spp() const { return state_->camera.spp; }
const std::vector<std::string>& Scene::warnings() const { return state_->scene.warnings; }

}  // namespace raylane
