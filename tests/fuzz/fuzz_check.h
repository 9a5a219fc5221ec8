// fuzz: checks on what a reader returns, shared by the libFuzzer targets tests/fuzz/fuzz_*.cpp.
// A reader either throws InputError or returns data the renderer can index and shade safely.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "scene/scene.h"

namespace raylane::fuzz {

/// Reports a broken invariant as a crash, so that libFuzzer saves the input.
[[noreturn]] inline void finding(const char* what) {
    std::fprintf(stderr, "==fuzz== reader returned bad data: %s\n", what);
    std::abort();
}

inline void require(bool ok, const char* what) {
    if (!ok) finding(what);
}

inline bool finite(float v) { return std::isfinite(v); }
inline bool finite(vec2 v) { return finite(v.x) && finite(v.y); }
inline bool finite(vec3 v) { return finite(v.x) && finite(v.y) && finite(v.z); }
inline bool finite(const mat4& m) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!finite(m[c][r])) return false;
        }
    }
    return true;
}

template <typename T>
bool all_finite(const std::vector<T>& values) {
    for (const T& v : values) {
        if (!finite(v)) return false;
    }
    return true;
}

/// Every index of `tris` is below `count`.
inline bool indices_below(const std::vector<uvec3>& tris, size_t count) {
    for (const uvec3& t : tris) {
        if (t.x >= count || t.y >= count || t.z >= count) return false;
    }
    return true;
}

/// The MeshData contract of scene/scene.h: triangles, in-range indices, one normal / uv triple per
/// triangle or none, finite positions, normals and uvs (load_obj.h, load_ply.h).
inline void check_mesh(const MeshData& mesh) {
    require(!mesh.tris.empty(), "mesh without triangles");
    require(indices_below(mesh.tris, mesh.positions.size()), "position index out of range");
    require(mesh.normal_tris.empty() || mesh.normal_tris.size() == mesh.tris.size(),
            "normal_tris is neither empty nor one per triangle");
    require(mesh.uv_tris.empty() || mesh.uv_tris.size() == mesh.tris.size(),
            "uv_tris is neither empty nor one per triangle");
    require(indices_below(mesh.normal_tris, mesh.normals.size()), "normal index out of range");
    require(indices_below(mesh.uv_tris, mesh.uvs.size()), "uv index out of range");
    require(all_finite(mesh.positions), "non-finite position");
    require(all_finite(mesh.normals), "non-finite normal");
    require(all_finite(mesh.uvs), "non-finite uv");
}

/// An image texture holds width * height RGB texels, all finite.
inline void check_texture(const Texture& t) {
    if (t.kind != TextureKind::image) return;
    require(t.width > 0 && t.height > 0, "image texture with a zero or negative size");
    require(t.texels.size() == size_t(t.width) * size_t(t.height) * 3,
            "texel count is not width * height * 3");
    for (float v : t.texels) require(finite(v), "non-finite texel");
}

}  // namespace raylane::fuzz
