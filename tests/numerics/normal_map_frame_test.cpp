// Numerical stability suite, shading (numerics.md §13): shading frames. The
// orthonormal bases of shade/brdf_scalar.h (orthonormal_basis) and of the normal maps
// (texture_scalar.h, normal_from_map's fallback frame) for normals at and near -z; normal-map
// texels tilted 89 degrees, bent by keep_above; and rendered normal-mapped floors seen at grazing
// angles, diffuse and mirror, through render_scalar and render_packet at every width.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "render/render_packet.h"
#include "render/render_scalar.h"
#include "shade/brdf_packet.h"
#include "shade/brdf_scalar.h"
#include "shade/texture_packet.h"
#include "shade/texture_scalar.h"
#include "simd/lanes.h"
#include "support/float_values.h"
#include "support/widths.h"

namespace raylane {
namespace {

using namespace test;

using dvec3 = glm::dvec3;

// ---- orthonormal bases ----------------------------------------------------------------------

/// Unit normals where a branch-free frame loses precision: +-z exactly, -z tilted by 1e-1 ..
/// 1e-20 in x, in y and diagonally, signed zeros in z, the axes, and random normals (half of
/// them within 1e-3 of -z).
std::vector<vec3> frame_normals() {
    std::vector<vec3> out = {{0, 0, 1},     {0, 0, -1}, {1, 0, -0.0f}, {1, 0, 0.0f},
                             {0, 1, -0.0f}, {0, -1, 0}, {-1, 0, 0}};
    for (int k = 1; k <= 20; ++k) {
        const float e = std::pow(10.0f, -float(k));
        for (vec3 v : {vec3(e, 0, -1), vec3(0, e, -1), vec3(e, -e, -1), vec3(-e, e, 1)})
            out.push_back(vec3(glm::normalize(dvec3(v))));
    }
    std::mt19937_64 rng(21);
    std::normal_distribution<double> g;
    for (int i = 0; i < 4000; ++i) {
        const dvec3 v =
            i % 2 ? dvec3(g(rng), g(rng), g(rng)) : dvec3(1e-3 * g(rng), 1e-3 * g(rng), -1.0);
        out.push_back(vec3(glm::normalize(v)));
    }
    return out;
}

/// t, b, n orthonormal and right-handed within 1e-6, evaluated in double.
void expect_orthonormal(vec3 n, vec3 t, vec3 b, const std::string& what, double* worst) {
    const dvec3 nd(n), td(t), bd(b);
    const double errs[] = {std::fabs(glm::length(td) - 1), std::fabs(glm::length(bd) - 1),
                           std::fabs(glm::dot(td, bd)),    std::fabs(glm::dot(td, nd)),
                           std::fabs(glm::dot(bd, nd)),    glm::length(glm::cross(td, bd) - nd)};
    for (double e : errs) {
        EXPECT_LE(e, 1e-6) << what << " n = (" << n.x << ", " << n.y << ", " << n.z << ")";
        *worst = std::max(*worst, e);
    }
}

/// The normal map's frame, read through normal_from_map with no usable dp/du: texel (1, 1/2,
/// 1/2) decodes to T, (1/2, 1, 1/2) to B = n x T.
void map_frame(vec3 n, vec3& t, vec3& b) {
    const glm::mat3 id(1.0f);
    t = normal_from_map(NormalMapMode::tangent, vec3(1.0f, 0.5f, 0.5f), n, vec3(0.0f), id);
    b = normal_from_map(NormalMapMode::tangent, vec3(0.5f, 1.0f, 0.5f), n, vec3(0.0f), id);
}

TEST(NormalMapFrame, OrthonormalBasesStayAccurateNearMinusZ) {
    double worst_brdf = 0, worst_map = 0;
    for (const vec3 n : frame_normals()) {
        vec3 t, b;
        orthonormal_basis(n, t, b);
        expect_orthonormal(n, t, b, "orthonormal_basis", &worst_brdf);
        map_frame(n, t, b);
        expect_orthonormal(n, t, b, "normal map frame", &worst_map);
    }
    std::printf("orthonormal bases near -z: max error %.2e (brdf), %.2e (normal map)\n", worst_brdf,
                worst_map);
}

// ---- 89-degree normal maps ------------------------------------------------------------------

/// A tangent-space texel tilting the normal by `deg` degrees towards azimuth phi.
vec3 tilted_texel(double deg, double phi) {
    const double th = deg * pi_d / 180;
    const dvec3 m(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th));
    return vec3((m + 1.0) * 0.5);
}

/// Shading points of a normal-mapped surface seen at grazing angles: geometric normal, view
/// direction (towards the surface), interpolated normal, dp/du, and an 89-degree texel.
struct MapCase {
    vec3 ng, view, n, dpdu, texel;
};

std::vector<MapCase> map_cases() {
    std::vector<MapCase> out;
    std::mt19937_64 rng(22);
    std::normal_distribution<float> g;
    std::uniform_real_distribution<double> u(0.0, 2 * pi_d);
    for (int i = 0; i < 4000; ++i) {
        MapCase c;
        c.ng = i % 3 == 0 ? vec3(0, 0, -1) : glm::normalize(vec3(g(rng), g(rng), g(rng)));
        vec3 t, b;
        orthonormal_basis(c.ng, t, b);
        // the viewer 0.01 .. 10 degrees above the surface
        const double elev = std::pow(10.0, -2 + 3 * u(rng) / (2 * pi_d)) * pi_d / 180;
        const double az = u(rng);
        const dvec3 to_eye = dvec3(c.ng) * std::sin(elev) +
                             (dvec3(t) * std::cos(az) + dvec3(b) * std::sin(az)) * std::cos(elev);
        c.view = -vec3(glm::normalize(to_eye));
        // interpolated normals differ from ng a little; dp/du along t, sometimes degenerate
        c.n = glm::normalize(c.ng + 0.05f * vec3(g(rng), g(rng), g(rng)));
        c.dpdu = i % 7 == 0 ? vec3(0.0f) : (i % 11 == 0 ? c.n * 2.0f : t * 3.0f + b);
        c.texel = i % 13 == 0 ? vec3(0.5f) : tilted_texel(i % 2 ? 89.0 : 80.0, u(rng));
        out.push_back(c);
    }
    return out;
}

/// The shading normal as shade_scalar.cpp forms it: decoded, turned to ng's side, bent above.
vec3 shading_normal(const MapCase& c) {
    vec3 ns = normal_from_map(NormalMapMode::tangent, c.texel, c.n, c.dpdu, glm::mat3(1.0f));
    if (glm::dot(ns, c.ng) < 0.0f) ns = -ns;
    return face_viewer(keep_above(ns, c.ng), c.ng, -c.view);  // as shade_scalar.cpp
}

TEST(NormalMapFrame, EightyNineDegreeTexelsGiveUnitNormalsAboveTheSurface) {
    int facing_away = 0;
    for (const MapCase& c : map_cases()) {
        const vec3 decoded =
            normal_from_map(NormalMapMode::tangent, c.texel, c.n, c.dpdu, glm::mat3(1.0f));
        ASSERT_TRUE(std::isfinite(decoded.x + decoded.y + decoded.z));
        EXPECT_NEAR(glm::length(dvec3(decoded)), 1.0, 1e-6);
        if (c.texel == vec3(0.5f)) {
            // a texel of exactly 1/2 decodes to the zero vector: the interpolated normal
            EXPECT_EQ(decoded, glm::normalize(c.n) * 1.0f);
        }
        const vec3 ns = shading_normal(c);
        ASSERT_TRUE(std::isfinite(ns.x + ns.y + ns.z));
        EXPECT_NEAR(glm::length(dvec3(ns)), 1.0, 1e-6);
        EXPECT_GE(glm::dot(dvec3(ns), dvec3(c.ng)), 0.01 - 1e-6) << "bent above the surface";
        if (!(glm::dot(ns, -c.view) > 0.0f)) ++facing_away;
    }
    EXPECT_EQ(facing_away, 0) << "shading normals facing away from the viewer (n_s . w_o <= 0)";
    std::printf(
        "89-degree maps at grazing views: %d of %zu shading normals face away from the "
        "viewer after face_viewer\n",
        facing_away, map_cases().size());
}

// ---- rendered floors ------------------------------------------------------------------------

/// A 20 x 20 quad at y = 0 (normal +y, uv 0..8, so the map repeats) under a 32 x 32 map of
/// random 89-degree tilts (nearest look-up, so each texel keeps its tilt), seen from 0.3 above
/// the floor: view elevations from about 1 to 10 degrees. `mirror`: a perfect angle-independent
/// mirror under a constant background L and no light; otherwise white diffuse under a
/// directional light straight above.
SceneData floor_scene(bool mapped, bool mirror) {
    SceneData s;
    s.camera.position = vec3(0.0f, 0.3f, -9.0f);
    s.camera.look_at = vec3(0.0f, 0.0f, 0.0f);
    s.camera.fov_deg = 30.0f;
    s.camera.width = 48;
    s.camera.height = 32;
    s.background = mirror ? vec3(0.6f) : vec3(0.0f);
    MeshData m;
    m.positions = {{-10, 0, -10}, {10, 0, -10}, {10, 0, 10}, {-10, 0, 10}};
    m.uvs = {{0, 0}, {8, 0}, {8, 8}, {0, 8}};
    m.tris = {{0, 2, 1}, {0, 3, 2}};  // (p2 - p0) x (p1 - p0) = +y
    m.uv_tris = m.tris;
    s.meshes.push_back(m);
    Object o;
    o.kind = ShapeKind::mesh;
    s.objects.push_back(o);
    Material mat;
    mat.c_d = vec3(1.0f);
    mat.k_d = mirror ? 0.0f : 1.0f;
    mat.k_s = 0.0f;
    if (mirror) {
        mat.reflection = 1.0f;
        mat.fresnel = false;
        mat.c_s = vec3(1.0f);
    }
    if (mapped) {
        Texture t;
        t.width = 32, t.height = 32;
        t.filter = TextureFilter::nearest;
        std::mt19937_64 rng(23);
        std::uniform_real_distribution<double> u(0.0, 2 * pi_d);
        for (int i = 0; i < t.width * t.height; ++i) {
            const vec3 texel = tilted_texel(89.0, u(rng));
            t.texels.insert(t.texels.end(), {texel.x, texel.y, texel.z});
        }
        s.textures.push_back(t);
        mat.normal_map = 0;
    }
    s.materials.push_back(mat);
    if (!mirror) {
        Light l;
        l.kind = LightKind::directional;
        l.direction = vec3(0.0f, 1.0f, 0.0f);
        s.lights.push_back(l);
    }
    return s;
}

double film_mean(const Film& f) {
    double s = 0;
    for (const vec3& p : f.pixels) s += double(p.x) + p.y + p.z;
    return s / (3.0 * double(f.pixels.size()));
}

void expect_clean(const RenderResult& r, float most, const std::string& what) {
    EXPECT_EQ(r.stats.bad_samples(), 0u) << what;
    for (size_t i = 0; i < r.film.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = r.film.pixels[i][c];
            ASSERT_TRUE(v >= 0.0f && v <= most) << what << " pixel " << i << ": " << v;
        }
}

/// Diffuse floor under a light straight above: no shading normal can catch more light than the
/// flat one (n_s . l <= 1 = n_g . l), so the mapped image is nowhere brighter; no NaN, nothing
/// negative. The render is deterministic (one sample, a directional light): no noise allowance.
template <class Render>
void check_diffuse_floor(Render render, const std::string& path) {
    const SceneData flat = floor_scene(false, false), mapped = floor_scene(true, false);
    const RenderResult a = render(flat, build_accel(flat, BuildParams{}));
    const RenderResult b = render(mapped, build_accel(mapped, BuildParams{}));
    expect_clean(a, 1.0f + 1e-6f, path + " flat");
    expect_clean(b, 1.0f + 1e-6f, path + " mapped");
    for (size_t i = 0; i < a.film.pixels.size(); ++i)
        EXPECT_LE(b.film.pixels[i].x, a.film.pixels[i].x * (1 + 1e-6f)) << path << " pixel " << i;
    EXPECT_LT(film_mean(b.film), film_mean(a.film)) << path;
    EXPECT_GT(film_mean(b.film), 0.0) << path << ": the mapped floor is lit";
    std::printf("%s diffuse floor: mean %.4f flat, %.4f with the 89-degree map\n", path.c_str(),
                film_mean(a.film), film_mean(b.film));
}

/// Mirror floor under a constant background L: on the flat floor every reflected ray leaves
/// upwards and escapes, so it traces exactly one reflection ray per floor pixel. With the map, a
/// reflection about n_s that points below the geometric surface (n_g . r <= 0) re-enters the
/// floor it started from; numerics.md §13 requires such rays to be discarded, so the mapped
/// floor must trace no more reflection rays than the flat one. Pixels stay in [0, L].
template <class Render>
void check_mirror_floor(Render render, const std::string& path) {
    const SceneData flat = floor_scene(false, true), mapped = floor_scene(true, true);
    const RenderResult a = render(flat, build_accel(flat, BuildParams{}));
    const RenderResult b = render(mapped, build_accel(mapped, BuildParams{}));
    expect_clean(a, 0.6f, path + " flat");
    expect_clean(b, 0.6f, path + " mapped");
    const uint64_t floor_pixels = a.stats.reflection_rays;
    EXPECT_GT(floor_pixels, 500u) << path;
    EXPECT_LE(b.stats.reflection_rays, floor_pixels)
        << path << ": " << b.stats.reflection_rays - floor_pixels
        << " reflection rays were traced into the surface they left (flat floor: " << floor_pixels
        << " rays)";
    std::printf("%s mirror floor: %llu reflection rays flat, %llu with the 89-degree map\n",
                path.c_str(), static_cast<unsigned long long>(floor_pixels),
                static_cast<unsigned long long>(b.stats.reflection_rays));
}

TEST(NormalMapFrame, DiffuseFloorWithAnEightyNineDegreeMapIsNoBrighterThanFlat) {
    check_diffuse_floor(
        [](const SceneData& s, const Accel& a) { return render_scalar(s, a, RenderParams{}); },
        "scalar");
}

TEST(NormalMapFrame, MirrorFloorWithAnEightyNineDegreeMapTracesNoRayIntoItself) {
    check_mirror_floor(
        [](const SceneData& s, const Accel& a) { return render_scalar(s, a, RenderParams{}); },
        "scalar");
}

// ---- packet path ----------------------------------------------------------------------------

template <class T>
class NormalMapFramePacket : public ::testing::Test {};
TYPED_TEST_SUITE(NormalMapFramePacket, Widths, WidthName);

template <int W>
Vec3<W> pack(const std::vector<vec3>& v, size_t i) {
    float x[W], y[W], z[W];
    for (int k = 0; k < W; ++k) {
        const vec3 a = v[std::min(i + size_t(k), v.size() - 1)];
        x[k] = a.x, y[k] = a.y, z[k] = a.z;
    }
    return load_vec3<W>(x, y, z);
}

/// No transcendental functions: every lane equals the scalar bit for bit, for the frames near
/// -z and for the 89-degree shading normals (decode, turn to n_g's side, keep_above,
/// face_viewer).
TYPED_TEST(NormalMapFramePacket, FramesAndBentNormalsMatchTheScalarBitForBit) {
    constexpr int W = TypeParam::value;
    const std::vector<vec3> normals = frame_normals();
    for (size_t i = 0; i < normals.size(); i += W) {
        const Vec3<W> n = pack<W>(normals, i);
        Vec3<W> t, b;
        orthonormal_basis(n, t, b);
        const Vec3<W> zero = make_vec3<W>(0.0f, 0.0f, 0.0f);
        const Vec3<W> mt = normal_from_map<W>(
            NormalMapMode::tangent, make_vec3<W>(1.0f, 0.5f, 0.5f), n, zero, glm::mat3(1.0f));
        for (int k = 0; k < W; ++k) {
            const vec3 ns = normals[std::min(i + size_t(k), normals.size() - 1)];
            vec3 ts, bs, ms, unused;
            orthonormal_basis(ns, ts, bs);
            map_frame(ns, ms, unused);
            EXPECT_EQ(lane3(t, k), ts);
            EXPECT_EQ(lane3(b, k), bs);
            EXPECT_EQ(lane3(mt, k), ms);
        }
    }
    const std::vector<MapCase> cases = map_cases();
    std::vector<vec3> ng, n, dpdu, texel, view;
    for (const MapCase& c : cases) {
        ng.push_back(c.ng), n.push_back(c.n), dpdu.push_back(c.dpdu), texel.push_back(c.texel);
        view.push_back(c.view);
    }
    for (size_t i = 0; i < cases.size(); i += W) {
        const Vec3<W> g = pack<W>(ng, i);
        Vec3<W> ns = normal_from_map<W>(NormalMapMode::tangent, pack<W>(texel, i), pack<W>(n, i),
                                        pack<W>(dpdu, i), glm::mat3(1.0f));
        ns = select(dot(ns, g) < vfloat<W>(0.0f), -ns, ns);  // as shade_packet.h
        ns = face_viewer<W>(keep_above<W>(ns, g), g, -pack<W>(view, i));
        for (int k = 0; k < W; ++k) {
            const vec3 s = shading_normal(cases[std::min(i + size_t(k), cases.size() - 1)]);
            const vec3 p = lane3(ns, k);
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(std::bit_cast<uint32_t>(p[c]), std::bit_cast<uint32_t>(s[c]))
                    << "case " << i + size_t(k);
        }
    }
}

TYPED_TEST(NormalMapFramePacket, DiffuseFloorWithAnEightyNineDegreeMapIsNoBrighterThanFlat) {
    constexpr int W = TypeParam::value;
    check_diffuse_floor([](const SceneData& s,
                           const Accel& a) { return render_packet_width<W>(s, a, RenderParams{}); },
                        "packet W=" + std::to_string(W));
}

TYPED_TEST(NormalMapFramePacket, MirrorFloorWithAnEightyNineDegreeMapTracesNoRayIntoItself) {
    constexpr int W = TypeParam::value;
    check_mirror_floor([](const SceneData& s,
                          const Accel& a) { return render_packet_width<W>(s, a, RenderParams{}); },
                       "packet W=" + std::to_string(W));
}

}  // namespace
}  // namespace raylane
