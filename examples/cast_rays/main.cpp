// examples/cast_rays: an 8 x 8 grid of rays cast at a triangle mesh with raylane::Mesh: the
// triangle each ray hits first and how far away, then the same rays as shadow rays (occlusion).
//
//   cast_rays [MODEL]
//
// MODEL is an OBJ or PLY file, or the name of one in a folder on RAYLANE_MODEL_PATH (a list of
// folders separated by ':'); the default is bunny.ply. Exits 0, or 1 with Raylane's one-line
// message when the model cannot be found or read.
#include <raylane/raylane.h>  // the whole library: Mesh, Scene, instruction sets, Error

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {

constexpr int grid = 8;                    // rays per side of the grid
constexpr size_t ray_count = grid * grid;  // 64 rays
constexpr size_t row_floats = 6;           // a ray is one row: origin x, y, z, direction x, y, z
constexpr size_t row_bytes = row_floats * sizeof(float);

/// The axis-aligned box around the mesh's vertices: mesh.vertices() holds x, y, z of each.
void bounding_box(const raylane::Mesh& mesh, float lo[3], float hi[3]) {
    for (int k = 0; k < 3; ++k) {
        lo[k] = std::numeric_limits<float>::infinity();
        hi[k] = -std::numeric_limits<float>::infinity();
    }
    const float* v = mesh.vertices();
    for (size_t i = 0; i < mesh.vertex_count(); ++i) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], v[3 * i + size_t(k)]);
            hi[k] = std::max(hi[k], v[3 * i + size_t(k)]);
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        // find_model returns the name itself when it is a file, else the first folder on
        // RAYLANE_MODEL_PATH that holds it; it throws raylane::Error naming every folder
        // searched. Mesh::load would search the same way; asking first shows which file it is.
        const std::string path = raylane::find_model(argc > 1 ? argv[1] : "bunny.ply");
        const raylane::Mesh mesh = raylane::Mesh::load(path);  // reads it and builds its BVHs
        std::printf("%s: %zu vertices, %zu triangles, BVHs built in %.1f ms\n", path.c_str(),
                    mesh.vertex_count(), mesh.triangle_count(), mesh.build_ms());
        std::printf("packet path: %s, %d rays per packet (Raylane %s)\n",
                    raylane::instruction_set().c_str(), raylane::packet_width(),
                    raylane::version());

        float lo[3], hi[3];
        bounding_box(mesh, lo, hi);
        const float centre[3] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
        const float size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
        std::printf("bounding box: (%.3f, %.3f, %.3f) to (%.3f, %.3f, %.3f)\n", lo[0], lo[1], lo[2],
                    hi[0], hi[1], hi[2]);

        // The rays start at one eye in front of the box (on its +z side, which the Stanford
        // models face) and pass through the centres of an 8 x 8 grid of cells that spans the
        // box across x and y at the depth of its centre. Their directions have unit length, so
        // a hit's t is its distance from the eye in the model's units. The rays are the rows
        // of one array, as an (N, 6) NumPy array lays them out: Rays takes each ray's origin
        // and direction at a stride (24 bytes here) from two pointers into it.
        const float eye[3] = {centre[0], centre[1], hi[2] + 2 * size};
        std::vector<float> rays(ray_count * row_floats);
        for (int row = 0; row < grid; ++row) {      // row 0 at the top of the box
            for (int col = 0; col < grid; ++col) {  // column 0 at its left (-x)
                float* ray = &rays[(size_t(row) * grid + size_t(col)) * row_floats];
                const float target[3] = {lo[0] + (hi[0] - lo[0]) * (float(col) + 0.5f) / grid,
                                         hi[1] - (hi[1] - lo[1]) * (float(row) + 0.5f) / grid,
                                         centre[2]};
                float length = 0;
                for (int k = 0; k < 3; ++k) {
                    ray[k] = eye[k];
                    ray[3 + k] = target[k] - eye[k];
                    length += ray[3 + k] * ray[3 + k];
                }
                for (int k = 0; k < 3; ++k) ray[3 + k] /= std::sqrt(length);
            }
        }
        raylane::Rays batch;
        batch.count = ray_count;
        batch.origins = rays.data();
        batch.origin_stride = row_bytes;
        batch.directions = rays.data() + 3;
        batch.direction_stride = row_bytes;
        // t_max: each ray is traced over (0, t_max); the default is infinity

        // Closest hits. Hits names the arrays to fill, one entry per ray; an array left null
        // (here u, v and the normal) is not written. A miss is t = inf and triangle = -1.
        std::vector<float> t(ray_count);
        std::vector<int32_t> triangle(ray_count);
        raylane::Hits hits;
        hits.t = t.data();
        hits.triangle = triangle.data();
        mesh.intersect(batch, hits);  // the packet path on every core; QuerySettings chooses

        std::printf("\nclosest hits from (%.3f, %.3f, %.3f): the triangle, then the distance\n",
                    eye[0], eye[1], eye[2]);
        size_t hit_count = 0;
        for (int row = 0; row < grid; ++row) {
            for (int col = 0; col < grid; ++col) {  // the triangle each ray hits, . for a miss
                const size_t i = size_t(row) * grid + size_t(col);
                if (triangle[i] >= 0)
                    std::printf(" %6d", int(triangle[i]));
                else
                    std::printf(" %6s", ".");
                hit_count += triangle[i] >= 0;
            }
            std::printf("   ");
            for (int col = 0; col < grid; ++col) {  // how far along the ray; inf for a miss
                const size_t i = size_t(row) * grid + size_t(col);
                std::printf(" %5.3f", double(t[i]));
            }
            std::printf("\n");
        }
        std::printf("hits: %zu of %zu rays\n", hit_count, ray_count);

        // Occlusion: whether anything lies on each ray in (0, t_max), without finding the
        // closest hit, as shadow rays ask. occluded[i] is 1 or 0.
        std::vector<uint8_t> occluded(ray_count);
        mesh.occluded(batch, occluded.data());
        std::printf("\noccluded (# = blocked, . = clear)\n");
        size_t occluded_count = 0, disagreements = 0;
        for (int row = 0; row < grid; ++row) {
            for (int col = 0; col < grid; ++col) {
                const size_t i = size_t(row) * grid + size_t(col);
                std::printf(" %c", occluded[i] ? '#' : '.');
                occluded_count += occluded[i];
                disagreements += (occluded[i] != 0) != (triangle[i] >= 0);
            }
            std::printf("\n");
        }
        std::printf("occluded: %zu of %zu rays; %s\n", occluded_count, ray_count,
                    disagreements == 0 ? "the same rays as hit"
                                       : "NOT the rays that hit (a fault in the library)");
        return disagreements == 0 ? 0 : 1;
    } catch (const raylane::Error& e) {  // every call reports bad input as one line
        std::fprintf(stderr, "cast_rays: %s\n", e.what());
        return 1;
    }
}
