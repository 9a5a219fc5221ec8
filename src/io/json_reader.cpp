// io: strict reading of JSON (json_reader.h): parsing with a depth limit and no duplicate keys,
// typed reads whose errors name the file and the JSON path.
#include "io/json_reader.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <type_traits>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/error.h"

namespace raylane {

/// `s` in double quotes, with quotes, backslashes and control characters escaped (one line).
std::string json_quoted(std::string_view s) {
    std::string out = "\"";
    for (char ch : s) {
        auto c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += ch;
        } else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", unsigned{c});
            out += buf;
        } else {
            out += ch;
        }
    }
    return out + "\"";
}

/// `v` with 9 significant digits (a float's value, whatever it was written as).
std::string format_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

/// The path of member `key` of the value at `parent`: "$.a.b", or "$.a[\"odd key\"]".
std::string member_path(const std::string& parent, std::string_view key) {
    bool plain = !key.empty() && !(key[0] >= '0' && key[0] <= '9');
    for (char c : key) {
        plain = plain && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                          (c >= '0' && c <= '9') || c == '_');
    }
    if (key.size() > 60) {  // a message names the key, not a megabyte of it
        size_t cut = 60;    // on a UTF-8 character's first byte
        while (cut > 0 && (static_cast<unsigned char>(key[cut]) & 0xc0) == 0x80) --cut;
        const std::string shown = json_quoted(key.substr(0, cut));
        return parent + "[" + shown.substr(0, shown.size() - 1) + "...\"]";
    }
    return plain ? parent + "." + std::string(key) : parent + "[" + json_quoted(key) + "]";
}

/// The path of element `index` of the array at `parent`: "$.a[3]".
std::string element_path(const std::string& parent, size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

/// "an object", "an array", ...: what a value is, for "must be X, got Y".
std::string describe_type(const Json& j) {
    if (j.is_object()) return "an object";
    if (j.is_array())
        return j.empty() ? "an empty array" : "an array of " + std::to_string(j.size());
    if (j.is_string()) return "a string";
    if (j.is_boolean()) return "a boolean";
    if (j.is_number()) return "a number";
    return "null";
}

/// The first max_items of `items` separated by commas ("none" when empty).
std::string join(const std::vector<std::string>& items, size_t max_items) {
    std::string out;
    for (size_t i = 0; i < items.size() && i < max_items; ++i) out += (i ? ", " : "") + items[i];
    if (items.size() > max_items) out += ", ...";
    return out.empty() ? "none" : out;
}

namespace {

/// Bytes outside printable ASCII written as \xNN, so a message stays one printable line.
std::string printable(std::string_view s) {
    std::string out;
    for (char ch : s) {
        auto c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c >= 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", unsigned{c});
            out += buf;
        } else {
            out += ch;
        }
    }
    return out;
}

/// 1-based line and column of byte `index` of `text`.
std::string line_column(std::string_view text, size_t index) {
    index = std::min(index, text.size());
    size_t line = 1, line_start = 0;
    for (size_t i = 0; i < index; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    return std::to_string(line) + ":" + std::to_string(index - line_start + 1);
}

/// Byte index of the first bracket that opens level `limit + 1`, or npos. Strings are skipped
/// with their escapes, so the count is exact for any text the JSON lexer accepts up to there.
size_t find_depth_overflow(std::string_view text, int limit) {
    int depth = 0;
    bool in_string = false, escaped = false;
    for (size_t i = 0; i < text.size(); ++i) {
        char c = text[i];
        if (in_string) {
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > limit) return i;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return std::string_view::npos;
}

// ---------------------------------------------------------------------------------------------
// Parsing: a SAX handler that builds the DOM (nlohmann's sax_parse is iterative, so the depth
// limit is what bounds the recursion of everything that later walks the tree).

// DomBuilder appends an object's members to ordered_json's vector directly (key() below)
static_assert(std::is_base_of_v<Json::object_t::Container, Json::object_t>,
              "nlohmann::ordered_map keeps its members in a std::vector");

class DomBuilder {
  public:
    explicit DomBuilder(int max_depth) : max_depth_(size_t(max_depth)) {}

    using number_integer_t = Json::number_integer_t;
    using number_unsigned_t = Json::number_unsigned_t;
    using number_float_t = Json::number_float_t;
    using string_t = Json::string_t;
    using binary_t = Json::binary_t;

    Json root;
    bool too_deep = false;
    std::string duplicate_key_path;  ///< set when the parse stopped at a repeated key
    bool syntax_error = false;
    size_t error_byte = 0;
    std::string error_message;

    bool null() { return put(Json(nullptr)); }
    bool boolean(bool v) { return put(Json(v)); }
    bool number_integer(number_integer_t v) { return put(Json(v)); }
    bool number_unsigned(number_unsigned_t v) { return put(Json(v)); }
    bool number_float(number_float_t v, const string_t&) { return put(Json(v)); }
    bool string(string_t& v) { return put(Json(std::move(v))); }
    bool binary(binary_t&) { return false; }  // never produced by JSON text
    bool start_object(size_t) {
        keys_.emplace_back();
        return open(Json::object());
    }
    bool start_array(size_t) { return open(Json::array()); }
    bool end_object() {
        keys_.pop_back();
        return close();
    }
    bool end_array() { return close(); }

    bool key(string_t& k) {
        // the object's keys in a hash set: ordered_json looks keys up by a linear search, which
        // made an object of n keys cost n^2 (100,000 keys: 30 s)
        if (!keys_.back().insert(k).second) {
            duplicate_key_path = member_path(current_path(), k);
            return false;
        }
        Json::object_t::Container& members = *stack_.back()->get_ptr<Json::object_t*>();
        pending_ = &members.emplace_back(std::move(k), nullptr).second;
        return true;
    }

    bool parse_error(size_t byte, const std::string&, const nlohmann::detail::exception& e) {
        syntax_error = true;
        error_byte = byte;
        std::string what = e.what();
        size_t at = what.find("syntax error");
        if (at == std::string::npos) {
            at = what.find("] ");
            at = at == std::string::npos ? 0 : at + 2;
        }
        // nlohmann's "last read" may be the whole input: 200 bytes of the reason at most
        error_message = what.size() - at > 200 ? printable(what.substr(at, 200)) + "..."
                                               : printable(what.substr(at));
        return false;
    }

  private:
    size_t max_depth_;          ///< deepest nesting accepted
    std::vector<Json*> stack_;  ///< open arrays and objects, outermost first
    std::vector<std::unordered_set<std::string>> keys_;  ///< the keys of each open object
    Json* pending_ = nullptr;  ///< slot of the last key read, in the innermost object
    Json* last_ = nullptr;

    bool put(Json&& v) {
        if (stack_.empty()) {
            root = std::move(v);
            last_ = &root;
        } else if (stack_.back()->is_array()) {
            stack_.back()->push_back(std::move(v));
            last_ = &stack_.back()->back();
        } else {
            *pending_ = std::move(v);
            last_ = pending_;
        }
        return true;
    }
    bool open(Json&& v) {
        if (stack_.size() >= max_depth_) {
            too_deep = true;
            return false;
        }
        put(std::move(v));
        stack_.push_back(last_);  // the parent does not grow while this child is open
        return true;
    }
    bool close() {
        stack_.pop_back();
        return true;
    }
    std::string current_path() const {
        std::string path = "$";
        for (size_t i = 1; i < stack_.size(); ++i) {
            const Json& parent = *stack_[i - 1];
            path = parent.is_array() ? element_path(path, parent.size() - 1)
                                     : member_path(path, std::prev(parent.end()).key());
        }
        return path;
    }
};

}  // namespace

Json parse_json(std::string_view text, const std::string& file, int max_depth) {
    DomBuilder builder(max_depth);
    bool ok = Json::sax_parse(text.data(), text.data() + text.size(), &builder,
                              nlohmann::json::input_format_t::json, true, false);
    if (ok) return std::move(builder.root);
    if (builder.too_deep) {
        size_t at = find_depth_overflow(text, max_depth);
        throw InputError(file + ":" + line_column(text, at) + ": JSON nested deeper than " +
                         std::to_string(max_depth) + " levels");
    }
    if (!builder.duplicate_key_path.empty()) {
        throw InputError(file + ": " + builder.duplicate_key_path + ": duplicate key");
    }
    size_t index = builder.error_byte > 0 ? builder.error_byte - 1 : 0;  // last byte read
    throw InputError(file + ":" + line_column(text, index) + ": " +
                     (builder.syntax_error ? builder.error_message : "malformed JSON"));
}

void JsonReader::fail(const JsonNode& n, const std::string& reason) const {
    throw InputError(file_ + ": " + n.path + ": " + reason);
}

void JsonReader::expect(const JsonNode& n, bool ok, const char* what) const {
    if (!ok) fail(n, std::string("must be ") + what + ", got " + describe_type(*n.j));
}

void JsonReader::expect_keys(const JsonNode& n,
                             std::initializer_list<std::string_view> allowed) const {
    expect(n, n.j->is_object(), "an object");
    for (auto it = n.j->begin(); it != n.j->end(); ++it) {
        if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
        std::vector<std::string> names(allowed.begin(), allowed.end());
        fail(JsonNode{&it.value(), member_path(n.path, it.key())},
             "unknown key (expected: " + join(names, names.size()) + ")");
    }
}

const Json* JsonReader::find(const JsonNode& n, std::string_view key) {
    auto it = n.j->find(std::string(key));
    return it == n.j->end() ? nullptr : &*it;
}

JsonNode JsonReader::child(const JsonNode& n, std::string_view key) const {
    const Json* v = find(n, key);
    JsonNode c{v, member_path(n.path, key)};
    if (!v) fail(c, "missing (required)");
    return c;
}

double JsonReader::number(const JsonNode& n) const {
    expect(n, n.j->is_number(), "a number");
    double v = n.j->get<double>();
    if (!std::isfinite(v)) fail(n, "must be finite");
    if (std::abs(v) > double(FLT_MAX)) {
        fail(n, format_number(v) + " is outside the float range");
    }
    return v;
}

double JsonReader::number(const JsonNode& n, Sign sign) const {
    double v = number(n);
    if (sign == Sign::positive && !(v > 0.0)) fail(n, "must be > 0, got " + format_number(v));
    if (sign == Sign::non_negative && v < 0.0) {
        fail(n, "must be >= 0, got " + format_number(v));
    }
    return v;
}

float JsonReader::real(const JsonNode& n, Sign sign) const {
    auto v = float(number(n, sign));
    if (sign == Sign::positive && !(v > 0.0f)) fail(n, "must be > 0 as a float");
    return v;
}

int JsonReader::integer(const JsonNode& n, int lo, int hi) const {
    expect(n, n.j->is_number_integer(), "an integer");
    std::string range = " an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
    if (n.j->is_number_unsigned()) {
        auto v = n.j->get<uint64_t>();
        if (v < uint64_t(std::max(lo, 0)) || v > uint64_t(hi)) {
            fail(n, "must be" + range + ", got " + std::to_string(v));
        }
        return int(v);
    }
    auto v = n.j->get<int64_t>();
    if (v < lo || v > hi) fail(n, "must be" + range + ", got " + std::to_string(v));
    return int(v);
}

bool JsonReader::boolean(const JsonNode& n) const {
    expect(n, n.j->is_boolean(), "true or false");
    return n.j->get<bool>();
}

std::string JsonReader::text(const JsonNode& n) const {
    expect(n, n.j->is_string(), "a string");
    return n.j->get<std::string>();
}

int JsonReader::choice(const JsonNode& n, std::initializer_list<const char*> choices) const {
    std::string s = text(n);
    std::vector<std::string> names;
    for (const char* c : choices) {
        if (s == c) return int(names.size());
        names.push_back(json_quoted(c));
    }
    fail(n, "must be one of " + join(names, names.size()) + ", got " + json_quoted(s));
}

glm::dvec3 JsonReader::dvec3(const JsonNode& n, Sign sign) const {
    expect(n, n.j->is_array() && n.j->size() == 3, "an array of 3 numbers");
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) {
        v[i] = number(JsonNode{&(*n.j)[size_t(i)], element_path(n.path, size_t(i))}, sign);
    }
    return v;
}

vec3 JsonReader::vector(const JsonNode& n) const { return vec3(dvec3(n)); }

vec3 JsonReader::color(const JsonNode& n) const { return vec3(dvec3(n, Sign::non_negative)); }

vec3 JsonReader::direction(const JsonNode& n) const {
    glm::dvec3 v = dvec3(n);
    double len = glm::length(v);
    if (!(len > 0.0)) fail(n, "must not be the zero vector");
    return vec3(v / len);
}

}  // namespace raylane
