// accel: the binned SAH build, a comparison option beside the report's median split (chosen with
// BuildParams::method; never the default). Same output as the median build: 32-byte nodes
// flattened depth-first, the first child next to its parent and holding the lower centroids
// along the node's axis, primitives in leaf order.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "accel/bvh.h"

namespace raylane {
namespace {

constexpr int bins = 16;
/// A node visit costs three triangle tests: leaves of about three triangles, so the tree takes
/// the median split's memory (61 bytes per triangle on the dragon). With a cost of 1 the leaves
/// hold 1.8 triangles and the dragon takes 75 bytes per triangle for no faster traversal.
constexpr float node_cost = 3.0f;
/// From this depth on the builder halves at the median: a depth of at most 31 + 32 levels for
/// fewer than 2^32 primitives, inside the traversal's stack.
constexpr int sah_depth_limit = 31;
static_assert(sah_depth_limit + 32 <= traversal_stack_size);

/// The bin of centroid coordinate c: (c - lo) * scale clamped to [0, bins - 1] in float, so no
/// value (NaN included: bin 0) reaches the int conversion out of range.
int bin_of(float c, float lo, float scale) {
    const float f = (c - lo) * scale;
    return f >= float(bins - 1) ? bins - 1 : (f > 0.0f ? static_cast<int>(f) : 0);
}

float half_area(const Aabb& b) {
    const vec3 d = b.hi - b.lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

/// What find_split chose for a node.
enum class Split { none, leaf, split };

struct SahBuilder {
    std::span<const Aabb> boxes;
    std::vector<vec3> centroids;
    std::vector<uint32_t, OverwriteAllocator<uint32_t>>& ids;
    std::vector<BvhNode, OverwriteAllocator<BvhNode>>& nodes;
    uint32_t max_leaf;

    /// Emits the node over ids[first, last) and its subtree; returns the node's index.
    uint32_t build(uint32_t first, uint32_t last, int depth) {
        const uint32_t index = static_cast<uint32_t>(nodes.size());
        nodes.push_back(BvhNode{});
        Aabb box, cbox;
        for (uint32_t i = first; i < last; ++i) {
            box.grow(boxes[ids[i]]);
            cbox.grow(centroids[ids[i]]);
        }
        for (int k = 0; k < 3; ++k) {
            nodes[index].lo[k] = box.lo[k];
            nodes[index].hi[k] = box.hi[k];
        }
        const uint32_t n = last - first;
        auto make_leaf = [&] {
            nodes[index].index = first;
            nodes[index].count = static_cast<uint16_t>(n);
            return index;
        };
        if (n == 1) return make_leaf();
        int axis = 0;
        uint32_t mid = first;
        const Split split =
            depth < sah_depth_limit ? find_split(first, last, box, cbox, axis, mid) : Split::none;
        if (split == Split::leaf || (split == Split::none && n <= max_leaf)) return make_leaf();
        if (split == Split::none) {
            // the median split on the longest centroid axis: equal halves, bounded depth
            const vec3 extent = cbox.hi - cbox.lo;
            axis =
                extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
            mid = first + n / 2;
            // a strict weak order even for NaN centroids (overflowed bounds): NaN sorts last
            auto key = [&](uint32_t id) {
                const float c = centroids[id][axis];
                return std::isnan(c) ? std::numeric_limits<float>::infinity() : c;
            };
            std::nth_element(ids.begin() + first, ids.begin() + mid, ids.begin() + last,
                             [&](uint32_t a, uint32_t b) {
                                 const float ca = key(a), cb = key(b);
                                 return ca < cb || (ca == cb && a < b);
                             });
        }
        nodes[index].axis = static_cast<uint16_t>(axis);
        build(first, mid, depth + 1);
        const uint32_t second = build(mid, last, depth + 1);
        nodes[index].index = second;
        return index;
    }

    /// The cheapest binned split over the three axes (node_cost per node visit, 1 per primitive
    /// test, areas relative to the node's): `split` with ids partitioned at mid, `leaf` when the
    /// node may be a leaf (n <= max_leaf) and that is cheaper, `none` when no bin boundary
    /// separates the centroids.
    Split find_split(uint32_t first, uint32_t last, const Aabb& box, const Aabb& cbox, int& axis,
                     uint32_t& mid) {
        const uint32_t n = last - first;
        float best = std::numeric_limits<float>::infinity();
        int best_axis = -1, best_bin = 0;
        for (int k = 0; k < 3; ++k) {
            const float lo = cbox.lo[k], extent = cbox.hi[k] - cbox.lo[k];
            const float scale = bins / extent;
            if (!(extent > 0.0f) || !std::isfinite(extent) || !std::isfinite(scale)) continue;
            std::array<Aabb, bins> bin_box{};
            std::array<uint32_t, bins> bin_count{};
            for (uint32_t i = first; i < last; ++i) {
                const int b = bin_of(centroids[ids[i]][k], lo, scale);
                bin_box[b].grow(boxes[ids[i]]);
                ++bin_count[b];
            }
            // right-to-left sweep: area x count of bins b+1 .. bins-1
            std::array<float, bins> right_cost{};
            Aabb acc;
            uint32_t count = 0;
            for (int b = bins - 1; b > 0; --b) {
                acc.grow(bin_box[b]);
                count += bin_count[b];
                right_cost[b - 1] = count ? half_area(acc) * static_cast<float>(count) : 0.0f;
            }
            acc = Aabb{};
            count = 0;
            for (int b = 0; b < bins - 1; ++b) {
                acc.grow(bin_box[b]);
                count += bin_count[b];
                if (count == 0 || count == n) continue;
                const float cost = half_area(acc) * static_cast<float>(count) + right_cost[b];
                if (cost < best) best = cost, best_axis = k, best_bin = b;
            }
        }
        if (best_axis < 0) return Split::none;
        const float area = half_area(box);
        const float split_cost = node_cost + (area > 0.0f ? best / area : static_cast<float>(n));
        if (n <= max_leaf && static_cast<float>(n) <= split_cost) return Split::leaf;
        axis = best_axis;
        const float lo = cbox.lo[axis], scale = bins / (cbox.hi[axis] - cbox.lo[axis]);
        const auto split = std::partition(
            ids.begin() + first, ids.begin() + last,
            [&](uint32_t id) { return bin_of(centroids[id][axis], lo, scale) <= best_bin; });
        mid = static_cast<uint32_t>(split - ids.begin());
        return mid != first && mid != last ? Split::split : Split::none;
    }
};

}  // namespace

Bvh build_bvh_sah(std::span<const Aabb> prim_bounds, const BuildParams& params) {
    Bvh bvh;
    if (prim_bounds.empty()) return bvh;
    const size_t n = prim_bounds.size();
    bvh.prim_ids.resize(n);
    for (size_t i = 0; i < n; ++i) bvh.prim_ids[i] = static_cast<uint32_t>(i);
    SahBuilder b{prim_bounds, std::vector<vec3>(n), bvh.prim_ids, bvh.nodes,
                 static_cast<uint32_t>(std::clamp(params.max_leaf_size, 1, 65535))};
    for (size_t i = 0; i < n; ++i) b.centroids[i] = 0.5f * (prim_bounds[i].lo + prim_bounds[i].hi);
    bvh.nodes.reserve(2 * n);
    b.build(0, static_cast<uint32_t>(n), 0);
    return bvh;
}

MeshAccel build_mesh_accel_sah(const MeshData& mesh, const BuildParams& params) {
    MeshAccel accel;
    std::vector<Aabb> boxes(mesh.tris.size());
    for (size_t i = 0; i < boxes.size(); ++i)
        for (int c = 0; c < 3; ++c) boxes[i].grow(mesh.positions[mesh.tris[i][c]]);
    accel.bvh = build_bvh_sah(boxes, params);
    accel.verts.reserve(boxes.size());
    for (uint32_t id : accel.bvh.prim_ids) {
        const uvec3 t = mesh.tris[id];
        accel.verts.push_back({mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]});
    }
    accel.wide = collapse_to_wide(accel.bvh);
    pack_leaf_triangles(accel.wide, accel.verts);
    return accel;
}

}  // namespace raylane
