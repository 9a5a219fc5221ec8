// Equivalence of traverse/{sphere,box,cylinder,plane}_packet.h with their *_scalar.h twins: every
// active lane's t is bit-identical to the scalar t of the same ray, and every inactive lane is
// +inf, at every packet width this machine runs, on random and adversarial rays.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "support/float_values.h"
#include "support/widths.h"
#include "traverse/box_packet.h"
#include "traverse/cylinder_packet.h"
#include "traverse/plane_packet.h"
#include "traverse/sphere_packet.h"

namespace raylane {
namespace {

#ifdef RAYLANE_SANITIZED
constexpr int rays_per_shape = 10000;  // over all configurations of one shape kind
#else
constexpr int rays_per_shape = 1000000;
#endif

using test::nan_f;

using Rng = std::mt19937;

float uniform(Rng& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}
bool chance(Rng& rng, double p) { return std::bernoulli_distribution(p)(rng); }
int pick(Rng& rng, int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }

vec3 unit_vector(Rng& rng) {
    for (;;) {
        const vec3 v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        const float len2 = glm::dot(v, v);
        if (len2 > 1e-4f && len2 <= 1.0f) return v / std::sqrt(len2);
    }
}

vec3 in_box(Rng& rng, vec3 lo, vec3 hi) {
    return vec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1)) * (hi - lo) + lo;
}

/// A point on the shape's surface and the surface normal there (exact floats on the planes of
/// boxes, caps and planes; within rounding of curved surfaces).
using SurfaceSampler = std::function<void(Rng&, vec3& p, vec3& n)>;

/// One shape with what the ray generator needs to know about it.
template <class Shape>
struct ShapeCase {
    std::string name;
    Shape shape;
    vec3 lo, hi;  ///< a box around the shape (around a patch of it, for planes)
    SurfaceSampler surface;
};

/// A special float: zero of either sign, denormal, huge, infinite or NaN.
float special_float(Rng& rng) {
    const float values[] = {0.0f,  -0.0f,  1e-40f,   -1e-40f,   1e-30f,
                            1e30f, -1e30f, infinity, -infinity, nan_f};
    return values[pick(rng, 10)];
}

/// count rays mixing: aimed at and around the box, from inside, tangent and grazing, parallel to
/// the axes with origins on the box's face planes, from surface points, and garbage; then zero
/// and -0.0 direction components, non-unit directions, t_min of 0, -0.0, > 0 and < 0 (the sign
/// of a t = 0 result shows then), and t_max in {0, 1, inf, ...}.
std::vector<Ray> make_rays(Rng& rng, vec3 lo, vec3 hi, const SurfaceSampler& surface, int count) {
    const vec3 center = 0.5f * (lo + hi);
    const vec3 ext = hi - lo;
    const float scale = std::max(std::max(ext.x, ext.y), std::max(ext.z, 1e-30f));
    std::vector<Ray> rays;
    rays.reserve(static_cast<size_t>(count));
    for (int k = 0; k < count; ++k) {
        Ray r;
        vec3 p, n;
        switch (pick(rng, 9)) {
            case 0:
            case 1: {  // aimed at the box enlarged by 20 %, from outside
                r.org = center + unit_vector(rng) * (scale * uniform(rng, 0.6f, 30.0f));
                const vec3 target = center + (in_box(rng, lo, hi) - center) * 1.2f;
                r.dir = target - r.org;
                break;
            }
            case 2:  // from inside
                r.org = in_box(rng, lo, hi);
                r.dir = unit_vector(rng);
                break;
            case 3: {  // tangent at a surface point
                surface(rng, p, n);
                r.dir = glm::cross(n, unit_vector(rng));
                r.org = p - r.dir * (scale * uniform(rng, 0.01f, 5.0f));
                break;
            }
            case 4: {  // grazing: tangent tilted slightly in or out
                surface(rng, p, n);
                r.dir = glm::normalize(glm::cross(n, unit_vector(rng))) +
                        n * uniform(rng, -1e-3f, 1e-3f);
                r.org = p - r.dir * (scale * uniform(rng, 0.01f, 5.0f));
                break;
            }
            case 5: {  // parallel to an axis, often starting on a face plane of the box
                const int axis = pick(rng, 3);
                r.dir = vec3(0.0f);
                r.dir[axis] = chance(rng, 0.5) ? 1.0f : -1.0f;
                for (int i = 0; i < 3; ++i)
                    if (i != axis && chance(rng, 0.5)) r.dir[i] = chance(rng, 0.5) ? 0.0f : -0.0f;
                r.org = center + (in_box(rng, lo, hi) - center) * 1.3f;
                r.org[axis] = center[axis] + r.dir[axis] * scale * uniform(rng, -30.0f, -0.6f);
                const int on = pick(rng, 3);
                if (chance(rng, 0.5)) r.org[on] = chance(rng, 0.5) ? lo[on] : hi[on];
                break;
            }
            case 6: {  // from a surface point, any direction
                surface(rng, p, n);
                r.org = p;
                const int kind = pick(rng, 4);
                r.dir = kind == 0 ? unit_vector(rng) : kind == 1 ? n : kind == 2 ? -n : vec3(0.0f);
                if (kind == 3) r.dir[pick(rng, 3)] = chance(rng, 0.5) ? 1.0f : -1.0f;
                break;
            }
            case 7: {  // from far away, aimed
                r.org = center + unit_vector(rng) * (scale * std::pow(10.0f, uniform(rng, 2, 6)));
                r.dir = in_box(rng, lo, hi) - r.org;
                break;
            }
            default:  // garbage: special values anywhere
                r.org = center + unit_vector(rng) * (scale * uniform(rng, 0.0f, 3.0f));
                r.dir = unit_vector(rng);
                if (chance(rng, 0.2)) r.org[pick(rng, 3)] = special_float(rng);
                r.dir[pick(rng, 3)] = special_float(rng);
                if (chance(rng, 0.1)) r.dir = vec3(0.0f);
                break;
        }
        // zero and -0.0 direction components
        if (chance(rng, 0.1)) r.dir[pick(rng, 3)] = chance(rng, 0.5) ? 0.0f : -0.0f;
        // length: unit, random in 1e-3 .. 1e3, or as made
        const int length = pick(rng, 3);
        if (length == 0 && glm::dot(r.dir, r.dir) > 0.0f) r.dir = glm::normalize(r.dir);
        if (length == 1) r.dir *= std::pow(10.0f, uniform(rng, -3.0f, 3.0f));
        // interval
        const float dist = glm::length(r.org - center) / glm::length(r.dir);
        const int t_min_kind = pick(rng, 10);
        r.t_min = t_min_kind < 5   ? 0.0f
                  : t_min_kind < 6 ? 1e-6f
                  : t_min_kind < 8 ? uniform(rng, 0.0f, 2.0f) * dist
                  : t_min_kind < 9 ? -0.0f
                                   : -uniform(rng, 0.0f, 2.0f) * dist;
        const int t_max_kind = pick(rng, 10);
        r.t_max = t_max_kind < 5   ? infinity
                  : t_max_kind < 6 ? 0.0f
                  : t_max_kind < 7 ? 1.0f
                                   : uniform(rng, 0.0f, 2.0f) * dist;
        rays.push_back(r);
    }
    return rays;
}

/// The same ray set for every width: built once per case.
template <class Shape>
struct CaseRays {
    std::vector<Ray> rays;
    std::vector<float> want;  ///< the scalar t of each ray
};

template <class Shape>
using ScalarTest = float (*)(const Shape&, const Ray&);

template <class Shape>
const std::vector<CaseRays<Shape>>& case_rays(const std::vector<ShapeCase<Shape>>& cases,
                                              std::type_identity_t<ScalarTest<Shape>> scalar,
                                              uint32_t seed) {
    static std::vector<CaseRays<Shape>> sets;
    if (!sets.empty()) return sets;
    Rng rng(seed);
    const int per_case =
        (rays_per_shape + static_cast<int>(cases.size()) - 1) / static_cast<int>(cases.size());
    for (const ShapeCase<Shape>& c : cases) {
        CaseRays<Shape> s;
        s.rays = make_rays(rng, c.lo, c.hi, c.surface, per_case);
        for (const Ray& r : s.rays) s.want.push_back(scalar(c.shape, r));
        sets.push_back(std::move(s));
    }
    return sets;
}

uint32_t float_bits(float v) { return std::bit_cast<uint32_t>(v); }

std::string describe(const Ray& r) {
    char buf[400];
    std::snprintf(buf, sizeof buf, "org (%a, %a, %a) dir (%a, %a, %a) t_min %a t_max %a",
                  double(r.org.x), double(r.org.y), double(r.org.z), double(r.dir.x),
                  double(r.dir.y), double(r.dir.z), double(r.t_min), double(r.t_max));
    return buf;
}

/// Packs the rays W at a time under random active masks (none, all, or random lanes; inactive
/// lanes often hold NaN garbage), runs the packet test and counts lanes that differ: an active
/// lane whose t is not the scalar t bit for bit (both infinite counts as equal), or an inactive
/// lane that is not +inf. The first few differences go to the test log.
template <int W, class Shape, class Packet>
size_t count_mismatches(const ShapeCase<Shape>& c, const CaseRays<Shape>& set, Packet packet,
                        Rng& rng) {
    size_t bad = 0;
    const size_t n = set.rays.size();
    Ray garbage;
    garbage.org = vec3(nan_f, 1e30f, -0.0f);
    garbage.dir = vec3(0.0f, nan_f, infinity);
    garbage.t_min = nan_f;
    garbage.t_max = -1.0f;
    for (size_t first = 0; first < n; first += W) {
        uint32_t active_bits;
        const int mode = pick(rng, 8);
        if (mode == 0) {
            active_bits = 0;
        } else if (mode < 4) {
            active_bits = ~0u;
        } else {
            active_bits = static_cast<uint32_t>(rng());
        }
        RayPacket<W> p;
        for (int i = 0; i < W; ++i) {
            const bool exists = first + size_t(i) < n;
            if (!exists) active_bits &= ~(1u << i);
            const bool on = (active_bits >> i) & 1u;
            set_ray(p, i,
                    exists && (on || chance(rng, 0.5)) ? set.rays[first + size_t(i)] : garbage);
        }
        active_bits &= (1u << W) - 1u;
        const vfloat<W> got = packet(c.shape, p, mask_from_bits<W>(active_bits));
        for (int i = 0; i < W; ++i) {
            const float g = get(got, i);
            const bool on = (active_bits >> i) & 1u;
            const float w = on ? set.want[first + size_t(i)] : infinity;
            const bool same = float_bits(g) == float_bits(w) || (std::isinf(g) && std::isinf(w));
            if (same) continue;
            if (++bad <= 5)
                ADD_FAILURE() << c.name << ", W = " << W << ", lane " << i
                              << (on ? " (active)" : " (inactive)") << ": packet t " << g
                              << ", expected " << w << "; ray "
                              << (on ? describe(set.rays[first + size_t(i)]) : "-");
        }
    }
    return bad;
}

/// Runs every case of a shape kind at width W and checks the ray set is not trivial.
template <int W, class Shape, class Packet>
void check_cases(const std::vector<ShapeCase<Shape>>& cases,
                 std::type_identity_t<ScalarTest<Shape>> scalar, Packet packet, uint32_t seed) {
    const std::vector<CaseRays<Shape>>& sets = case_rays(cases, scalar, seed);
    Rng rng(seed + static_cast<uint32_t>(W));
    size_t total = 0, hits = 0;
    for (size_t k = 0; k < cases.size(); ++k) {
        EXPECT_EQ(count_mismatches<W>(cases[k], sets[k], packet, rng), 0u) << cases[k].name;
        total += sets[k].rays.size();
        for (float t : sets[k].want) hits += t < infinity;
    }
    EXPECT_GE(total, size_t(rays_per_shape));
    EXPECT_GT(hits, total / 10) << "the rays must hit often";
    EXPECT_LT(hits, total - total / 10) << "the rays must miss often";
}

// --- shapes ------------------------------------------------------------------------------------

std::vector<ShapeCase<Sphere>> sphere_cases() {
    std::vector<ShapeCase<Sphere>> cases;
    auto add = [&](const char* name, vec3 center, float radius) {
        const Sphere s{center, radius};
        cases.push_back({name, s, center - vec3(radius), center + vec3(radius),
                         [s](Rng& rng, vec3& p, vec3& n) {
                             n = unit_vector(rng);
                             if (chance(rng, 0.2)) {  // a pole: p exact when center + r is
                                 n = vec3(0.0f);
                                 n[pick(rng, 3)] = chance(rng, 0.5) ? 1.0f : -1.0f;
                             }
                             p = s.center + s.radius * n;
                         }});
    };
    add("unit sphere", vec3(0.3f, -0.2f, 0.5f), 1.0f);
    add("far sphere", vec3(1e3f, -2e3f, 5e3f), 1.0f);
    add("tiny sphere", vec3(0.1f, 0.2f, 0.3f), 1e-3f);
    add("huge ground sphere", vec3(0.0f, -1e5f, 0.0f), 1e5f);
    add("sphere far from the origin", vec3(1e5f, 1e5f, -1e5f), 10.0f);
    add("sphere of radius 0", vec3(2.0f, 0.0f, 0.0f), 0.0f);
    return cases;
}

std::vector<ShapeCase<Box>> box_cases() {
    std::vector<ShapeCase<Box>> cases;
    auto add = [&](const char* name, vec3 lo, vec3 hi) {
        const Box b{lo, hi};
        cases.push_back({name, b, lo, hi, [b](Rng& rng, vec3& p, vec3& n) {
                             // a face, a point on it, sometimes snapped to an edge or corner
                             const int axis = pick(rng, 3);
                             const bool high = chance(rng, 0.5);
                             p = in_box(rng, b.lo, b.hi);
                             for (int i = 0; i < 3; ++i)
                                 if (chance(rng, 0.2)) p[i] = chance(rng, 0.5) ? b.lo[i] : b.hi[i];
                             p[axis] = high ? b.hi[axis] : b.lo[axis];
                             n = vec3(0.0f);
                             n[axis] = high ? 1.0f : -1.0f;
                         }});
    };
    add("cube", vec3(-1.0f), vec3(1.0f));
    add("box of zero thickness", vec3(-0.5f, 0.2f, -3.0f), vec3(2.0f, 0.2f, 1.0f));
    add("far box", vec3(1e4f, 2e4f, -3e4f), vec3(1e4f + 1.0f, 2e4f + 3.0f, -3e4f + 0.5f));
    add("tiny box", vec3(1e-3f, -2e-3f, 0.0f), vec3(2e-3f, -1e-3f, 1e-3f));
    add("flat box through the origin", vec3(-1.0f, 0.0f, -1.0f), vec3(1.0f, 0.0f, 1.0f));
    add("box of zero size", vec3(0.5f), vec3(0.5f));
    return cases;
}

std::vector<ShapeCase<Cylinder>> cylinder_cases() {
    std::vector<ShapeCase<Cylinder>> cases;
    auto add = [&](const char* name, float radius, float height) {
        const Cylinder c{radius, height};
        cases.push_back({name, c, vec3(-radius, 0.0f, -radius), vec3(radius, height, radius),
                         [c](Rng& rng, vec3& p, vec3& n) {
                             const float phi = uniform(rng, 0.0f, 6.2831853f);
                             const float cx = std::cos(phi), cz = std::sin(phi);
                             const int part = pick(rng, 4);
                             if (part < 2) {  // side, sometimes exactly on a rim
                                 const int y = pick(rng, 4);
                                 p = vec3(c.radius * cx,
                                          y == 0   ? 0.0f
                                          : y == 1 ? c.height
                                                   : uniform(rng, 0.0f, c.height),
                                          c.radius * cz);
                                 n = vec3(cx, 0.0f, cz);
                             } else {  // caps, sometimes on the rim
                                 const float rho =
                                     chance(rng, 0.25) ? c.radius : c.radius * uniform(rng, 0, 1);
                                 p = vec3(rho * cx, part == 2 ? 0.0f : c.height, rho * cz);
                                 n = vec3(0.0f, part == 2 ? -1.0f : 1.0f, 0.0f);
                             }
                         }});
    };
    add("unit cylinder", 1.0f, 2.0f);
    add("tiny cylinder", 1e-3f, 2e-3f);
    add("wide flat cylinder", 1e4f, 1.0f);
    add("tall thin cylinder", 0.5f, 1e4f);
    add("cylinder of height 0", 0.5f, 0.0f);
    add("cylinder of radius 0", 0.0f, 1.0f);
    return cases;
}

std::vector<ShapeCase<Plane>> plane_cases() {
    std::vector<ShapeCase<Plane>> cases;
    auto add = [&](const char* name, vec3 point, vec3 normal, float half_size) {
        const Plane pl{point, normal};
        cases.push_back({name, pl, point - vec3(half_size), point + vec3(half_size),
                         [pl, half_size](Rng& rng, vec3& p, vec3& n) {
                             n = glm::normalize(pl.normal);
                             const vec3 t1 = glm::normalize(glm::cross(n, unit_vector(rng)));
                             const vec3 t2 = glm::cross(n, t1);
                             p = pl.point + t1 * uniform(rng, -half_size, half_size) +
                                 t2 * uniform(rng, -half_size, half_size);
                             if (chance(rng, 0.3)) p = pl.point;
                         }});
    };
    add("ground plane", vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), 4.0f);
    add("tilted plane", vec3(1.0f, 2.0f, 3.0f), glm::normalize(vec3(1.0f, 2.0f, -3.0f)), 4.0f);
    add("far plane", vec3(1e5f, -1e5f, 3e4f), glm::normalize(vec3(-0.3f, 0.9f, 0.1f)), 10.0f);
    add("plane facing -z", vec3(0.0f, 1e-3f, 0.0f), vec3(0.0f, 0.0f, -1.0f), 1e-2f);
    add("plane with a non-unit normal", vec3(0.5f, -0.5f, 0.0f), vec3(0.0f, 2.0f, 0.5f), 2.0f);
    return cases;
}

// --- tests -------------------------------------------------------------------------------------

template <class T>
class ShapesPacket : public ::testing::Test {};
TYPED_TEST_SUITE(ShapesPacket, Widths, WidthName);

TYPED_TEST(ShapesPacket, SphereMatchesScalarBitForBit) {
    constexpr int W = TypeParam::value;
    check_cases<W>(
        sphere_cases(), [](const Sphere& s, const Ray& r) { return intersect_sphere(s, r); },
        [](const Sphere& s, const RayPacket<W>& r, vmask<W> a) {
            return intersect_sphere<W>(s, r, a);
        },
        11u);
}

TYPED_TEST(ShapesPacket, BoxMatchesScalarBitForBit) {
    constexpr int W = TypeParam::value;
    check_cases<W>(
        box_cases(), [](const Box& b, const Ray& r) { return intersect_box(b, r); },
        [](const Box& b, const RayPacket<W>& r, vmask<W> a) { return intersect_box<W>(b, r, a); },
        22u);
}

TYPED_TEST(ShapesPacket, CylinderMatchesScalarBitForBit) {
    constexpr int W = TypeParam::value;
    check_cases<W>(
        cylinder_cases(), [](const Cylinder& c, const Ray& r) { return intersect_cylinder(c, r); },
        [](const Cylinder& c, const RayPacket<W>& r, vmask<W> a) {
            return intersect_cylinder<W>(c, r, a);
        },
        33u);
}

TYPED_TEST(ShapesPacket, PlaneMatchesScalarBitForBit) {
    constexpr int W = TypeParam::value;
    check_cases<W>(
        plane_cases(), [](const Plane& p, const Ray& r) { return intersect_plane(p, r); },
        [](const Plane& p, const RayPacket<W>& r, vmask<W> a) {
            return intersect_plane<W>(p, r, a);
        },
        44u);
}

TYPED_TEST(ShapesPacket, NoActiveLanesMeansInfinity) {
    constexpr int W = TypeParam::value;
    RayPacket<W> p;  // every lane from (0, 0.5, -5) along +z: hits each shape below if active
    p.org = make_vec3<W>(0.0f, 0.5f, -5.0f);
    const vmask<W> all_lanes = mask_from_bits<W>(~0u), no_lanes = mask_from_bits<W>(0u);
    const Sphere s;
    const Box b;
    const Cylinder c;
    const Plane pl{vec3(0.0f), vec3(0.0f, 0.0f, 1.0f)};
    const uint32_t every = bits(all_lanes);
    EXPECT_EQ(bits(intersect_sphere<W>(s, p, all_lanes) < vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_box<W>(b, p, all_lanes) < vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_cylinder<W>(c, p, all_lanes) < vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_plane<W>(pl, p, all_lanes) < vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_sphere<W>(s, p, no_lanes) == vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_box<W>(b, p, no_lanes) == vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_cylinder<W>(c, p, no_lanes) == vfloat<W>(infinity)), every);
    EXPECT_EQ(bits(intersect_plane<W>(pl, p, no_lanes) == vfloat<W>(infinity)), every);
}

}  // namespace
}  // namespace raylane
