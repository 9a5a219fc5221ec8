// io: PLY reader (load_ply.h): header, then ASCII or binary body from the file held in memory.
// Sibling of load_obj.cpp.
#include "io/load_ply.h"

#include <bit>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <vector>

#include "core/error.h"
#include "io/drop_degenerate.h"
#include "io/read_file.h"

namespace raylane {

namespace {

// header ---------------------------------------------------------------------------------

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

const TypeInfo& info(PlyType t) { return type_info[static_cast<size_t>(t)]; }
size_t type_size(PlyType t) { return info(t).size; }
bool is_integer(PlyType t) { return t != PlyType::f32 && t != PlyType::f64; }

PlyType parse_type(std::string_view name) {
    for (size_t i = 1; i < std::size(type_info); ++i) {
        if (type_info[i].name == name || type_info[i].sized_name == name) {
            return static_cast<PlyType>(i);
        }
    }
    return PlyType::invalid;
}

/// Whether an ASCII integer fits the declared type (always true for float types).
bool fits_type(long long v, PlyType t) {
    return !is_integer(t) || (v >= info(t).lo && v <= info(t).hi);
}

/// What a property feeds in the Mesh; the first role_count roles are vertex attributes.
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

[[noreturn]] void fail_line(const std::string& file, size_t line, const std::string& reason) {
    throw InputError(file + ":" + std::to_string(line) + ": " + reason);
}

[[noreturn]] void fail_byte(const std::string& file, size_t offset, const std::string& reason) {
    throw InputError(file + ": byte " + std::to_string(offset) + ": " + reason);
}

std::string quoted(std::string_view text) { return quote_for_error(text); }

size_t find_property(const PlyElement& e, std::string_view name) {
    for (size_t i = 0; i < e.props.size(); ++i) {
        if (e.props[i].name == name) return i;
    }
    return SIZE_MAX;
}

/// Gives the vertex properties their roles; checks x y z, nx ny nz and the uv pair.
void assign_vertex_roles(const std::string& file, PlyElement& e, PlyHeader& header) {
    auto take = [&](std::string_view name, Role role) {
        size_t i = find_property(e, name);
        if (i == SIZE_MAX) return false;
        if (e.props[i].is_list()) {
            fail_line(file, e.line, "vertex property " + quoted(name) + " must not be a list");
        }
        e.props[i].role = role;
        return true;
    };
    for (Role r : {role_x, role_y, role_z}) {
        if (!take(role_name[r], r)) {
            fail_line(file, e.line,
                      std::string("vertex element has no '") + role_name[r] + "' property");
        }
    }
    int normals = int{take("nx", role_nx)} + int{take("ny", role_ny)} + int{take("nz", role_nz)};
    if (normals != 0 && normals != 3) {
        fail_line(file, e.line, "vertex element has some but not all of nx ny nz");
    }
    header.has_normals = normals == 3;
    constexpr std::string_view uv_pairs[][2] = {
        {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const auto& pair : uv_pairs) {
        bool has_u = find_property(e, pair[0]) != SIZE_MAX;
        bool has_v = find_property(e, pair[1]) != SIZE_MAX;
        if (has_u != has_v) {
            fail_line(file, e.line,
                      "vertex element has " + quoted(has_u ? pair[0] : pair[1]) + " but no " +
                          quoted(has_u ? pair[1] : pair[0]));
        }
        if (has_u) {
            take(pair[0], role_u);
            take(pair[1], role_v);
            header.has_uvs = true;
            break;
        }
    }
}

void assign_face_roles(const std::string& file, PlyElement& e) {
    size_t i = find_property(e, "vertex_indices");
    if (i == SIZE_MAX) i = find_property(e, "vertex_index");
    if (i == SIZE_MAX) {
        fail_line(file, e.line, "face element has no 'vertex_indices' list property");
    }
    PlyProperty& prop = e.props[i];
    if (!prop.is_list())
        fail_line(file, e.line, "face property " + quoted(prop.name) + " is not a list");
    if (!is_integer(prop.type)) {
        fail_line(file, e.line,
                  "face property " + quoted(prop.name) + " has a non-integer item type");
    }
    prop.role = role_indices;
}

/// `format <ascii | binary_little_endian | binary_big_endian> 1.0`, once.
void parse_format(Tokens& tokens, const std::string& file, size_t line, bool& has_format,
                  PlyHeader& header) {
    std::string_view name = tokens.next();
    std::string_view version = tokens.next();
    if (has_format) fail_line(file, line, "second format line");
    if (name == "ascii") {
        header.format = PlyFormat::ascii;
    } else if (name == "binary_little_endian") {
        header.format = PlyFormat::binary_little_endian;
    } else if (name == "binary_big_endian") {
        header.format = PlyFormat::binary_big_endian;
    } else {
        fail_line(file, line,
                  "unsupported format " + quoted(name) +
                      " (expected ascii, binary_little_endian or "
                      "binary_big_endian)");
    }
    if (version != "1.0") fail_line(file, line, "unsupported PLY version " + quoted(version));
    if (!tokens.next().empty()) fail_line(file, line, "bad header: extra words after format");
    has_format = true;
}

/// `element <name> <count>`; notes which element is the vertex and which the face element.
void parse_element(Tokens& tokens, const std::string& file, size_t line, PlyHeader& header) {
    PlyElement e;
    e.name = tokens.next();
    std::string_view count = tokens.next();
    auto [next, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
    if (e.name.empty() || count.empty() || ec != std::errc() ||
        next != count.data() + count.size() || !tokens.next().empty()) {
        fail_line(file, line, "bad header: expected 'element <name> <count>'");
    }
    // Only the two elements the reader uses must be unique (and this stays O(n)).
    if ((e.name == "vertex" && header.vertex_element != SIZE_MAX) ||
        (e.name == "face" && header.face_element != SIZE_MAX)) {
        fail_line(file, line, "second element " + quoted(e.name));
    }
    if (e.name == "vertex") header.vertex_element = header.elements.size();
    if (e.name == "face") header.face_element = header.elements.size();
    e.line = line;
    header.elements.push_back(std::move(e));
}

/// `property <type> <name>` or `property list <count type> <item type> <name>`, of the last
/// element.
void parse_property(Tokens& tokens, const std::string& file, size_t line, PlyHeader& header) {
    if (header.elements.empty()) fail_line(file, line, "bad header: property before any element");
    PlyProperty prop;
    std::string_view type = tokens.next();
    if (type == "list") {
        std::string_view count_type = tokens.next();
        prop.count_type = parse_type(count_type);
        if (prop.count_type == PlyType::invalid) {
            fail_line(file, line, "unknown property type " + quoted(count_type));
        }
        if (!is_integer(prop.count_type)) {
            fail_line(file, line, "list count type must be an integer type");
        }
        type = tokens.next();
    }
    prop.type = parse_type(type);
    if (prop.type == PlyType::invalid)
        fail_line(file, line, "unknown property type " + quoted(type));
    prop.name = tokens.next();
    if (prop.name.empty() || !tokens.next().empty()) {
        fail_line(file, line, "bad header: expected 'property <type> <name>'");
    }
    header.elements.back().props.push_back(prop);
}

/// After the header's last line (`line`): the roles of the vertex and face properties, each
/// element's smallest record, and the vertex and face elements present.
void finish_elements(const std::string& file, size_t line, PlyHeader& header) {
    for (size_t i = 0; i < header.elements.size(); ++i) {
        PlyElement& e = header.elements[i];
        if (e.props.empty())
            fail_line(file, e.line, "element " + quoted(e.name) + " has no properties");
        if (i == header.vertex_element) {
            if (e.count > UINT32_MAX)
                fail_line(file, e.line, "too many vertices for 32-bit indices");
            assign_vertex_roles(file, e, header);
        } else if (i == header.face_element) {
            assign_face_roles(file, e);
        }
        for (const PlyProperty& prop : e.props) {
            size_t min_items = prop.role == role_indices ? 3 : 0;
            if (prop.is_list()) {
                e.fixed_size = false;
                e.min_bytes += type_size(prop.count_type) + min_items * type_size(prop.type);
            } else {
                e.min_bytes += type_size(prop.type);
            }
            e.min_ascii_values += 1;
        }
    }
    if (header.vertex_element == SIZE_MAX)
        fail_line(file, line, "no 'vertex' element in the header");
    if (header.face_element == SIZE_MAX) fail_line(file, line, "no 'face' element in the header");
}

PlyHeader parse_header(std::string_view bytes, const std::string& file) {
    PlyHeader header;
    const char* cur = bytes.data();
    const char* end = bytes.data() + bytes.size();
    size_t line = 0;
    bool has_format = false;
    bool ended = false;
    while (cur < end && !ended) {
        const void* newline = std::memchr(cur, '\n', static_cast<size_t>(end - cur));
        const char* line_end = newline ? static_cast<const char*>(newline) : end;
        ++line;
        Tokens tokens{cur, line_end};
        cur = newline ? line_end + 1 : end;
        std::string_view keyword = tokens.next();
        if (line == 1) {
            if (keyword != "ply" || !tokens.next().empty()) {
                fail_line(file, 1, "not a PLY file: the first line must be 'ply'");
            }
            continue;
        }
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            parse_format(tokens, file, line, has_format, header);
        } else if (keyword == "element") {
            parse_element(tokens, file, line, header);
        } else if (keyword == "property") {
            parse_property(tokens, file, line, header);
        } else if (keyword == "end_header") {
            if (!tokens.next().empty())
                fail_line(file, line, "bad header: extra words after end_header");
            ended = true;
        } else {
            fail_line(file, line, "bad header: unknown keyword " + quoted(keyword));
        }
    }
    if (line == 0) throw InputError(file + ": empty file, not a PLY file");
    if (!ended) fail_line(file, line, "bad header: no end_header line");
    if (!has_format) fail_line(file, line, "bad header: no format line");
    header.body_offset = static_cast<size_t>(cur - bytes.data());
    header.header_lines = line;
    finish_elements(file, line, header);
    return header;
}

// body, shared ---------------------------------------------------------------------------

struct PlyReader {
    PlyReader(std::string_view body, const std::string& file_name, const PlyHeader& head, Mesh& out)
        : bytes(body), file(file_name), header(head), mesh(out) {}

    std::string_view bytes;
    const std::string& file;
    const PlyHeader& header;
    Mesh& mesh;
    std::vector<uint32_t> corners;  ///< vertex indices of the face being read; reused

    uint64_t vertex_count() const { return header.elements[header.vertex_element].count; }

    /// Writes one vertex attribute, checking the float range (NaN and inf included).
    /// Returns false when the value is not a finite float.
    bool store(Role role, size_t vertex, double value) {
        if (!(std::fabs(value) <= static_cast<double>(FLT_MAX))) return false;
        auto f = static_cast<float>(value);
        if (role < role_nx) {
            mesh.positions[vertex][role - role_x] = f;
        } else if (role < role_u) {
            mesh.normals[vertex][role - role_nx] = f;
        } else if (role < role_count) {
            mesh.uvs[vertex][role - role_u] = f;
        }
        return true;
    }

    /// Sizes the mesh arrays for an element whose count has been checked against the file.
    void begin_element(size_t index) {
        const PlyElement& e = header.elements[index];
        if (index == header.vertex_element) {
            auto n = static_cast<size_t>(e.count);
            mesh.positions.resize(n);
            if (header.has_normals) mesh.normals.resize(n);
            if (header.has_uvs) mesh.uvs.resize(n);
        } else if (index == header.face_element) {
            mesh.tris.reserve(static_cast<size_t>(e.count));
        }
    }

    /// Appends the fan (c0, ci, ci+1) of the face in `corners` (already range-checked).
    void emit_face() {
        const uint32_t c0 = corners[0];
        for (size_t i = 1; i + 1 < corners.size(); ++i) {
            mesh.tris.push_back({c0, corners[i], corners[i + 1]});
        }
    }

    std::string index_error(long long index) const {
        if (index < 0) return "negative vertex index " + std::to_string(index);
        return "vertex index " + std::to_string(index) + " out of range (" +
               std::to_string(vertex_count()) + " vertices)";
    }

    std::string count_error(const PlyElement& e, const PlyProperty& prop, long long count) const {
        if (count < 0)
            return "negative list count " + std::to_string(count) + " in " + quoted(prop.name);
        return "face with " + std::to_string(count) + " vertices in element " + quoted(e.name) +
               "; at least 3 are needed";
    }

    // binary ---------------------------------------------------------------------------

    template <bool Swap>
    static uint16_t load16(const unsigned char* p) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        if constexpr (Swap) v = __builtin_bswap16(v);
        return v;
    }
    template <bool Swap>
    static uint32_t load32(const unsigned char* p) {
        uint32_t v;
        std::memcpy(&v, p, 4);
        if constexpr (Swap) v = __builtin_bswap32(v);
        return v;
    }
    template <bool Swap>
    static uint64_t load64(const unsigned char* p) {
        uint64_t v;
        std::memcpy(&v, p, 8);
        if constexpr (Swap) v = __builtin_bswap64(v);
        return v;
    }

    template <bool Swap>
    static double load_number(PlyType t, const unsigned char* p) {
        switch (t) {
            case PlyType::i8:
                return static_cast<int8_t>(*p);
            case PlyType::u8:
                return *p;
            case PlyType::i16:
                return static_cast<int16_t>(load16<Swap>(p));
            case PlyType::u16:
                return load16<Swap>(p);
            case PlyType::i32:
                return static_cast<int32_t>(load32<Swap>(p));
            case PlyType::u32:
                return load32<Swap>(p);
            case PlyType::f32:
                return std::bit_cast<float>(load32<Swap>(p));
            case PlyType::f64:
                return std::bit_cast<double>(load64<Swap>(p));
            case PlyType::invalid:
                break;
        }
        return 0.0;
    }

    /// Integer types only (checked in the header for counts and vertex indices); every value
    /// of a 32-bit type is exact in a double.
    template <bool Swap>
    static long long load_integer(PlyType t, const unsigned char* p) {
        return static_cast<long long>(load_number<Swap>(t, p));
    }

    size_t offset_of(const unsigned char* p) const {
        return static_cast<size_t>(p - reinterpret_cast<const unsigned char*>(bytes.data()));
    }

    /// Fixed-size vertex records: one bounds check for the element, then a plain loop; with
    /// native-endian float x y z (and nx ny nz, u v) each field is a 4-byte memcpy.
    template <bool Swap>
    void read_fixed_vertices(const PlyElement& e, const unsigned char* base) {
        size_t offset[role_count] = {};
        PlyType type[role_count] = {};
        bool used[role_count] = {};
        bool all_float = true;
        size_t at = 0;
        for (const PlyProperty& prop : e.props) {
            if (prop.role < role_count) {
                offset[prop.role] = at;
                type[prop.role] = prop.type;
                used[prop.role] = true;
                all_float = all_float && prop.type == PlyType::f32;
            }
            at += type_size(prop.type);
        }
        const size_t record = e.min_bytes;
        const auto n = static_cast<size_t>(e.count);
        if (!Swap && all_float) {
            for (size_t i = 0; i < n; ++i) {
                const unsigned char* r = base + i * record;
                vec3& pos = mesh.positions[i];
                std::memcpy(&pos.x, r + offset[role_x], 4);
                std::memcpy(&pos.y, r + offset[role_y], 4);
                std::memcpy(&pos.z, r + offset[role_z], 4);
                if (header.has_normals) {
                    vec3& nrm = mesh.normals[i];
                    std::memcpy(&nrm.x, r + offset[role_nx], 4);
                    std::memcpy(&nrm.y, r + offset[role_ny], 4);
                    std::memcpy(&nrm.z, r + offset[role_nz], 4);
                }
                if (header.has_uvs) {
                    std::memcpy(&mesh.uvs[i].x, r + offset[role_u], 4);
                    std::memcpy(&mesh.uvs[i].y, r + offset[role_v], 4);
                }
            }
            for (size_t i = 0; i < n; ++i) {
                const unsigned char* r = base + i * record;
                for (int role = 0; role < role_count; ++role) {
                    if (used[role] &&
                        !std::isfinite(load_number<false>(PlyType::f32, r + offset[role]))) {
                        fail_byte(
                            file, offset_of(r + offset[role]),
                            std::string("vertex ") + role_name[role] + " is not a finite float");
                    }
                }
            }
            return;
        }
        for (size_t i = 0; i < n; ++i) {
            const unsigned char* r = base + i * record;
            for (int role = 0; role < role_count; ++role) {
                if (!used[role]) continue;
                const unsigned char* field = r + offset[role];
                if (!store(static_cast<Role>(role), i, load_number<Swap>(type[role], field))) {
                    fail_byte(file, offset_of(field),
                              std::string("vertex ") + role_name[role] + " is not a finite float");
                }
            }
        }
    }

    /// Any record, property by property, with a bounds check before every read.
    template <bool Swap>
    const unsigned char* read_record(size_t element, size_t record, const unsigned char* p,
                                     const unsigned char* end) {
        const PlyElement& e = header.elements[element];
        auto need = [&](size_t n, const char* what) {
            if (static_cast<size_t>(end - p) < n) {
                fail_byte(file, offset_of(p),
                          "file truncated: " + std::string(what) + " of " + quoted(e.name) +
                              " record " + std::to_string(record) + " needs " + std::to_string(n) +
                              " bytes, " + std::to_string(end - p) + " remain");
            }
        };
        for (const PlyProperty& prop : e.props) {
            const size_t item = type_size(prop.type);
            if (!prop.is_list()) {
                need(item, "a property");
                if (prop.role < role_count &&
                    !store(prop.role, record, load_number<Swap>(prop.type, p))) {
                    fail_byte(
                        file, offset_of(p),
                        std::string("vertex ") + role_name[prop.role] + " is not a finite float");
                }
                p += item;
                continue;
            }
            need(type_size(prop.count_type), "a list count");
            const unsigned char* count_at = p;
            long long count = load_integer<Swap>(prop.count_type, p);
            p += type_size(prop.count_type);
            if (count < 0) fail_byte(file, offset_of(count_at), count_error(e, prop, count));
            if (static_cast<unsigned long long>(count) > static_cast<size_t>(end - p) / item) {
                fail_byte(file, offset_of(count_at),
                          "list count " + std::to_string(count) + " in " + quoted(prop.name) +
                              " needs more than the " + std::to_string(end - p) +
                              " bytes that remain (file truncated?)");
            }
            if (prop.role != role_indices) {
                p += static_cast<size_t>(count) * item;
                continue;
            }
            if (count < 3) fail_byte(file, offset_of(count_at), count_error(e, prop, count));
            corners.clear();
            for (long long k = 0; k < count; ++k, p += item) {
                long long index = load_integer<Swap>(prop.type, p);
                if (index < 0 || static_cast<unsigned long long>(index) >= vertex_count()) {
                    fail_byte(file, offset_of(p), index_error(index));
                }
                corners.push_back(static_cast<uint32_t>(index));
            }
            emit_face();
        }
        return p;
    }

    template <bool Swap>
    void read_binary() {
        const auto* begin = reinterpret_cast<const unsigned char*>(bytes.data());
        const unsigned char* end = begin + bytes.size();
        const unsigned char* p = begin + header.body_offset;
        for (size_t ei = 0; ei < header.elements.size(); ++ei) {
            const PlyElement& e = header.elements[ei];
            const auto remaining = static_cast<size_t>(end - p);
            if (e.count > remaining / e.min_bytes) {
                fail_byte(file, offset_of(p),
                          "file truncated or bad count: element " + quoted(e.name) + " declares " +
                              std::to_string(e.count) + " records of at least " +
                              std::to_string(e.min_bytes) + " bytes, but only " +
                              std::to_string(remaining) + " bytes remain");
            }
            begin_element(ei);
            if (e.fixed_size) {
                if (ei == header.vertex_element) read_fixed_vertices<Swap>(e, p);
                p += static_cast<size_t>(e.count) * e.min_bytes;
                continue;
            }
            for (size_t r = 0; r < e.count; ++r) p = read_record<Swap>(ei, r, p, end);
        }
    }

    // ascii ----------------------------------------------------------------------------

    const char* cur = nullptr;       ///< start of the next line
    const char* text_end = nullptr;  ///< end of the file
    size_t line = 0;
    Tokens tokens{nullptr, nullptr};

    [[noreturn]] void fail_here(const std::string& reason) const { fail_line(file, line, reason); }

    /// Moves `tokens` to the next non-blank line; false at the end of the file.
    bool next_line() {
        while (cur < text_end) {
            const void* newline = std::memchr(cur, '\n', static_cast<size_t>(text_end - cur));
            const char* line_end = newline ? static_cast<const char*>(newline) : text_end;
            ++line;
            tokens = Tokens{cur, line_end};
            cur = newline ? line_end + 1 : text_end;
            while (tokens.p < tokens.end && is_blank(*tokens.p)) ++tokens.p;
            if (tokens.p < tokens.end) return true;
        }
        return false;
    }

    std::string_view value_token(const PlyElement& e, const PlyProperty& prop) {
        std::string_view token = tokens.next();
        if (token.empty()) {
            fail_here("too few values on the line: element " + quoted(e.name) + " property " +
                      quoted(prop.name) + " is missing");
        }
        return token;
    }

    /// An integer of any size; range checks are the caller's.
    long long parse_any_integer(std::string_view token, const PlyProperty& prop) {
        const char* first = token.data();
        const char* last = first + token.size();
        if (token.size() > 1 && *first == '+') ++first;
        long long v = 0;
        auto [next, ec] = std::from_chars(first, last, v);
        if (ec != std::errc() || next != last) {
            fail_here("bad integer " + quoted(token) + " for property " + quoted(prop.name));
        }
        return v;
    }

    long long parse_integer(std::string_view token, PlyType type, const PlyProperty& prop) {
        long long v = parse_any_integer(token, prop);
        if (!fits_type(v, type)) {
            fail_here("value " + quoted(token) + " does not fit the " +
                      std::string(info(type).name) + " property " + quoted(prop.name));
        }
        return v;
    }

    double parse_number(std::string_view token, const PlyProperty& prop) {
        if (is_integer(prop.type))
            return static_cast<double>(parse_integer(token, prop.type, prop));
        const char* first = token.data();
        const char* last = first + token.size();
        if (token.size() > 1 && *first == '+') ++first;
        double v = 0.0;
        auto [next, ec] = std::from_chars(first, last, v);
        if (ec != std::errc() || next != last) {
            fail_here("bad number " + quoted(token) + " for property " + quoted(prop.name));
        }
        return v;
    }

    void read_ascii_record(size_t element, size_t record) {
        const PlyElement& e = header.elements[element];
        for (const PlyProperty& prop : e.props) {
            if (!prop.is_list()) {
                std::string_view token = value_token(e, prop);
                double v = parse_number(token, prop);
                if (prop.role < role_count && !store(prop.role, record, v)) {
                    fail_here(std::string("vertex ") + role_name[prop.role] + " " + quoted(token) +
                              " is not a finite float");
                }
                continue;
            }
            std::string_view count_token = value_token(e, prop);
            long long count = parse_any_integer(count_token, prop);
            if (count < 0 || (prop.role == role_indices && count < 3)) {
                fail_here(count_error(e, prop, count));
            }
            if (!fits_type(count, prop.count_type)) {
                fail_here("list count " + quoted(count_token) + " does not fit the " +
                          std::string(info(prop.count_type).name) + " count type of " +
                          quoted(prop.name));
            }
            if (prop.role == role_indices) corners.clear();
            // Each item consumes a token or fails, so the loop is bounded by the line length.
            for (long long k = 0; k < count; ++k) {
                std::string_view token = value_token(e, prop);
                if (prop.role != role_indices) {
                    parse_number(token, prop);
                    continue;
                }
                long long index = parse_any_integer(token, prop);
                if (index < 0 || static_cast<unsigned long long>(index) >= vertex_count()) {
                    fail_here(index_error(index));
                }
                if (!fits_type(index, prop.type)) {
                    fail_here("vertex index " + quoted(token) + " does not fit the " +
                              std::string(info(prop.type).name) + " item type of " +
                              quoted(prop.name));
                }
                corners.push_back(static_cast<uint32_t>(index));
            }
            if (prop.role == role_indices) emit_face();
        }
        if (!tokens.next().empty()) {
            fail_here("too many values on the line: element " + quoted(e.name) + " has " +
                      std::to_string(e.props.size()) + " properties");
        }
    }

    void read_ascii() {
        cur = bytes.data() + header.body_offset;
        text_end = bytes.data() + bytes.size();
        line = header.header_lines;
        for (size_t ei = 0; ei < header.elements.size(); ++ei) {
            const PlyElement& e = header.elements[ei];
            // Every value takes a character and a separator (the last one may lack it).
            const auto remaining = static_cast<size_t>(text_end - cur);
            if (e.count > (remaining + 1) / (2 * e.min_ascii_values)) {
                fail_line(file, line + 1,
                          "file truncated or bad count: element " + quoted(e.name) + " declares " +
                              std::to_string(e.count) + " records of at least " +
                              std::to_string(e.min_ascii_values) + " values, but only " +
                              std::to_string(remaining) + " bytes remain");
            }
            begin_element(ei);
            for (size_t r = 0; r < e.count; ++r) {
                if (!next_line()) {
                    fail_here("unexpected end of file: element " + quoted(e.name) + " has " +
                              std::to_string(r) + " of " + std::to_string(e.count) + " records");
                }
                read_ascii_record(ei, r);
            }
        }
        if (next_line()) fail_here("unexpected data after the last element");
    }
};

}  // namespace

Mesh load_ply_from_memory(std::string_view bytes, const std::string& name_for_errors) {
    const PlyHeader header = parse_header(bytes, name_for_errors);
    Mesh mesh;
    mesh.name = file_name_of(name_for_errors);
    PlyReader reader(bytes, name_for_errors, header, mesh);
    constexpr bool little = std::endian::native == std::endian::little;
    switch (header.format) {
        case PlyFormat::ascii:
            reader.read_ascii();
            break;
        case PlyFormat::binary_little_endian:
            little ? reader.read_binary<false>() : reader.read_binary<true>();
            break;
        case PlyFormat::binary_big_endian:
            little ? reader.read_binary<true>() : reader.read_binary<false>();
            break;
    }
    if (mesh.tris.empty()) throw InputError(name_for_errors + ": no faces");
    if (header.has_normals) mesh.normal_tris = mesh.tris;
    if (header.has_uvs) mesh.uv_tris = mesh.tris;
    drop_zero_area_triangles(mesh, name_for_errors);
    return mesh;
}

Mesh load_ply(const std::string& path) { return load_ply_from_memory(map_file(path).view(), path); }

}  // namespace raylane
