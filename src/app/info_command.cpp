// app: `raylane info SCENE`: scene contents, BVH statistics, memory and build time
// (raylane::Scene::stats of the public API).
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "core/isa.h"
#include "raylane/scene.h"

namespace raylane {
namespace {

/// A binary tree's shape; `bytes` are its nodes, ids and (for a mesh) vertices.
void print_bvh(const char* label, const TreeStats& s, size_t triangles, size_t bytes) {
    std::printf("%-10s %zu nodes, %zu leaves, leaf depth max %d mean %.1f, SAH cost %.1f\n", label,
                s.nodes, s.leaves, s.max_leaf_depth, s.mean_leaf_depth, s.sah_cost);
    if (triangles > 0)
        std::printf("%-10s %.1f bytes per triangle (nodes, ids, vertices), %.2f MiB\n", "",
                    double(bytes) / double(triangles), double(bytes) / (1024.0 * 1024.0));
}

/// The packet path's wide tree of a mesh; `bytes` with the primitive ids both trees read.
void print_wide(const WideTreeStats& s, size_t triangles, size_t bytes) {
    std::printf(
        "%-10s wide tree (packet path): %zu nodes, %.2f children per node, %zu leaves, "
        "%.2f triangles per leaf\n",
        "", s.nodes, s.mean_children, s.leaves, s.triangles_per_leaf);
    if (triangles > 0)
        std::printf("%-10s %.1f bytes per triangle (wide nodes, leaf triangles, ids), %.2f MiB\n",
                    "", double(bytes) / double(triangles), double(bytes) / (1024.0 * 1024.0));
}

int run_info(const std::string& path, const std::string& bvh) {
    const SceneStats s = load_command_scene(path, bvh).stats();
    std::printf("scene      %s\n", s.source.c_str());
    std::printf("camera     %dx%d, %d spp, %s fov %.1f deg\n", s.width, s.height, s.spp,
                s.fov_vertical ? "vertical" : "horizontal", s.fov_deg);
    if (s.frames > 1) {
        std::printf("animation  %d frames (0..%d), %s\n", s.frames, s.frames - 1,
                    s.turntable ? "turntable" : "camera path");
    }
    std::printf(
        "objects    %zu (%zu spheres, %zu boxes, %zu cylinders, %zu planes, %zu triangles, "
        "%zu meshes)\n",
        s.objects, s.spheres, s.boxes, s.cylinders, s.planes, s.single_triangles, s.meshes.size());
    std::printf("materials  %zu, lights %zu, textures %zu\n", s.materials, s.lights, s.textures);
    std::printf("features   %s\n", s.features.c_str());
    std::printf("triangles  %zu\n", s.triangles);
    for (size_t i = 0; i < s.meshes.size(); ++i) {
        const MeshStats& m = s.meshes[i];
        const std::string label = "mesh " + std::to_string(i);
        std::printf("%-10s %s: %zu triangles", label.c_str(), m.name.c_str(), m.triangles);
        if (m.dropped_triangles > 0)
            std::printf(" (%zu zero-area faces dropped)", m.dropped_triangles);
        std::printf("\n");
        std::printf("%-10s binary tree (scalar path):\n", "");
        print_bvh("", m.binary, m.triangles, m.binary_bytes_with_vertices);
        print_wide(m.wide, m.triangles, m.wide_bytes_with_ids);
    }
    print_bvh("top level", s.top_level, 0, 0);
    std::printf("memory     %.2f MiB of BVH and triangle data\n",
                double(s.memory_bytes) / (1024.0 * 1024.0));
    std::printf("time       load %.1f ms, build %.1f ms (%s)\n", s.load_ms, s.build_ms,
                s.build == BvhBuild::sah ? "binned SAH" : "median split");
    if (s.build == BvhBuild::median && !s.meshes.empty()) {
        const BuildPhaseTimes& p = s.build_phases_ms;  // the meshes' builds, phase by phase
        std::printf(
            "%-10s mesh builds: centroids %.1f, sorts %.1f, splits %.1f, vertices %.1f, boxes "
            "%.1f ms; wide trees collapsed and leaves packed in %.1f ms\n",
            "", p.centroids, p.sorts, p.splits, p.vertices, p.boxes, p.collapse);
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
