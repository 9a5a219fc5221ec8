// io: the PLY header parsed and checked (ply_header.h). The body is read in load_ply.cpp.
#include "io/ply_header.h"

#include <charconv>
#include <iterator>

#include "core/error.h"
#include "io/read_file.h"
#include "io/text_form.h"
#include "io/text_lines.h"

namespace raylane::ply {

namespace {

PlyType parse_type(std::string_view name) {
    for (size_t i = 1; i < std::size(type_info); ++i) {
        if (type_info[i].name == name || type_info[i].sized_name == name) {
            return static_cast<PlyType>(i);
        }
    }
    return PlyType::invalid;
}

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

/// The first line, `ply`; when it is not, what the file is instead, if it is something else.
void check_magic(std::string_view first_line, std::string_view bytes, const std::string& file) {
    Tokens tokens{first_line.data(), first_line.data() + first_line.size()};
    if (tokens.next() == "ply" && tokens.next().empty()) return;
    refuse_utf16(bytes, file);
    refuse_gzip(bytes, file);
    fail_line(file, 1, "not a PLY file: the first line must be 'ply'");
}

}  // namespace

[[noreturn]] void fail_line(const std::string& file, size_t line, const std::string& reason) {
    throw InputError(file + ":" + std::to_string(line) + ": " + reason);
}

[[noreturn]] void fail_byte(const std::string& file, size_t offset, const std::string& reason) {
    throw InputError(file + ": byte " + std::to_string(offset) + ": " + reason);
}

std::string quoted(std::string_view text) { return quote_for_error(text); }

PlyHeader parse_header(std::string_view bytes, const std::string& file) {
    refuse_empty(bytes, file);
    PlyHeader header;
    LineCursor lines(bytes);
    std::string_view text;
    lines.next(text);
    check_magic(text, bytes, file);
    const bool cr_only = lines.line_end() == "\r";
    size_t line = 1;
    bool has_format = false;
    bool ended = false;
    while (!ended && lines.next(text)) {
        ++line;
        Tokens tokens{text.data(), text.data() + text.size()};
        std::string_view keyword = tokens.next();
        // a last line without its line end: the file was cut inside the header
        if (lines.line_end().empty() && keyword != "end_header")
            fail_line(file, line,
                      "the file ends inside the header, after " + quoted(text) +
                          " (no end_header line; is the file cut short?)");
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
    if (!ended) fail_line(file, line, "bad header: no end_header line");
    if (!has_format) fail_line(file, line, "bad header: no format line");
    // After a CR-only `ply` line, a CR LF after end_header is a CR and the body's first byte.
    const bool body_starts_with_lf = cr_only && lines.line_end() == "\r\n";
    header.body_offset =
        static_cast<size_t>(lines.rest() - bytes.data()) - static_cast<size_t>(body_starts_with_lf);
    header.header_lines = line;
    finish_elements(file, line, header);
    return header;
}

}  // namespace raylane::ply
