// python: raylane.load_scene and Scene: render (the pixels `raylane render -o FILE.pfm` writes),
// compare (the figures of `raylane compare`) and info (those of `raylane info`), over the
// library's raylane::Scene (raylane/scene.h).
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "python/bindings.h"
#include "raylane/scene.h"

namespace raylane::python {
namespace {

Scene load(const std::string& path) {
    require_file(path);
    std::optional<Scene> scene;
    {
        py::gil_scoped_release release;
        scene = Scene::load(path);
    }
    for (const std::string& w : scene->warnings())
        std::fprintf(stderr, "raylane: warning: %s\n", w.c_str());
    return std::move(*scene);
}

/// The image as a NumPy array that owns its pixels (no copy): (H, W, 3) or (H, W).
py::array image_array(Image image) {
    auto* pixels = new std::vector<float>(std::move(image.pixels));
    py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    std::vector<py::ssize_t> shape = {image.height, image.width};
    if (image.channels > 1) shape.push_back(image.channels);
    return py::array_t<float>(shape, pixels->data(), owner);
}

py::array render(const Scene& scene, int spp, int threads, const std::string& path,
                 const std::string& aov, int width, int height, uint32_t seed) {
    RenderSettings settings;
    if (path == "scalar")
        settings.path = TracePath::scalar;
    else if (path != "packet")
        throw BadArgument(join("path: unknown renderer \"", path, "\" (use packet or scalar)"));
    if (aov == "normal")
        settings.image = ImageKind::normal;
    else if (aov == "depth")
        settings.image = ImageKind::depth;
    else if (aov == "bvh-cost")
        settings.image = ImageKind::bvh_cost;
    else if (aov != "color")
        throw BadArgument(
            join("aov: unknown output \"", aov, "\" (use color, normal, depth or bvh-cost)"));
    settings.spp = spp, settings.threads = threads, settings.width = width;
    settings.height = height, settings.seed = seed;
    Image image;
    {
        py::gil_scoped_release release;
        image = scene.render(settings);
    }
    return image_array(std::move(image));
}

py::dict compare(const Scene& scene, int spp, int threads, int width, int height, int repeats,
                 double tolerance, size_t id_allowance) {
    CompareSettings settings;
    settings.spp = spp, settings.threads = threads, settings.width = width;
    settings.height = height, settings.repeats = repeats, settings.tolerance = tolerance;
    settings.id_allowance = id_allowance;
    Comparison c;
    {
        py::gil_scoped_release release;
        c = scene.compare(settings);
    }
    py::dict d;
    d["width"] = c.width;
    d["height"] = c.height;
    d["spp"] = c.spp;
    d["repeats"] = c.repeats;
    d["isa"] = c.instruction_set;
    d["packet_width"] = c.packet_width;
    d["scalar_ms"] = c.scalar_ms;
    d["packet_ms"] = c.packet_ms;
    d["speedup"] = c.scalar_ms / c.packet_ms;
    d["max_abs_diff"] = c.max_abs_diff;
    d["mean_abs_diff"] = c.mean_abs_diff;
    d["rmse"] = c.rmse;
    d["psnr_db"] = c.psnr_db;
    d["pixels_over_1_255"] = c.pixels_over_1_255;
    d["pixels"] = c.pixels;
    d["hit_id_mismatches"] = c.hit_id_mismatches;
    d["scalar_nan_samples"] = c.scalar_nan_samples;
    d["scalar_inf_samples"] = c.scalar_inf_samples;
    d["packet_nan_samples"] = c.packet_nan_samples;
    d["packet_inf_samples"] = c.packet_inf_samples;
    d["scalar_shadow_rays"] = c.scalar_shadow_rays;
    d["packet_shadow_rays"] = c.packet_shadow_rays;
    d["tolerance"] = tolerance;
    d["id_allowance"] = id_allowance;
    d["agree"] = c.agree;
    return d;
}

py::dict tree_dict(const TreeStats& s) {
    py::dict d;
    d["nodes"] = s.nodes;
    d["leaves"] = s.leaves;
    d["max_leaf_depth"] = s.max_leaf_depth;
    d["mean_leaf_depth"] = s.mean_leaf_depth;
    d["sah_cost"] = s.sah_cost;
    d["bytes"] = s.bytes;
    return d;
}

py::dict info(const Scene& scene) {
    const SceneStats s = scene.stats();
    py::dict d, camera;
    d["source"] = s.source;
    camera["width"] = s.width;
    camera["height"] = s.height;
    camera["spp"] = s.spp;
    camera["fov_axis"] = s.fov_vertical ? "vertical" : "horizontal";
    camera["fov_deg"] = s.fov_deg;
    d["camera"] = camera;
    d["objects"] = s.objects;
    d["spheres"] = s.spheres;
    d["boxes"] = s.boxes;
    d["cylinders"] = s.cylinders;
    d["planes"] = s.planes;
    d["single_triangles"] = s.single_triangles;
    d["materials"] = s.materials;
    d["lights"] = s.lights;
    d["textures"] = s.textures;
    d["features"] = s.features;
    d["triangles"] = s.triangles;
    py::list meshes;
    for (const MeshStats& m : s.meshes) {
        py::dict md, wd;
        md["name"] = m.name;
        md["triangles"] = m.triangles;
        md["dropped_triangles"] = m.dropped_triangles;
        md["binary"] = tree_dict(m.binary);
        md["binary_bytes_with_vertices"] = m.binary_bytes_with_vertices;
        wd["nodes"] = m.wide.nodes;
        wd["leaves"] = m.wide.leaves;
        wd["mean_children"] = m.wide.mean_children;
        wd["triangles_per_leaf"] = m.wide.triangles_per_leaf;
        wd["bytes"] = m.wide.bytes;
        md["wide"] = wd;
        md["wide_bytes_with_ids"] = m.wide_bytes_with_ids;
        meshes.append(md);
    }
    d["meshes"] = meshes;
    d["top_level"] = tree_dict(s.top_level);
    d["memory_bytes"] = s.memory_bytes;
    d["memory_mib"] = double(s.memory_bytes) / (1024.0 * 1024.0);
    d["load_ms"] = s.load_ms;
    d["build_ms"] = s.build_ms;
    d["build"] = s.build == BvhBuild::sah ? "binned SAH" : "median split";
    py::dict phases;
    phases["centroids"] = s.build_phases_ms.centroids;
    phases["sorts"] = s.build_phases_ms.sorts;
    phases["splits"] = s.build_phases_ms.splits;
    phases["vertices"] = s.build_phases_ms.vertices;
    phases["boxes"] = s.build_phases_ms.boxes;
    phases["collapse"] = s.build_phases_ms.collapse;
    d["build_phases_ms"] = phases;
    return d;
}

}  // namespace

void add_scene(py::module_& m) {
    py::class_<Scene>(m, "Scene",
                      "A scene loaded by raylane.load_scene, with its BVHs (built once, at load).")
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
        .def_property_readonly("source", &Scene::source, "the file the scene was loaded from")
        .def_property_readonly("width", &Scene::width, "the scene's own image width")
        .def_property_readonly("height", &Scene::height, "the scene's own image height")
        .def_property_readonly("spp", &Scene::spp, "the scene's own samples per pixel")
        .def("__repr__", [](const Scene& s) {
            return join("<raylane.Scene ", s.source(), " ", std::to_string(s.width()), "x",
                        std::to_string(s.height()), ">");
        });
    m.def("load_scene", &load, py::arg("path"),
          "Loads a JSON scene or a model file (.obj, .ply: the model's own scene) as `raylane "
          "render` does; models named by a scene are looked up beside it, then on "
          "RAYLANE_MODEL_PATH.");
}

}  // namespace raylane::python
