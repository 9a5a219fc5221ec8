// accel: the BVH invariant checker and the statistics `raylane info` prints.
#include <string>
#include <utility>

#include "accel/bvh.h"

namespace raylane {

std::string check_bvh(const Bvh& bvh, std::span<const Aabb> prim_bounds, int max_leaf_size) {
    const size_t n = prim_bounds.size();
    if (bvh.nodes.empty()) return n == 0 ? "" : "no nodes for a non-empty primitive set";
    if (bvh.prim_ids.size() != n) return "prim_ids has the wrong size";
    std::vector<int> seen(n, 0);
    // (node, parent) pairs, depth first
    std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 0xffffffffu}};
    size_t visited = 0;
    while (!stack.empty()) {
        auto [i, parent] = stack.back();
        stack.pop_back();
        if (i >= bvh.nodes.size()) return "node index " + std::to_string(i) + " out of range";
        if (++visited > bvh.nodes.size()) return "a node is reachable twice";
        const BvhNode& node = bvh.nodes[i];
        if (parent != 0xffffffffu && !bvh.nodes[parent].bounds().contains(node.bounds()))
            return "node " + std::to_string(i) + " is not inside its parent";
        if (node.is_leaf()) {
            if (node.count > max_leaf_size)
                return "leaf " + std::to_string(i) + " holds " + std::to_string(node.count);
            if (size_t(node.index) + node.count > n) return "leaf range out of bounds";
            for (uint32_t k = node.index; k < node.index + node.count; ++k) {
                uint32_t p = bvh.prim_ids[k];
                if (p >= n) return "primitive id out of range";
                if (++seen[p] != 1) return "primitive " + std::to_string(p) + " in two leaves";
                if (!node.bounds().contains(prim_bounds[p]))
                    return "leaf " + std::to_string(i) + " does not contain primitive " +
                           std::to_string(p);
            }
        } else {
            if (node.index <= i + 1 || node.index >= bvh.nodes.size())
                return "interior node " + std::to_string(i) + " has a bad second child";
            stack.push_back({node.index, i});
            stack.push_back({i + 1, i});
        }
    }
    if (visited != bvh.nodes.size()) return "unreachable nodes";
    for (size_t p = 0; p < n; ++p)
        if (seen[p] != 1) return "primitive " + std::to_string(p) + " is in no leaf";
    return "";
}

BvhStats compute_stats(const Bvh& bvh) {
    BvhStats s;
    s.nodes = bvh.nodes.size();
    s.prims = bvh.prim_ids.size();
    s.bytes = bvh.nodes.size() * sizeof(BvhNode) + bvh.prim_ids.size() * sizeof(uint32_t);
    if (bvh.nodes.empty()) return s;
    const double root_area = bvh.nodes[0].bounds().surface_area();
    double depth_sum = 0.0;
    std::vector<std::pair<uint32_t, int>> stack{{0u, 0}};
    while (!stack.empty()) {
        auto [i, depth] = stack.back();
        stack.pop_back();
        const BvhNode& node = bvh.nodes[i];
        const double rel = root_area > 0.0 ? node.bounds().surface_area() / root_area : 1.0;
        if (node.is_leaf()) {
            ++s.leaves;
            depth_sum += depth;
            s.max_leaf_depth = std::max(s.max_leaf_depth, depth);
            s.sah_cost += rel * node.count;
        } else {
            s.sah_cost += rel;
            stack.push_back({node.index, depth + 1});
            stack.push_back({i + 1, depth + 1});
        }
    }
    s.mean_leaf_depth = depth_sum / static_cast<double>(s.leaves);
    return s;
}

}  // namespace raylane
