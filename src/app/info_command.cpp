// app: `raylane info SCENE`: scene contents, BVH statistics, memory and build time.
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "core/isa.h"
#include "scene/camera_path.h"
#include "scene/features.h"

namespace raylane {
namespace {

void print_bvh(const char* label, const BvhStats& s, size_t triangles, size_t extra_bytes) {
    std::printf("%-10s %zu nodes, %zu leaves, leaf depth max %d mean %.1f, SAH cost %.1f\n", label,
                s.nodes, s.leaves, s.max_leaf_depth, s.mean_leaf_depth, s.sah_cost);
    const size_t bytes = s.bytes + extra_bytes;
    if (triangles > 0)
        std::printf("%-10s %.1f bytes per triangle (nodes, ids, vertices), %.2f MiB\n", "",
                    double(bytes) / double(triangles), double(bytes) / (1024.0 * 1024.0));
}

/// The packet path's wide tree of a mesh; `shared_bytes` are the primitive ids both trees read.
void print_wide(const WideStats& s, size_t triangles, size_t shared_bytes) {
    std::printf(
        "%-10s wide tree (packet path): %zu nodes, %.2f children per node, %zu leaves, "
        "%.2f triangles per leaf\n",
        "", s.nodes, s.mean_children, s.leaves,
        s.leaves ? double(s.prims) / double(s.leaves) : 0.0);
    const size_t bytes = s.bytes + shared_bytes;
    if (triangles > 0)
        std::printf("%-10s %.1f bytes per triangle (wide nodes, leaf triangles, ids), %.2f MiB\n",
                    "", double(bytes) / double(triangles), double(bytes) / (1024.0 * 1024.0));
}

int run_info(const std::string& path, const std::string& bvh) {
    const double t_load = now_seconds();
    const SceneData scene = load_command_scene(path);
    const double load_ms = elapsed_ms(t_load);
    const double t_build = now_seconds();
    const Accel accel = build_accel(scene, build_params(bvh));
    const double build_ms = elapsed_ms(t_build);

    const Camera& c = scene.camera;
    std::printf("scene      %s\n", scene.source.c_str());
    std::printf("camera     %dx%d, %d spp, %s fov %.1f deg\n", c.width, c.height, c.spp,
                c.fov_axis == FovAxis::vertical ? "vertical" : "horizontal", double(c.fov_deg));
    if (const int frames = frame_count(scene.camera_path); frames > 1) {
        std::printf("animation  %d frames (0..%d), %s\n", frames, frames - 1,
                    scene.camera_path.turntable_frames > 0 ? "turntable" : "camera path");
    }
    std::printf(
        "objects    %zu (%zu spheres, %zu boxes, %zu cylinders, %zu planes, %zu triangles, "
        "%zu meshes)\n",
        scene.objects.size(), scene.spheres.size(), scene.boxes.size(), scene.cylinders.size(),
        scene.planes.size(), scene.triangles.size(), scene.meshes.size());
    std::printf("materials  %zu, lights %zu, textures %zu\n", scene.materials.size(),
                scene.lights.size(), scene.textures.size());
    std::printf("features   %s\n", feature_names(scene_features(scene)).c_str());
    std::printf("triangles  %zu\n", count_triangles(scene));
    size_t total = 0;
    for (size_t i = 0; i < accel.meshes.size(); ++i) {
        const MeshAccel& m = accel.meshes[i];
        const std::string label = "mesh " + std::to_string(i);
        std::printf("%-10s %s: %zu triangles", label.c_str(), scene.meshes[i].name.c_str(),
                    m.verts.size());
        if (scene.meshes[i].dropped_triangles > 0)
            std::printf(" (%zu zero-area faces dropped)", scene.meshes[i].dropped_triangles);
        std::printf("\n");
        const size_t vert_bytes = m.verts.size() * sizeof(TriangleVerts);
        const BvhStats s = compute_stats(m.bvh);
        std::printf("%-10s binary tree (scalar path):\n", "");
        print_bvh("", s, m.verts.size(), vert_bytes);
        const WideStats w = compute_wide_stats(m.wide);
        print_wide(w, m.verts.size(), m.bvh.prim_ids.size() * sizeof(uint32_t));
        total += s.bytes + vert_bytes + w.bytes;
    }
    const BvhStats top = compute_stats(accel.top);
    print_bvh("top level", top, 0, 0);
    total += top.bytes;
    std::printf("memory     %.2f MiB of BVH and triangle data\n",
                double(total) / (1024.0 * 1024.0));
    std::printf("time       load %.1f ms, build %.1f ms (%s)\n", load_ms, build_ms,
                bvh == "sah" ? "binned SAH" : "median split");
    if (bvh != "sah" && !accel.meshes.empty()) {
        BuildPhases sum;  // the meshes' median-split builds, phase by phase
        for (const MeshAccel& m : accel.meshes) sum += m.phases;
        std::printf(
            "%-10s mesh builds: centroids %.1f, sorts %.1f, splits %.1f, vertices %.1f, boxes "
            "%.1f ms; wide trees collapsed and leaves packed in %.1f ms\n",
            "", sum.centroids, sum.sorts, sum.splits, sum.vertices, sum.boxes, sum.collapse);
    }
    std::printf("isa        %s\n", isa_summary().c_str());
    return 0;
}

}  // namespace

void add_info_command(CLI::App& app, int& exit_code) {
    auto path = std::make_shared<std::string>();
    auto bvh = std::make_shared<std::string>("median");
    CLI::App* cmd = app.add_subcommand("info", "print scene and BVH statistics");
    cmd->add_option("scene", *path,
                    "scene JSON file or model (.obj, .ply; default: the built-in scene)")
        ->check(existing_scene_file());
    add_bvh_option(cmd, *bvh);
    cmd->callback([path, bvh, &exit_code] { exit_code = run_info(*path, *bvh); });
}

}  // namespace raylane
