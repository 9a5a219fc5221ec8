// io: Wavefront MTL material libraries (load_mtl.h).
#include "io/load_mtl.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace raylane {

namespace {

/// The line's tokens, up to a `#` comment.
std::vector<std::string_view> tokens_of(std::string_view line) {
    if (const size_t hash = line.find('#'); hash != std::string_view::npos)
        line = line.substr(0, hash);
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        size_t j = i;
        while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
        if (j > i) out.push_back(line.substr(i, j - i));
        i = j;
    }
    return out;
}

bool is_number(std::string_view t) {
    float v = 0.0f;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && end == t.data() + t.size();
}

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

/// Reads one MTL file's lines, keeping the position for errors.
struct MtlReader {
    const std::string& file;
    int line = 0;
    MtlLibrary lib;

    [[noreturn]] void fail(const std::string& reason) const {
        throw InputError(file + ":" + std::to_string(line) + ": " + reason);
    }

    float number(std::string_view t) const {
        float v = 0.0f;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (ec != std::errc() || end != t.data() + t.size() || !std::isfinite(v))
            fail("expected a number, got '" + std::string(t) + "'");
        return v;
    }

    /// Kd r g b, or Kd v (grey); "Kd spectral ..." and "Kd xyz ..." are refused.
    vec3 colour(const std::vector<std::string_view>& t) const {
        if (t.size() == 2) return vec3(number(t[1]));
        if (t.size() == 4) return vec3(number(t[1]), number(t[2]), number(t[3]));
        fail(std::string(t[0]) + " needs 1 or 3 numbers");
    }

    /// The file of a texture line: past the options, the rest of the line, '\' made '/'.
    std::string texture_file(std::string_view raw_line, const std::vector<std::string_view>& t) {
        // options and how many values follow each
        static const std::pair<const char*, int> options[] = {
            {"-blendu", 1},  {"-blendv", 1}, {"-bm", 1}, {"-boost", 1}, {"-cc", 1}, {"-clamp", 1},
            {"-imfchan", 1}, {"-mm", 2},     {"-o", 3},  {"-s", 3},     {"-t", 3},  {"-texres", 1}};
        size_t k = 1;
        while (k < t.size() && t[k].size() > 1 && t[k][0] == '-') {
            int values = 0;
            for (const auto& [name, n] : options)
                if (lower(t[k]) == name) values = n;
            if (values == 0) fail("unknown texture option '" + std::string(t[k]) + "'");
            // -mm, -o, -s and -t take up to 2 or 3 numbers: those that follow; the last token
            // is always the file
            size_t taken = 0;
            while (taken < size_t(values) && k + 1 + taken < t.size() - 1 &&
                   (values == 1 || is_number(t[k + 1 + taken])))
                ++taken;
            k += 1 + taken;
        }
        if (k >= t.size()) fail(std::string(t[0]) + " names no file");
        // the rest of the line from the first file token, so names may hold spaces
        std::string_view rest = raw_line.substr(size_t(t[k].data() - raw_line.data()));
        if (const size_t hash = rest.find('#'); hash != std::string_view::npos)
            rest = rest.substr(0, hash);
        while (!rest.empty() && std::isspace(static_cast<unsigned char>(rest.back())))
            rest.remove_suffix(1);
        std::string name(rest);
        std::replace(name.begin(), name.end(), '\\', '/');
        return name;
    }

    void ignore(std::string_view key) {
        const std::string k(key);
        if (std::find(lib.ignored.begin(), lib.ignored.end(), k) == lib.ignored.end())
            lib.ignored.push_back(k);
    }

    MtlMaterial& current(std::string_view key) {
        if (lib.materials.empty()) fail(std::string(key) + " before any newmtl");
        return lib.materials.back();
    }

    void read_line(std::string_view raw) {
        const std::vector<std::string_view> t = tokens_of(raw);
        if (t.empty()) return;
        const std::string key = lower(t[0]);
        if (key == "newmtl") {
            if (t.size() < 2) fail("newmtl needs a name");
            MtlMaterial m;
            m.name = std::string(t[1]);
            lib.materials.push_back(std::move(m));
        } else if (key == "kd") {
            current(t[0]).kd = colour(t);
        } else if (key == "ks") {
            current(t[0]).ks = colour(t);
        } else if (key == "ke") {
            current(t[0]).ke = colour(t);
        } else if (key == "ns" || key == "ni" || key == "d" || key == "tr" || key == "illum") {
            if (t.size() != 2) fail(std::string(t[0]) + " needs one number");
            MtlMaterial& m = current(t[0]);
            const float v = number(t[1]);
            if (key == "ns") m.ns = v;
            if (key == "ni") m.ni = v;
            if (key == "d") m.d = v;
            if (key == "tr") m.d = 1.0f - v;
            if (key == "illum") m.illum = int(v);
            if ((key == "d" || key == "tr") && m.d < 1.0f) ignore(t[0]);
        } else if (key == "map_kd") {
            current(t[0]).map_kd = texture_file(raw, t);
        } else if (key == "map_bump" || key == "bump" || key == "norm") {
            current(t[0]).map_bump = texture_file(raw, t);
        } else if (key != "ka") {  // Ka: Raylane's ambient term is k_a c_d
            ignore(t[0]);          // Tf, map_Ks, map_d, refl, Pr, ...
        }
    }
};

}  // namespace

MtlLibrary parse_mtl(std::string_view text, const std::string& path_for_errors) {
    MtlReader r{path_for_errors, 0, {}};
    size_t start = 0;
    while (start < text.size()) {
        // LF, CR LF or CR alone end a line
        size_t end = start;
        while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
        ++r.line;
        r.read_line(text.substr(start, end - start));
        if (end < text.size() && text[end] == '\r' && end + 1 < text.size() &&
            text[end + 1] == '\n')
            ++end;
        start = end + 1;
    }
    return r.lib;
}

MtlLibrary load_mtl(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot read the material library");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_mtl(text.str(), path);
}

Material material_from_mtl(const MtlMaterial& m) {
    Material out;
    out.name = m.name;
    out.c_d = m.kd;
    out.k_d = 1.0f;
    out.k_a = 0.1f;
    const float ks = std::max(m.ks.x, std::max(m.ks.y, m.ks.z));
    out.c_s = m.ks;
    out.k_s = ks > 0.0f ? 1.0f : 0.0f;
    out.exponent = std::max(1.0f, m.ns);
    out.emission = glm::max(m.ke, vec3(0.0f));
    if (m.illum == 3 || m.illum == 5) out.reflection = ks;
    if (m.illum == 4 || m.illum == 6 || m.illum == 7 || m.illum == 9) {
        out.refractive = true;
        out.ior = m.ni >= 1.0f ? m.ni : 1.5f;
    }
    return out;
}

}  // namespace raylane
