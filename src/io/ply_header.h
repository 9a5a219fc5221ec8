// io: the header of a PLY file (load_ply.h): elements, properties and their types, the roles
// of the vertex and face properties. Shared by ply_header.cpp, which parses it, and
// load_ply.cpp, which reads the body it describes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace raylane::ply {

enum class PlyType : uint8_t { invalid, i8, u8, i16, u16, i32, u32, f32, f64 };

/// Names, size in bytes and (integer types) value range, indexed by PlyType.
struct TypeInfo {
    std::string_view name;
    std::string_view sized_name;
    size_t size;
    long long lo;
    long long hi;
};
constexpr TypeInfo type_info[] = {
    {"?", "?", 0, 0, 0},
    {"char", "int8", 1, INT8_MIN, INT8_MAX},
    {"uchar", "uint8", 1, 0, UINT8_MAX},
    {"short", "int16", 2, INT16_MIN, INT16_MAX},
    {"ushort", "uint16", 2, 0, UINT16_MAX},
    {"int", "int32", 4, INT32_MIN, INT32_MAX},
    {"uint", "uint32", 4, 0, UINT32_MAX},
    {"float", "float32", 4, 0, 0},
    {"double", "float64", 8, 0, 0},
};

inline const TypeInfo& info(PlyType t) { return type_info[static_cast<size_t>(t)]; }
inline size_t type_size(PlyType t) { return info(t).size; }
inline bool is_integer(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

/// Whether an ASCII integer fits the declared type (always true for float types).
inline bool fits_type(long long v, PlyType t) {
    return !is_integer(t) || (v >= info(t).lo && v <= info(t).hi);
}

/// What a property feeds in the MeshData; the first role_count roles are vertex attributes.
enum Role : uint8_t {
    role_x,
    role_y,
    role_z,
    role_nx,
    role_ny,
    role_nz,
    role_u,
    role_v,
    role_none,
    role_indices
};
constexpr int role_count = role_none;
constexpr const char* role_name[role_count] = {"x", "y", "z", "nx", "ny", "nz", "u", "v"};

struct PlyProperty {
    std::string_view name;
    PlyType type = PlyType::invalid;        ///< scalar type, or the item type of a list
    PlyType count_type = PlyType::invalid;  ///< invalid for scalars
    Role role = role_none;
    bool is_list() const { return count_type != PlyType::invalid; }
};

struct PlyElement {
    std::string_view name;
    uint64_t count = 0;
    size_t line = 0;  ///< header line of the `element` line
    std::vector<PlyProperty> props;
    bool fixed_size = true;  ///< no list properties: every record has min_bytes bytes
    /// Smallest binary record: lists empty, except vertex_indices which needs 3 items.
    size_t min_bytes = 0;
    /// Smallest ASCII record, in values: one per property (so that a short face line is
    /// reported as such rather than as a truncated file).
    size_t min_ascii_values = 0;
};

enum class PlyFormat : uint8_t { ascii, binary_little_endian, binary_big_endian };

struct PlyHeader {
    PlyFormat format = PlyFormat::ascii;
    std::vector<PlyElement> elements;
    size_t body_offset = 0;   ///< first byte after the end_header line
    size_t header_lines = 0;  ///< number of lines up to and including end_header
    size_t vertex_element = SIZE_MAX;
    size_t face_element = SIZE_MAX;
    bool has_normals = false;
    bool has_uvs = false;
};

constexpr bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Splits one line into blank-separated tokens, one at a time.
struct Tokens {
    const char* p;
    const char* end;
    std::string_view next() {
        while (p < end && is_blank(*p)) ++p;
        const char* start = p;
        while (p < end && !is_blank(*p)) ++p;
        return {start, static_cast<size_t>(p - start)};
    }
};

/// Throws InputError "file:line: reason" (the header and ASCII bodies).
[[noreturn]] void fail_line(const std::string& file, size_t line, const std::string& reason);

/// Throws InputError "file: byte N: reason" (binary bodies).
[[noreturn]] void fail_byte(const std::string& file, size_t offset, const std::string& reason);

/// `text` quoted for an error message (quote_for_error).
std::string quoted(std::string_view text);

/// The header of `bytes`, checked: its elements and properties, the roles of the vertex and face
/// properties, each element's smallest record, and where the body starts. Refuses an empty
/// file; when the first line is not `ply`, says whether the file is UTF-16 text or gzip data
/// under a plain name (text_form.h). The header's lines may end in LF, CR LF or CR; the body starts
/// after the end of the `end_header` line, read as the `ply` line ends (so a binary body after a
/// CR-only header may start with an LF byte).
PlyHeader parse_header(std::string_view bytes, const std::string& file);

}  // namespace raylane::ply
