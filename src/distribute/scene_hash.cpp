// distribute: the scene hash of parts (scene_hash.h).
#include "distribute/scene_hash.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

#include "core/fnv1a.h"

namespace raylane {
namespace {

void hash_vec(Fnv1a& hash, const vec3& v) { hash.number(v.x), hash.number(v.y), hash.number(v.z); }

/// The file's bytes; false when it cannot be read.
bool hash_file(Fnv1a& hash, const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::vector<char> buffer(size_t(1) << 16);
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        hash.bytes(buffer.data(), size_t(in.gcount()));
    }
    return in.eof();
}

// glm's vectors are their floats (or ints), with no padding: hashed as bytes
static_assert(sizeof(vec3) == 12 && sizeof(vec2) == 8 && sizeof(uvec3) == 12);

}  // namespace

std::string scene_hash(const SceneData& scene) {
    Fnv1a hash;
    if (scene.source == "<built-in>" || !hash_file(hash, scene.source)) {
        hash = Fnv1a{};
        hash.text(scene.source);
    }
    for (const MeshData& m : scene.meshes) {
        hash.array(m.positions), hash.array(m.normals), hash.array(m.uvs);
        hash.array(m.tris), hash.array(m.normal_tris), hash.array(m.uv_tris);
    }
    for (const Texture& t : scene.textures) {
        hash.number(t.width), hash.number(t.height);
        hash.array(t.texels);
    }
    // the materials a model's material library defines are in no file the scene names
    for (const Material& m : scene.materials) {
        hash.text(m.name);
        hash_vec(hash, m.c_d), hash.number(m.k_d), hash.number(m.k_a), hash.number(m.texture);
        hash.number(m.texture_specular), hash.number(m.model), hash_vec(hash, m.c_s);
        hash.number(m.k_s), hash.number(m.exponent), hash.number(m.alpha);
        hash.number(m.glossy_samples), hash.number(m.reflection), hash.number(m.k_a_after);
        hash.number(m.fresnel), hash.number(m.refractive), hash.number(m.ior),
            hash_vec(hash, m.filter);
        hash.number(m.env_map), hash.number(m.normal_map), hash.number(m.normal_map_mode);
        hash_vec(hash, m.emission);
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash.h));
    return text;
}

}  // namespace raylane
