// python: raylane.load_scene and Scene: render (the pixels `raylane render -o FILE.pfm` writes),
// compare (the figures of `raylane compare`) and info (those of `raylane info`).
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

#include "app/commands.h"
#include "core/float_modes.h"
#include "core/isa.h"
#include "python/bindings.h"
#include "render/primary_ids.h"
#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "report/compare.h"
#include "report/report_metrics.h"
#include "scene/features.h"

namespace raylane::python {
namespace {

/// A loaded scene and its BVHs, built once at load.
struct SceneHandle {
    SceneData scene;
    Accel accel;
    Camera camera;  ///< the file's camera; render and compare change scene.camera
    double load_ms = 0.0, build_ms = 0.0;
    std::mutex mutex;  ///< one render or compare at a time (they set scene.camera)
};

std::shared_ptr<SceneHandle> load(const std::string& path) {
    require_file(path);
    auto h = std::make_shared<SceneHandle>();
    py::gil_scoped_release release;
    const double t_load = now_seconds();
    h->scene = load_command_scene(path);
    h->load_ms = elapsed_ms(t_load);
    const double t_build = now_seconds();
    h->accel = build_accel(h->scene, BuildParams{});
    h->build_ms = elapsed_ms(t_build);
    h->camera = h->scene.camera;
    return h;
}

void check_range(const char* name, int value, int lo, int hi) {
    if (value < lo || value > hi) {
        std::string m = name;
        m.append(": ").append(std::to_string(value)).append(" is outside ");
        m.append(std::to_string(lo)).append(" .. ").append(std::to_string(hi));
        throw BadArgument(m);
    }
}

/// The scene's camera at the requested size, and the render parameters, as `raylane render`
/// sets them from its options (0 = the scene's own value).
RenderParams prepare(SceneHandle& h, int spp, int threads, int width, int height) {
    check_range("spp", spp, 0, 1 << 20);
    check_range("threads", threads, 0, 1024);
    check_range("width", width, 0, max_film_side);
    check_range("height", height, 0, max_film_side);
    h.scene.camera = h.camera;
    apply_resolution(h.scene.camera, width, height);
    RenderParams params;
    params.spp = spp > 0 ? spp : h.camera.spp;
    params.threads = worker_threads(threads);
    return params;
}

py::array film_array(const Film& film, bool one_channel) {
    const auto h = static_cast<py::ssize_t>(film.height), w = static_cast<py::ssize_t>(film.width);
    if (one_channel) {
        py::array_t<float> a({h, w});
        float* out = a.mutable_data();
        for (size_t i = 0; i < film.pixels.size(); ++i) out[i] = film.pixels[i].x;
        return a;
    }
    py::array_t<float> a({h, w, py::ssize_t(3)});
    static_assert(sizeof(vec3) == 3 * sizeof(float));
    if (!film.pixels.empty())
        std::memcpy(a.mutable_data(), film.pixels.data(), film.pixels.size() * sizeof(vec3));
    return a;
}

py::array render(SceneHandle& h, int spp, int threads, const std::string& path,
                 const std::string& aov, int width, int height, uint32_t seed) {
    if (path != "packet" && path != "scalar")
        throw BadArgument(join("path: unknown renderer \"", path, "\" (use packet or scalar)"));
    RenderParams params;
    Aov kind = Aov::color;
    if (!parse_aov(aov, kind))
        throw BadArgument(
            join("aov: unknown output \"", aov, "\" (use color, normal, depth or bvh-cost)"));
    Film film;
    {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(h.mutex);
        params = prepare(h, spp, threads, width, height);
        params.aov = kind;
        params.seed = seed;
        KeepFloatModes keep;
        RenderResult r = path == "scalar" ? render_scalar(h.scene, h.accel, params)
                                          : render_packet(h.scene, h.accel, params);
        // as the command line writes a PFM: colour in the report's look is clamped (the
        // report's tone mapping), AOVs are raw
        film = kind == Aov::color && h.scene.tonemap == Tonemap::report
                   ? hue_preserving_clamp(std::move(r.film))
                   : std::move(r.film);
    }
    return film_array(film, kind == Aov::depth || kind == Aov::bvh_cost);
}

py::dict compare(SceneHandle& h, int spp, int threads, int width, int height, int repeats,
                 double tolerance, size_t id_allowance) {
    check_range("repeats", repeats, 1, 100);
    if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
        throw BadArgument("tolerance: must be a finite number >= 0");
    py::dict d;
    RenderParams params;
    RenderResult scalar, packet;
    std::vector<double> scalar_s, packet_s;
    ImageDiff diff;
    size_t ids = 0;
    {
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(h.mutex);
        params = prepare(h, spp, threads, width, height);
        KeepFloatModes keep;
        // as `raylane compare` times: an untimed 1-spp render per path, then the paths in turn
        RenderParams warm = params;
        warm.spp = 1;
        (void)render_scalar(h.scene, h.accel, warm);
        (void)render_packet(h.scene, h.accel, warm);
        for (int r = 0; r < repeats; ++r) {
            RenderResult a = render_scalar(h.scene, h.accel, params);
            RenderResult b = render_packet(h.scene, h.accel, params);
            scalar_s.push_back(a.stats.seconds), packet_s.push_back(b.stats.seconds);
            if (r == 0) scalar = std::move(a), packet = std::move(b);
        }
        diff = diff_images(scalar.film, packet.film);
        ids = primary_id_mismatches(h.scene, h.accel);
    }
    const double scalar_ms = 1000.0 * median(scalar_s), packet_ms = 1000.0 * median(packet_s);
    const bool agree = diff.max_abs <= tolerance && ids <= id_allowance &&
                       scalar.stats.shadow_rays == packet.stats.shadow_rays &&
                       scalar.stats.bad_samples() == 0 && packet.stats.bad_samples() == 0;
    d["width"] = h.scene.camera.width;
    d["height"] = h.scene.camera.height;
    d["spp"] = params.spp;
    d["repeats"] = repeats;
    d["isa"] = isa_name(active_isa());
    d["packet_width"] = isa_width(active_isa());
    d["scalar_ms"] = scalar_ms;
    d["packet_ms"] = packet_ms;
    d["speedup"] = scalar_ms / packet_ms;
    d["max_abs_diff"] = diff.max_abs;
    d["mean_abs_diff"] = diff.mean_abs;
    d["rmse"] = diff.rmse;
    d["psnr_db"] = diff.psnr_db;
    d["pixels_over_1_255"] = diff.pixels_over_8bit;
    d["pixels"] = scalar.film.pixels.size();
    d["hit_id_mismatches"] = ids;
    d["scalar_nan_samples"] = scalar.stats.nan_samples;
    d["scalar_inf_samples"] = scalar.stats.inf_samples;
    d["packet_nan_samples"] = packet.stats.nan_samples;
    d["packet_inf_samples"] = packet.stats.inf_samples;
    d["scalar_shadow_rays"] = scalar.stats.shadow_rays;
    d["packet_shadow_rays"] = packet.stats.shadow_rays;
    d["tolerance"] = tolerance;
    d["id_allowance"] = id_allowance;
    d["agree"] = agree;
    return d;
}

py::dict bvh_dict(const BvhStats& s) {
    py::dict d;
    d["nodes"] = s.nodes;
    d["leaves"] = s.leaves;
    d["max_leaf_depth"] = s.max_leaf_depth;
    d["mean_leaf_depth"] = s.mean_leaf_depth;
    d["sah_cost"] = s.sah_cost;
    d["bytes"] = s.bytes;
    return d;
}

py::dict info(const SceneHandle& h) {
    const SceneData& s = h.scene;
    const Camera& c = h.camera;
    py::dict d, camera, counts;
    d["source"] = s.source;
    camera["width"] = c.width;
    camera["height"] = c.height;
    camera["spp"] = c.spp;
    camera["fov_axis"] = c.fov_axis == FovAxis::vertical ? "vertical" : "horizontal";
    camera["fov_deg"] = c.fov_deg;
    d["camera"] = camera;
    d["objects"] = s.objects.size();
    d["spheres"] = s.spheres.size();
    d["boxes"] = s.boxes.size();
    d["cylinders"] = s.cylinders.size();
    d["planes"] = s.planes.size();
    d["single_triangles"] = s.triangles.size();
    d["materials"] = s.materials.size();
    d["lights"] = s.lights.size();
    d["textures"] = s.textures.size();
    d["features"] = feature_names(scene_features(s));
    d["triangles"] = count_triangles(s);
    py::list meshes;
    size_t total = 0;
    for (size_t i = 0; i < h.accel.meshes.size(); ++i) {
        const MeshAccel& m = h.accel.meshes[i];
        const size_t vert_bytes = m.verts.size() * sizeof(TriangleVerts);
        const BvhStats b = compute_stats(m.bvh);
        const WideStats w = compute_wide_stats(m.wide);
        py::dict md, wd;
        md["name"] = s.meshes[i].name;
        md["triangles"] = m.verts.size();
        md["dropped_triangles"] = s.meshes[i].dropped_triangles;
        md["binary"] = bvh_dict(b);
        md["binary_bytes_with_vertices"] = b.bytes + vert_bytes;
        wd["nodes"] = w.nodes;
        wd["leaves"] = w.leaves;
        wd["mean_children"] = w.mean_children;
        wd["triangles_per_leaf"] = w.leaves ? double(w.prims) / double(w.leaves) : 0.0;
        wd["bytes"] = w.bytes;
        md["wide"] = wd;
        md["wide_bytes_with_ids"] = w.bytes + m.bvh.prim_ids.size() * sizeof(uint32_t);
        meshes.append(md);
        total += b.bytes + vert_bytes + w.bytes;
    }
    d["meshes"] = meshes;
    const BvhStats top = compute_stats(h.accel.top);
    d["top_level"] = bvh_dict(top);
    total += top.bytes;
    d["memory_bytes"] = total;
    d["memory_mib"] = double(total) / (1024.0 * 1024.0);
    d["load_ms"] = h.load_ms;
    d["build_ms"] = h.build_ms;
    d["build"] = "median split";
    BuildPhases sum;  // the meshes' builds, phase by phase (ms)
    for (const MeshAccel& m : h.accel.meshes) sum += m.phases;
    py::dict phases;
    phases["centroids"] = sum.centroids;
    phases["sorts"] = sum.sorts;
    phases["splits"] = sum.splits;
    phases["vertices"] = sum.vertices;
    phases["boxes"] = sum.boxes;
    phases["collapse"] = sum.collapse;
    d["build_phases_ms"] = phases;
    return d;
}

}  // namespace

void add_scene(py::module_& m) {
    py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(
        m, "Scene", "A scene loaded by raylane.load_scene, with its BVHs (built once, at load).")
        .def("render", &render, py::arg("spp") = 0, py::arg("threads") = 0,
             py::arg("path") = "packet", py::arg("aov") = "color", py::arg("width") = 0,
             py::arg("height") = 0, py::arg("seed") = 0,
             "Renders the scene; returns float32 linear values, (H, W, 3) for color and normal, "
             "(H, W) for depth and bvh-cost, row 0 at the top: the pixels `raylane render -o "
             "FILE.pfm` writes with the same options (0 = the scene's own value).")
        .def("compare", &compare, py::arg("spp") = 0, py::arg("threads") = 0, py::arg("width") = 0,
             py::arg("height") = 0, py::arg("repeats") = 3, py::arg("tolerance") = 2e-3,
             py::arg("id_allowance") = 0,
             "Renders with both paths, as `raylane compare` does; returns its figures as a dict.")
        .def("info", &info,
             "The figures `raylane info` prints (scene contents, BVH statistics, memory, load "
             "and build time) as a dict.")
        .def_property_readonly("source", [](const SceneHandle& h) { return h.scene.source; })
        .def_property_readonly("width", [](const SceneHandle& h) { return h.camera.width; })
        .def_property_readonly("height", [](const SceneHandle& h) { return h.camera.height; })
        .def_property_readonly("spp", [](const SceneHandle& h) { return h.camera.spp; })
        .def("__repr__", [](const SceneHandle& h) {
            std::string r = "<raylane.Scene ";
            r.append(h.scene.source).append(" ").append(std::to_string(h.camera.width));
            r.append("x").append(std::to_string(h.camera.height)).append(">");
            return r;
        });
    m.def("load_scene", &load, py::arg("path"),
          "Loads a JSON scene or a model file (.obj, .ply: the model's own scene) as `raylane "
          "render` does; models named by a scene are looked up beside it, then on "
          "RAYLANE_MODEL_PATH.");
}

}  // namespace raylane::python
