// io: PLY reader (load_ply.h): the body, ASCII or binary, from the file held in memory, as the
// header (ply_header.h) describes it. Sibling of load_obj.cpp.
#include "io/load_ply.h"

#include <bit>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "io/drop_degenerate.h"
#include "io/gzip_file.h"
#include "io/ply_header.h"
#include "io/read_file.h"
#include "io/text_lines.h"

namespace raylane {

namespace {

using namespace ply;  // NOLINT(google-build-using-namespace): the header's vocabulary

// body, shared ---------------------------------------------------------------------------

struct PlyReader {
    PlyReader(std::string_view body, const std::string& file_name, const PlyHeader& head,
              MeshData& out)
        : bytes(body), file(file_name), header(head), mesh(out) {}

    std::string_view bytes;
    const std::string& file;
    const PlyHeader& header;
    MeshData& mesh;
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

    /// Sizes the mesh arrays for `records` records of an element, a number the file has been
    /// found to hold (its count, or fewer when the file ends early).
    void begin_element(size_t index, uint64_t records) {
        if (index == header.vertex_element) {
            auto n = static_cast<size_t>(records);
            mesh.positions.resize(n);
            if (header.has_normals) mesh.normals.resize(n);
            if (header.has_uvs) mesh.uvs.resize(n);
        } else if (index == header.face_element) {
            mesh.tris.reserve(static_cast<size_t>(records));
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

    /// "ends after K of N vertices" ("faces", "'edge' records"): the file held K whole records
    /// of the N the header promised for `e`.
    static std::string ended_after(const PlyElement& e, uint64_t whole) {
        const bool one = e.count == 1;
        const std::string noun = e.name == "vertex" ? (one ? "vertex" : "vertices")
                                 : e.name == "face"
                                     ? (one ? "face" : "faces")
                                     : quoted(e.name) + (one ? " record" : " records");
        return "ends after " + std::to_string(whole) + " of " + std::to_string(e.count) + " " +
               noun;
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
        auto need = [&](size_t n) {
            if (static_cast<size_t>(end - p) < n)
                fail_byte(file, bytes.size(), ended_after(e, record));
        };
        for (const PlyProperty& prop : e.props) {
            const size_t item = type_size(prop.type);
            if (!prop.is_list()) {
                need(item);
                if (prop.role < role_count &&
                    !store(prop.role, record, load_number<Swap>(prop.type, p))) {
                    fail_byte(
                        file, offset_of(p),
                        std::string("vertex ") + role_name[prop.role] + " is not a finite float");
                }
                p += item;
                continue;
            }
            need(type_size(prop.count_type));
            const unsigned char* count_at = p;
            long long count = load_integer<Swap>(prop.count_type, p);
            p += type_size(prop.count_type);
            if (count < 0) fail_byte(file, offset_of(count_at), count_error(e, prop, count));
            if (static_cast<unsigned long long>(count) > static_cast<size_t>(end - p) / item) {
                fail_byte(file, offset_of(count_at),
                          "list count " + std::to_string(count) + " in " + quoted(prop.name) +
                              " needs " + std::to_string(count * static_cast<long long>(item)) +
                              " bytes, but only " + std::to_string(end - p) + " remain: the file " +
                              ended_after(e, record));
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

    /// How many records of `e` lie whole between `p` and `end`, up to e.count; every record
    /// takes at least a byte, so the walk ends within the file. A negative list count is
    /// reported as reading it would.
    template <bool Swap>
    uint64_t count_whole_records(const PlyElement& e, const unsigned char* p,
                                 const unsigned char* end) const {
        if (e.fixed_size)
            return std::min<uint64_t>(e.count, static_cast<size_t>(end - p) / e.min_bytes);
        for (uint64_t r = 0; r < e.count; ++r) {
            for (const PlyProperty& prop : e.props) {
                const size_t size = type_size(prop.is_list() ? prop.count_type : prop.type);
                if (static_cast<size_t>(end - p) < size) return r;
                if (!prop.is_list()) {
                    p += size;
                    continue;
                }
                const long long count = load_integer<Swap>(prop.count_type, p);
                if (count < 0) fail_byte(file, offset_of(p), count_error(e, prop, count));
                p += size;
                const size_t item = type_size(prop.type);
                if (static_cast<unsigned long long>(count) > static_cast<size_t>(end - p) / item)
                    return r;
                p += static_cast<size_t>(count) * item;
            }
        }
        return e.count;
    }

    template <bool Swap>
    void read_binary() {
        const auto* begin = reinterpret_cast<const unsigned char*>(bytes.data());
        const unsigned char* end = begin + bytes.size();
        const unsigned char* p = begin + header.body_offset;
        for (size_t ei = 0; ei < header.elements.size(); ++ei) {
            const PlyElement& e = header.elements[ei];
            // Records the file cannot hold are never allocated: the whole ones are counted.
            if (e.count > static_cast<size_t>(end - p) / e.min_bytes) {
                const uint64_t whole = count_whole_records<Swap>(e, p, end);
                if (whole < e.count) fail_byte(file, bytes.size(), ended_after(e, whole));
            }
            begin_element(ei, e.count);
            if (e.fixed_size) {
                if (ei == header.vertex_element) read_fixed_vertices<Swap>(e, p);
                p += static_cast<size_t>(e.count) * e.min_bytes;
                continue;
            }
            for (size_t r = 0; r < e.count; ++r) p = read_record<Swap>(ei, r, p, end);
        }
    }

    // ascii ----------------------------------------------------------------------------

    LineCursor lines{std::string_view()};  ///< the body's lines, from the line after the header
    size_t line = 0;                       ///< the line `tokens` holds
    Tokens tokens{nullptr, nullptr};

    [[noreturn]] void fail_here(const std::string& reason) const { fail_line(file, line, reason); }

    static bool is_blank_line(std::string_view text) {
        for (char c : text) {
            if (!is_blank(c)) return false;
        }
        return true;
    }

    /// Moves `tokens` to the next non-blank line; false at the end of the file.
    bool next_line() {
        for (std::string_view text; lines.next(text);) {
            ++line;
            if (is_blank_line(text)) continue;
            tokens = Tokens{text.data(), text.data() + text.size()};
            return true;
        }
        return false;
    }

    /// The non-blank lines after the current one, counted up to `limit` on a copy of the cursor.
    uint64_t count_lines_left(uint64_t limit) const {
        LineCursor rest = lines;
        uint64_t records = 0;
        for (std::string_view text; records < limit && rest.next(text);) {
            records += is_blank_line(text) ? 0 : 1;
        }
        return records;
    }

    /// Whether records are promised after record `r` of element `ei`.
    bool promised_after(size_t ei, size_t r) const {
        if (r + 1 < header.elements[ei].count) return true;
        for (size_t later = ei + 1; later < header.elements.size(); ++later) {
            if (header.elements[later].count > 0) return true;
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

    /// Whether the current line is the file's last and has no end while more records are
    /// promised: the file was cut there, and the line is no whole record, whatever it holds.
    bool at_cut_line(size_t ei, size_t r) const {
        return lines.rest() == bytes.data() + bytes.size() && lines.line_end().empty() &&
               promised_after(ei, r);
    }

    void read_ascii() {
        lines = LineCursor(bytes.substr(header.body_offset));
        line = header.header_lines;
        for (size_t ei = 0; ei < header.elements.size(); ++ei) {
            const PlyElement& e = header.elements[ei];
            // Every value takes a character and a separator (the last one may lack it). Records
            // the file cannot hold are never allocated: its lines are counted.
            uint64_t records = e.count;
            const auto remaining = static_cast<size_t>(bytes.data() + bytes.size() - lines.rest());
            if (e.count > (remaining + 1) / (2 * e.min_ascii_values)) {
                records = count_lines_left(e.count);
            }
            begin_element(ei, records);
            for (size_t r = 0; r < e.count; ++r) {
                if (!next_line()) fail_here(ended_after(e, r));  // (r == records when fewer)
                if (at_cut_line(ei, r))
                    fail_here(ended_after(e, r) + " (the last line is cut short)");
                read_ascii_record(ei, r);
            }
        }
        if (next_line()) fail_here("unexpected data after the last element");
    }
};

}  // namespace

MeshData load_ply_from_memory(std::string_view bytes, const std::string& name_for_errors) {
    const PlyHeader header = parse_header(bytes, name_for_errors);
    MeshData mesh;
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

MeshData load_ply(const std::string& path) {
    return load_ply_from_memory(read_model_file(path).view(), path);
}

}  // namespace raylane
