// io: Wavefront MTL material libraries (named by an OBJ's `mtllib`), and how their materials
// map onto Raylane's (docs/scene-format.md, "OBJ materials").
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace raylane {

/// One `newmtl` block as written.
struct MtlMaterial {
    std::string name;
    vec3 kd{0.8f}, ks{0.0f}, ke{0.0f};
    float ns = 10.0f;  ///< specular exponent
    float ni = 1.5f;   ///< index of refraction
    float d = 1.0f;    ///< dissolve (opacity); Raylane has no partial opacity
    int illum = 2;
    std::string map_kd;    ///< diffuse texture, relative to the MTL file's folder ('/' separated)
    std::string map_bump;  ///< map_Bump, bump or norm: read as a tangent-space normal map
};

/// The materials of one MTL file, and the keywords it holds that Raylane does not use (d below
/// 1, Tf, map_Ks, ..., each once, in order of appearance), for one warning line. Ka is read as
/// nothing and not listed: Raylane's ambient term is k_a c_d.
struct MtlLibrary {
    std::vector<MtlMaterial> materials;
    std::vector<std::string> ignored;
};

/// Parses MTL text. Keywords are matched case-insensitively; `#` starts a comment anywhere; a
/// texture line's options (-bm 1.0, -s 1 1 1, ...) are skipped and the rest of the line is the
/// file, with Windows `\` separators turned into `/`. Throws InputError "file:line: reason" for
/// a bad number, a colour of other than 1 or 3 numbers, or a value before any `newmtl`.
MtlLibrary parse_mtl(std::string_view text, const std::string& path_for_errors);

/// Reads and parses an MTL file (InputError "path: cannot read: ..." when it cannot be read).
MtlLibrary load_mtl(const std::string& path);

/// Raylane's material for an MTL material (textures are left to the caller: texture and
/// normal_map stay -1): c_d = Kd, k_d = 1, k_a = 0.1; c_s = Ks and k_s = 1 when Ks is not black,
/// exponent = Ns (at least 1); emission = Ke; illum 3 or 5 a mirror of strength max(Ks); illum
/// 4, 6, 7 or 9 glass of index Ni.
Material material_from_mtl(const MtlMaterial& m);

}  // namespace raylane
