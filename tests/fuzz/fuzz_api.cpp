// fuzz: libFuzzer target for the public API's array entry points (raylane/mesh.h): a mesh from
// the caller's vertex and index arrays, and closest-hit and occlusion queries of rays given as
// strided arrays, with values anywhere (NaN, infinities, huge, denormal), shared origins
// (stride 0), rays interleaved in an (N, 6) array and per-ray or shared t_max. Bad arrays must
// throw raylane::Error; any answer must be one the renderer could use: both paths alike, bit
// for bit, a hit within (0, t_max] on a real triangle, a miss as documented, and occlusion
// exactly where there is a closest hit. Run by scripts/fuzz.sh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <vector>

#include "raylane/raylane.h"

namespace {

[[noreturn]] void finding(const char* what) {
    std::fprintf(stderr, "==fuzz== the API answered wrongly: %s\n", what);
    std::abort();
}

void require(bool ok, const char* what) {
    if (!ok) finding(what);
}

/// The input read as a stream of bytes, zeros past its end.
struct Input {
    const uint8_t* data;
    size_t size, at = 0;
    uint8_t byte() { return at < size ? data[at++] : 0; }
    uint32_t word() {
        uint32_t w = 0;
        for (int k = 0; k < 4; ++k) w |= uint32_t(byte()) << (8 * k);
        return w;
    }
    /// A raw float (any bit pattern) or, half the time, a small one on a grid, so that meshes
    /// and rays that meet are common.
    float number(bool raw) {
        if (raw) {
            const uint32_t w = word();
            float f;
            std::memcpy(&f, &w, sizeof f);
            return f;
        }
        return float(int8_t(byte())) / 16.0f;
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Input in{data, size};
    const uint8_t shape = in.byte(), flags = in.byte();
    const size_t vertex_count = shape % 9, triangle_count = (shape / 9) % 9;
    const size_t ray_count = in.byte() % 33;
    const bool raw_vertices = flags & 1, raw_rays = flags & 2, loose_indices = flags & 4;

    std::vector<float> vertices(3 * vertex_count);
    for (float& v : vertices) v = in.number(raw_vertices);
    std::vector<uint32_t> triangles(3 * triangle_count);
    for (uint32_t& t : triangles)
        t = loose_indices ? in.word() : uint32_t(in.byte() % (vertex_count + 1));
    std::optional<raylane::Mesh> mesh;
    try {
        mesh.emplace(vertices.data(), vertex_count, triangles.data(), triangle_count);
    } catch (const raylane::Error&) {
        return 0;  // a vertex not finite or an index out of range: refused, as documented
    }

    // rays: separate arrays, one (N, 6) array, or one origin for all (stride 0)
    const int layout = (flags >> 3) % 3;
    std::vector<float> floats(6 * ray_count + 6);
    for (float& f : floats) f = in.number(raw_rays);
    raylane::Rays rays;
    rays.count = ray_count;
    rays.origins = floats.data();
    if (layout == 0) {
        rays.directions = floats.data() + 3 * ray_count + 3;
    } else if (layout == 1) {
        rays.directions = floats.data() + 3;
        rays.origin_stride = rays.direction_stride = 6 * sizeof(float);
    } else {
        rays.origin_stride = 0;
        rays.directions = floats.data() + 3;
    }
    std::vector<float> t_max(ray_count);
    if (flags & 32) {
        for (float& t : t_max) t = in.number(raw_rays);
        rays.t_max = t_max.data();
    } else if (flags & 64) {
        rays.t_max_all = in.number(true);
    }
    raylane::QuerySettings settings;
    settings.threads = 1;
    settings.coherence = raylane::Coherence((flags >> 7) ? in.byte() % 3 : 0);

    std::vector<float> t[2], u[2], v[2], normal[2];
    std::vector<int32_t> triangle[2];
    std::vector<uint8_t> occluded[2];
    for (int p = 0; p < 2; ++p) {
        t[p].resize(ray_count), u[p].resize(ray_count), v[p].resize(ray_count);
        normal[p].resize(3 * ray_count), triangle[p].resize(ray_count);
        occluded[p].resize(ray_count);
        raylane::Hits hits;
        hits.t = t[p].data(), hits.u = u[p].data(), hits.v = v[p].data();
        hits.normal = normal[p].data(), hits.triangle = triangle[p].data();
        settings.path = p == 0 ? raylane::TracePath::packet : raylane::TracePath::scalar;
        try {
            mesh->intersect(rays, hits, settings);
            mesh->occluded(rays, occluded[p].data(), settings);
        } catch (const raylane::Error&) {
            finding("a query of well-formed arrays threw");
        }
    }
    if (ray_count == 0) return 0;  // (memcmp of empty vectors' null data is undefined)
    const size_t bytes = ray_count * sizeof(float);
    require(triangle[0] == triangle[1], "the paths hit different triangles");
    require(std::memcmp(t[0].data(), t[1].data(), bytes) == 0, "the paths differ in t");
    require(std::memcmp(u[0].data(), u[1].data(), bytes) == 0, "the paths differ in u");
    require(std::memcmp(v[0].data(), v[1].data(), bytes) == 0, "the paths differ in v");
    require(occluded[0] == occluded[1], "the paths differ in occlusion");
    for (size_t i = 0; i < ray_count; ++i) {
        const float limit = rays.t_max ? rays.t_max[i] : rays.t_max_all;
        if (triangle[0][i] < 0) {
            require(
                triangle[0][i] == -1 && std::isinf(t[0][i]) && u[0][i] == 0.0f && v[0][i] == 0.0f,
                "a miss is not t = inf, triangle = -1, u = v = 0");
            require(occluded[0][i] == 0, "occluded without a closest hit");
        } else {
            require(size_t(triangle[0][i]) < triangle_count, "a hit on no triangle");
            require(t[0][i] > 0.0f && t[0][i] <= limit, "a hit outside (0, t_max]");
            require(occluded[0][i] == 1, "a closest hit but not occluded");
        }
    }
    return 0;
}
