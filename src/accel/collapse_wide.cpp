// accel: the wide tree collapsed from a binary BVH, its invariant checker and its statistics
// (wide_bvh.h).
#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include "accel/bvh.h"
#include "accel/wide_bvh.h"
#include "core/triangle_area.h"

namespace raylane {
namespace {

constexpr float infinity_f = std::numeric_limits<float>::infinity();

/// A node's surface area in double, so boxes up to float's largest extent do not overflow.
double area(const BvhNode& node) {
    const double dx = double(node.hi[0]) - double(node.lo[0]);
    const double dy = double(node.hi[1]) - double(node.lo[1]);
    const double dz = double(node.hi[2]) - double(node.lo[2]);
    return dx * dy + dy * dz + dz * dx;
}

WideNode empty_node() {
    WideNode w;
    for (int k = 0; k < wide_arity; ++k) {
        for (int axis = 0; axis < 3; ++axis) {
            w.lo[axis][k] = infinity_f;
            w.hi[axis][k] = -infinity_f;
        }
        w.child[k] = 0;
        w.count[k] = 0;
    }
    return w;
}

/// Every binary node's primitives: a contiguous range of the leaf order (the subtree's leaves
/// are consecutive in depth-first order).
struct Subtrees {
    std::vector<uint32_t> first, count;
};

Subtrees subtree_ranges(const Bvh& bvh) {
    Subtrees s;
    s.first.resize(bvh.nodes.size());
    s.count.resize(bvh.nodes.size());
    for (size_t i = bvh.nodes.size(); i-- > 0;) {  // children after their parent
        const BvhNode& node = bvh.nodes[i];
        if (node.is_leaf()) {
            s.first[i] = node.index;
            s.count[i] = node.count;
        } else {
            s.first[i] = s.first[i + 1];
            s.count[i] = s.count[i + 1] + s.count[node.index];
        }
    }
    return s;
}

/// Whether binary node i becomes a leaf of the wide tree: a binary leaf, or a subtree of at most
/// wide_leaf_size primitives (its leaves merged).
bool wide_leaf(const Bvh& bvh, const Subtrees& sub, uint32_t i) {
    return bvh.nodes[i].is_leaf() || sub.count[i] <= wide_leaf_size;
}

/// The binary nodes a wide node over binary node `root` adopts as its children: root's two
/// children, then, while there is room, the interior child of largest area replaced by its
/// two children in its place (ties: the first in depth-first order). A leaf root is its own
/// only child.
int adopt_children(const Bvh& bvh, const Subtrees& sub, uint32_t root,
                   uint32_t (&slots)[wide_arity]) {
    const BvhNode& node = bvh.nodes[root];
    if (wide_leaf(bvh, sub, root)) {
        slots[0] = root;
        return 1;
    }
    int n = 2;
    slots[0] = root + 1;
    slots[1] = node.index;
    while (n < wide_arity) {
        int best = -1;
        double best_area = -1.0;
        for (int k = 0; k < n; ++k) {
            const BvhNode& c = bvh.nodes[slots[k]];
            if (!wide_leaf(bvh, sub, slots[k]) && area(c) > best_area) {
                best = k;
                best_area = area(c);
            }
        }
        if (best < 0) break;
        const uint32_t opened = slots[best];
        std::copy_backward(slots + best + 1, slots + n, slots + n + 1);
        slots[best] = opened + 1;
        slots[best + 1] = bvh.nodes[opened].index;
        ++n;
    }
    return n;
}

/// Appends the wide node over binary node `root` and, depth first, those of its interior
/// children; returns its index.
uint32_t collapse_node(const Bvh& bvh, const Subtrees& sub, uint32_t root, WideBvh& wide) {
    uint32_t slots[wide_arity];
    const int n = adopt_children(bvh, sub, root, slots);
    const auto at = static_cast<uint32_t>(wide.nodes.size());
    wide.nodes.push_back(empty_node());
    wide.nodes[at].children = static_cast<uint8_t>(n);
    for (int k = 0; k < n; ++k) {
        const BvhNode& c = bvh.nodes[slots[k]];
        for (int axis = 0; axis < 3; ++axis) {
            wide.nodes[at].lo[axis][k] = c.lo[axis];
            wide.nodes[at].hi[axis][k] = c.hi[axis];
        }
        if (wide_leaf(bvh, sub, slots[k])) {
            wide.nodes[at].child[k] = sub.first[slots[k]];
            wide.nodes[at].count[k] = static_cast<uint16_t>(sub.count[slots[k]]);
        } else {
            const uint32_t child = collapse_node(bvh, sub, slots[k], wide);  // may move the nodes
            wide.nodes[at].child[k] = child;
        }
    }
    return at;
}

bool box_inside(const WideNode& inner, int k, const WideNode& outer, int slot) {
    for (int axis = 0; axis < 3; ++axis) {
        if (!(inner.lo[axis][k] >= outer.lo[axis][slot] &&
              inner.hi[axis][k] <= outer.hi[axis][slot]))
            return false;
    }
    return true;
}

bool slot_empty(const WideNode& w, int k) {
    for (int axis = 0; axis < 3; ++axis) {
        if (w.lo[axis][k] != infinity_f || w.hi[axis][k] != -infinity_f) return false;
    }
    return w.count[k] == 0 && w.child[k] == 0;
}

}  // namespace

WideBvh collapse_to_wide(const Bvh& bvh) {
    WideBvh wide;
    if (bvh.nodes.empty()) return wide;
    // about one wide node per (arity - 1) binary interior nodes
    wide.nodes.reserve(bvh.nodes.size() / (2 * (wide_arity - 1)) + 1);
    collapse_node(bvh, subtree_ranges(bvh), 0, wide);
    return wide;
}

void pack_leaf_triangles(WideBvh& wide, std::span<const TriangleVerts> verts) {
    wide.tris.clear();
    if (wide.nodes.empty()) return;
    wide.tris.resize(9 * verts.size() + wide_tris_pad);
    float* out = wide.tris.data();
    for (const WideNode& w : wide.nodes) {
        for (int s = 0; s < w.children; ++s) {
            if (!w.is_leaf(s)) continue;
            const uint32_t first = w.child[s], n = w.count[s];
            float* group = out + 9 * size_t(first);
            for (uint32_t k = 0; k < n; ++k) {
                const TriangleVerts& tv = verts[first + k];
                vec3 v[3] = {tv.a, tv.b, tv.c};
                if (is_zero_area_triangle(tv.a, tv.b, tv.c))
                    v[0] = v[1] = v[2] = vec3(std::numeric_limits<float>::quiet_NaN());
                for (int c = 0; c < 9; ++c) group[c * n + k] = v[c / 3][c % 3];
            }
        }
    }
    std::fill(out + 9 * verts.size(), out + wide.tris.size(), 0.0f);
}

std::string check_wide_bvh(const WideBvh& wide, const Bvh& bvh) {
    if (bvh.nodes.empty()) return wide.nodes.empty() ? "" : "wide nodes for an empty tree";
    if (wide.nodes.empty()) return "no wide nodes for a non-empty tree";
    const size_t n = bvh.prim_ids.size();
    // the binary leaves' boundaries in leaf order, and which leaf starts where
    std::vector<uint16_t> leaf_at(n + 1, 0);  // a binary leaf's count at its first primitive
    for (const BvhNode& node : bvh.nodes) {
        if (!node.is_leaf()) continue;
        if (size_t(node.index) + node.count > n) return "binary leaf out of range";
        leaf_at[node.index] = node.count;
    }
    std::vector<std::pair<uint32_t, uint32_t>> ranges;  // the wide leaves: first, count
    std::vector<uint8_t> reached(wide.nodes.size(), 0);
    for (size_t i = 0; i < wide.nodes.size(); ++i) {
        const std::string at = "wide node " + std::to_string(i);
        if (i > 0 && !reached[i]) return at + " is not reached from the root";
        const WideNode& w = wide.nodes[i];
        if (w.children < 1 || w.children > wide_arity) return at + " has a bad child count";
        const bool root_over_leaf = i == 0 && w.children == 1 && w.is_leaf(0);
        if (w.children < 2 && !root_over_leaf) return at + " has one child";
        for (int k = w.children; k < wide_arity; ++k)
            if (!slot_empty(w, k)) return at + ": unused slot " + std::to_string(k) + " not empty";
        for (int k = 0; k < w.children; ++k) {
            if (w.is_leaf(k)) {
                ranges.push_back({w.child[k], w.count[k]});
                continue;
            }
            const uint32_t c = w.child[k];
            if (c <= i || c >= wide.nodes.size())
                return at + ": child " + std::to_string(c) + " out of order or range";
            if (reached[c]++) return "wide node " + std::to_string(c) + " is reached twice";
            const WideNode& cw = wide.nodes[c];
            for (int j = 0; j < cw.children; ++j)
                if (!box_inside(cw, j, w, k))
                    return "wide node " + std::to_string(c) + " is not inside its parent's slot";
        }
    }
    // the wide leaves tile the leaf order, each one binary leaf or consecutive binary leaves of
    // at most wide_leaf_size primitives in all
    std::sort(ranges.begin(), ranges.end());
    uint32_t next = 0;
    for (const auto& [first, count] : ranges) {
        const std::string leaf = "wide leaf at " + std::to_string(first);
        if (first != next) return leaf + ": primitives before it are in no leaf or in two";
        if (size_t(first) + count > n) return leaf + " is out of range";
        const bool one_leaf = leaf_at[first] == count;
        if (!one_leaf && count > wide_leaf_size) return leaf + " merges too many primitives";
        uint32_t p = first;
        for (; p < first + count; p += leaf_at[p])
            if (leaf_at[p] == 0) return leaf + " does not fall on binary leaves";
        if (p != first + count) return leaf + " ends inside a binary leaf";
        next = first + count;
    }
    if (next != n) return "primitives after " + std::to_string(next) + " are in no leaf";
    return "";
}

WideStats compute_wide_stats(const WideBvh& wide) {
    WideStats s;
    s.nodes = wide.nodes.size();
    s.bytes = wide.nodes.size() * sizeof(WideNode) + wide.tris.size() * sizeof(float);
    size_t slots = 0;
    for (const WideNode& w : wide.nodes) {
        slots += w.children;
        for (int k = 0; k < w.children; ++k) {
            if (!w.is_leaf(k)) continue;
            ++s.leaves;
            s.prims += w.count[k];
        }
    }
    s.mean_children = s.nodes ? double(slots) / double(s.nodes) : 0.0;
    return s;
}

}  // namespace raylane
