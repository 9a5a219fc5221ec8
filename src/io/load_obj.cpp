// io: Wavefront OBJ reader (load_obj.h). One pass over the file held in memory, floats parsed
// with std::from_chars, no allocation per line. Sibling of load_ply.cpp.
#include "io/load_obj.h"

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/error.h"
#include "io/drop_degenerate.h"
#include "io/gzip_file.h"
#include "io/read_file.h"
#include "io/text_form.h"
#include "io/text_lines.h"

namespace raylane {

namespace {

constexpr bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}
constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
constexpr bool is_keyword_char(char c) { return is_letter(c) || is_digit(c) || c == '_'; }

enum Attribute : uint8_t { attr_position = 0, attr_uv = 1, attr_normal = 2 };
constexpr const char* attribute_name[3] = {"vertex", "texture coordinate", "normal"};

/// Index forms of a face corner, as bits: 1 = has vt, 2 = has vn.
constexpr const char* form_name[4] = {"v", "v/vt", "v//vn", "v/vt/vn"};

/// A face corner whose positive index points past the attributes read so far. OBJ allows
/// that; whether the attribute ever appears is checked once the whole file has been read.
struct ForwardRef {
    size_t line = 0;
    long long index = 0;  ///< as written (1-based)
    Attribute attribute = attr_position;
};

struct ObjReader {
    ObjReader(const std::string& file_name, MeshData& out) : file(file_name), mesh(out) {}

    const std::string& file;
    MeshData& mesh;
    size_t line = 0;
    const char* p = nullptr;     ///< cursor inside the current line
    const char* end = nullptr;   ///< end of the current line, before its '\n'
    std::vector<uvec3> corners;  ///< (v, vt, vn) of the face being read; reused across faces
    std::vector<ForwardRef> forward_refs;
    size_t faces_without_uv = 0;
    size_t faces_without_normal = 0;
    /// The material of the faces read now: an index into mesh.material_names, or `no_material`
    /// before any `usemtl` and after a bare one.
    static constexpr uint32_t no_material = ~0u;
    uint32_t material = no_material;

    [[noreturn]] void fail(const std::string& reason) const {
        throw InputError(file + ":" + std::to_string(line) + ": " + reason);
    }

    void skip_blanks() {
        while (p < end && is_blank(*p)) ++p;
    }
    /// True when only blanks or a trailing '#' comment are left on the line.
    bool at_end_of_values() {
        skip_blanks();
        return p == end || *p == '#';
    }
    std::string_view token_at(const char* q) const {
        const char* e = q;
        while (e < end && !is_blank(*e)) ++e;
        return {q, static_cast<size_t>(e - q)};
    }

    float read_float(const char* what) {
        if (at_end_of_values()) fail(std::string("missing ") + what);
        const char* start = p;
        if (*p == '+' && p + 1 < end && (is_digit(p[1]) || p[1] == '.')) ++p;
        double value = 0.0;
        auto [next, ec] = std::from_chars(p, end, value);
        if (ec != std::errc() || (next < end && !is_blank(*next))) {
            fail(std::string("bad number ") + quote_for_error(token_at(start)) + " for " + what);
        }
        // fabs(NaN) <= max is false, so this also rejects NaN; it also keeps the cast defined.
        if (!(std::fabs(value) <= static_cast<double>(FLT_MAX))) {
            fail(std::string(what) + " " + quote_for_error(token_at(start)) +
                 " is not a finite float");
        }
        p = next;
        return static_cast<float>(value);
    }

    /// One index of the face corner starting at `corner`.
    uint32_t read_index(Attribute attribute, const char* corner) {
        const bool negative = p < end && *p == '-';
        if (p < end && (*p == '-' || *p == '+')) ++p;
        if (p == end || !is_digit(*p)) fail("bad face corner " + quote_for_error(token_at(corner)));
        // Decimal digits by hand (faster than from_chars here); stops growing past 2^36, which
        // is out of range for 32-bit indices anyway, so it cannot overflow.
        long long value = 0;
        for (; p < end && is_digit(*p); ++p) {
            if (value < (1ll << 36)) value = value * 10 + (*p - '0');
        }
        if (negative) value = -value;
        auto count = static_cast<long long>(attribute == attr_position ? mesh.positions.size()
                                            : attribute == attr_uv     ? mesh.uvs.size()
                                                                       : mesh.normals.size());
        const char* name = attribute_name[attribute];
        if (value == 0) fail(std::string(name) + " index 0 is invalid (OBJ indices start at 1)");
        if (value < 0) {
            if (value < -count) {
                fail("relative " + std::string(name) + " index " + std::to_string(value) +
                     " out of range: only " + std::to_string(count) + " defined so far");
            }
            return static_cast<uint32_t>(count + value);
        }
        if (value > static_cast<long long>(UINT32_MAX)) {
            fail(std::string(name) + " index " + std::to_string(value) + " out of range");
        }
        if (value > count) forward_refs.push_back({line, value, attribute});
        return static_cast<uint32_t>(value - 1);
    }

    void parse_vertex() {
        vec3 v;
        v.x = read_float("x");
        v.y = read_float("y");
        v.z = read_float("z");
        // Optional w, or the r g b of vertex colours: checked, then ignored.
        for (int extra = 0; !at_end_of_values(); ++extra) {
            if (extra == 4) fail("too many values on a 'v' line");
            read_float("value");
        }
        mesh.positions.push_back(v);
    }

    void parse_uv() {
        vec2 uv{0.0f};
        uv.x = read_float("u");
        if (!at_end_of_values()) uv.y = read_float("v");
        if (!at_end_of_values()) read_float("w");
        if (!at_end_of_values()) fail("too many values on a 'vt' line");
        mesh.uvs.push_back(uv);
    }

    void parse_normal() {
        vec3 n;
        n.x = read_float("x");
        n.y = read_float("y");
        n.z = read_float("z");
        if (!at_end_of_values()) fail("too many values on a 'vn' line");
        mesh.normals.push_back(n);
    }

    bool at_index() const { return p < end && (is_digit(*p) || *p == '-' || *p == '+'); }

    /// One face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` into `corner`; returns its index form
    /// (form_name). An index left empty (`7/`, `7//`, `7/2/`) is absent, as common readers take
    /// it: `7/` and `7//` are the form `v`, `7/2/` the form `v/vt`.
    int read_corner(uvec3& corner) {
        const char* start = p;
        int form = 0;
        corner.x = read_index(attr_position, start);
        if (p < end && *p == '/') {
            ++p;
            if (at_index()) {
                corner.y = read_index(attr_uv, start);
                form |= 1;
            }
            if (p < end && *p == '/') {
                ++p;
                if (at_index()) {
                    corner.z = read_index(attr_normal, start);
                    form |= 2;
                }
            }
        }
        if (p < end && !is_blank(*p)) fail("bad face corner " + quote_for_error(token_at(start)));
        return form;
    }

    void parse_face() {
        corners.clear();
        int form = -1;
        while (!at_end_of_values()) {
            uvec3 corner{0u};
            const int corner_form = read_corner(corner);
            if (form < 0) {
                form = corner_form;
            } else if (corner_form != form) {
                fail(std::string("face mixes index forms ") + form_name[form] + " and " +
                     form_name[corner_form]);
            }
            corners.push_back(corner);
        }
        if (corners.size() < 3) {
            fail("face has " + std::to_string(corners.size()) + " corners; at least 3 are needed");
        }
        bool has_uv = (form & 1) != 0;
        bool has_normal = (form & 2) != 0;
        faces_without_uv += has_uv ? 0 : 1;
        faces_without_normal += has_normal ? 0 : 1;
        // Fan (c0, ci, ci+1): exact for convex polygons, which is all OBJ promises.
        const uvec3 c0 = corners[0];
        for (size_t i = 1; i + 1 < corners.size(); ++i) {
            const uvec3 a = corners[i];
            const uvec3 b = corners[i + 1];
            mesh.tris.push_back({c0.x, a.x, b.x});
            mesh.tri_material.push_back(material);
            if (has_uv) mesh.uv_tris.push_back({c0.y, a.y, b.y});
            if (has_normal) mesh.normal_tris.push_back({c0.z, a.z, b.z});
        }
    }

    void parse_line() {
        skip_blanks();
        if (p == end || *p == '#') return;
        const char* keyword_start = p;
        if (!is_letter(*p)) {
            fail("expected a keyword or '#' at the start of the line, found " +
                 quote_for_error(token_at(keyword_start)));
        }
        while (p < end && is_keyword_char(*p)) ++p;
        if (p < end && !is_blank(*p)) {
            fail("bad keyword " + quote_for_error(token_at(keyword_start)));
        }
        std::string_view keyword(keyword_start, static_cast<size_t>(p - keyword_start));
        if (keyword == "v") {
            parse_vertex();
        } else if (keyword == "f") {
            parse_face();
        } else if (keyword == "vt") {
            parse_uv();
        } else if (keyword == "vn") {
            parse_normal();
        } else if (keyword == "usemtl") {
            parse_usemtl();
        } else if (keyword == "mtllib") {
            parse_mtllib();
        }
        // o g s l p and all other keywords: accepted and ignored.
    }

    /// The rest of the line, without blanks at either end or a trailing comment.
    std::string_view rest_of_line() {
        skip_blanks();
        const char* stop = p;
        while (stop < end && *stop != '#') ++stop;
        while (stop > p && is_blank(stop[-1])) --stop;
        return {p, static_cast<size_t>(stop - p)};
    }

    /// `usemtl name`, or a bare `usemtl`: back to the default material.
    void parse_usemtl() {
        const std::string_view name = rest_of_line();
        if (name.empty()) {
            material = no_material;
            return;
        }
        auto& names = mesh.material_names;
        const auto it = std::find(names.begin(), names.end(), name);
        material = static_cast<uint32_t>(it - names.begin());
        if (it == names.end()) names.emplace_back(name);
    }

    /// `mtllib a.mtl [b.mtl ...]`: the libraries, names separated by blanks.
    void parse_mtllib() {
        const std::string_view names = rest_of_line();
        size_t i = 0;
        while (i < names.size()) {
            while (i < names.size() && is_blank(names[i])) ++i;
            size_t j = i;
            while (j < names.size() && !is_blank(names[j])) ++j;
            if (j > i) mesh.material_libraries.emplace_back(names.substr(i, j - i));
            i = j;
        }
    }

    /// The faces before any `usemtl` or after a bare one get the material named "" (the
    /// object's own); a file that names no material keeps no material lists.
    void finish_materials() {
        if (mesh.material_names.empty()) {
            mesh.tri_material.clear();
            return;
        }
        const auto unnamed = static_cast<uint32_t>(mesh.material_names.size());
        bool any_unnamed = false;
        for (uint32_t& m : mesh.tri_material) {
            if (m != no_material) continue;
            m = unnamed;
            any_unnamed = true;
        }
        if (any_unnamed) mesh.material_names.emplace_back();
    }

    void check_forward_refs() {
        for (const ForwardRef& ref : forward_refs) {
            size_t count = ref.attribute == attr_position ? mesh.positions.size()
                           : ref.attribute == attr_uv     ? mesh.uvs.size()
                                                          : mesh.normals.size();
            if (static_cast<unsigned long long>(ref.index) > count) {
                line = ref.line;
                fail(std::string(attribute_name[ref.attribute]) + " index " +
                     std::to_string(ref.index) + " out of range: the file has " +
                     std::to_string(count));
            }
        }
    }
};

}  // namespace

MeshData load_obj_from_memory(std::string_view text, const std::string& name_for_errors) {
    MeshData mesh;
    mesh.name = file_name_of(name_for_errors);
    refuse_non_text(text, name_for_errors, "OBJ");
    ObjReader reader(name_for_errors, mesh);
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
    LineCursor lines(text);
    for (std::string_view line; lines.next(line);) {
        ++reader.line;
        reader.p = line.data();
        reader.end = line.data() + line.size();
        reader.parse_line();
    }
    reader.check_forward_refs();
    reader.finish_materials();
    if (mesh.tris.empty()) throw InputError(name_for_errors + ": no faces ('f' lines)");
    // Attributes only some faces have are dropped for the whole mesh (see load_obj.h).
    if (reader.faces_without_uv > 0) {
        mesh.uvs.clear();
        mesh.uv_tris.clear();
    }
    if (reader.faces_without_normal > 0) {
        mesh.normals.clear();
        mesh.normal_tris.clear();
    }
    drop_zero_area_triangles(mesh, name_for_errors);
    return mesh;
}

MeshData load_obj(const std::string& path) {
    return load_obj_from_memory(read_model_file(path).view(), path);
}

}  // namespace raylane
