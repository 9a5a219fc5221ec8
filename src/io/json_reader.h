// io: strict reading of JSON for the scene loader: a parser that bounds the nesting depth and
// rejects duplicate keys, and typed reads whose errors are one line naming the file and the
// JSON path of the value ("scene.json: $.objects[2].radius: must be > 0, got -1").
#pragma once

#include <cstddef>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/ray.h"

namespace raylane {

using Json = nlohmann::ordered_json;

/// The parsed tree of `text`. Throws InputError with one line: "file:line:column: reason" for
/// malformed JSON or nesting deeper than max_depth, "file: $.path: duplicate key".
Json parse_json(std::string_view text, const std::string& file, int max_depth);

/// `s` in double quotes, with quotes, backslashes and control characters escaped (one line).
std::string json_quoted(std::string_view s);
/// `v` with 9 significant digits (a float's value, whatever it was written as).
std::string format_number(double v);
/// The path of member `key` of the value at `parent`: "$.a.b", or "$.a[\"odd key\"]".
std::string member_path(const std::string& parent, std::string_view key);
/// The path of element `index` of the array at `parent`: "$.a[3]".
std::string element_path(const std::string& parent, size_t index);
/// "an object", "an array", ...: what a value is, for "must be X, got Y".
std::string describe_type(const Json& j);
/// The first max_items of `items` separated by commas ("none" when empty).
std::string join(const std::vector<std::string>& items, size_t max_items);

/// A value in the tree and its JSON path ("$.objects[2].radius").
struct JsonNode {
    const Json* j;
    std::string path;
};

enum class Sign { any, non_negative, positive };

/// Typed reads of the tree of one file. Each throws InputError("file: $.path: reason") when the
/// value is not what is asked for; numbers must be finite and within the float range.
class JsonReader {
  protected:
    explicit JsonReader(std::string file) : file_(std::move(file)) {}

    std::string file_;  ///< the file named in every message

    [[noreturn]] void fail(const JsonNode& n, const std::string& reason) const;
    /// fail with "must be <what>, got <its type>" unless `ok`.
    void expect(const JsonNode& n, bool ok, const char* what) const;
    /// `n` must be an object whose keys are all in `allowed`.
    void expect_keys(const JsonNode& n, std::initializer_list<std::string_view> allowed) const;
    /// Member `key` of the object `n`, or nullptr.
    static const Json* find(const JsonNode& n, std::string_view key);
    /// Member `key` of the object `n`, which must be there.
    JsonNode child(const JsonNode& n, std::string_view key) const;
    double number(const JsonNode& n) const;
    /// A number with its sign checked, kept in double (rounded to float where it is stored).
    double number(const JsonNode& n, Sign sign) const;
    float real(const JsonNode& n, Sign sign = Sign::any) const;
    int integer(const JsonNode& n, int lo, int hi) const;
    bool boolean(const JsonNode& n) const;
    std::string text(const JsonNode& n) const;
    /// Index of the string value in `choices`.
    int choice(const JsonNode& n, std::initializer_list<const char*> choices) const;
    glm::dvec3 dvec3(const JsonNode& n, Sign sign = Sign::any) const;
    /// A point in an object's own space, or an offset between points: not moved.
    vec3 vector(const JsonNode& n) const;
    vec3 color(const JsonNode& n) const;
    /// A direction, normalised in double; the zero vector is an error.
    vec3 direction(const JsonNode& n) const;
};

}  // namespace raylane
