// A small JSON Schema (2020-12) checker for the keywords materials/schema.json uses: type, const,
// enum, required, properties, additionalProperties: false, items, minItems, uniqueItems, minLength,
// minimum, exclusiveMinimum, exclusiveMaximum, oneOf, not, $ref to "#/$defs/...". Enough to test
// that the schema describes the bundled files and rejects what the loader rejects, without a new
// dependency. Returns the first violation as "path: keyword", or "" when the document conforms.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace bssrdf::test_schema {

using json = nlohmann::json;

inline bool has_type(const json& v, const std::string& type) {
  if (type == "object") return v.is_object();
  if (type == "array") return v.is_array();
  if (type == "string") return v.is_string();
  if (type == "number") return v.is_number();
  if (type == "integer")
    return v.is_number_integer() || (v.is_number() && v.get<double>() == static_cast<long long>(v.get<double>()));
  if (type == "boolean") return v.is_boolean();
  if (type == "null") return v.is_null();
  return false;
}

inline std::string check(const json& root, const json& schema, const json& v, const std::string& path) {
  if (schema.contains("$ref")) {
    const std::string ref = schema["$ref"];
    const std::string prefix = "#/$defs/";
    return check(root, root["$defs"][ref.substr(prefix.size())], v, path);
  }
  if (schema.contains("type") && !has_type(v, schema["type"])) return path + ": type";
  if (schema.contains("const") && v != schema["const"]) return path + ": const";
  if (schema.contains("enum")) {
    bool found = false;
    for (const auto& e : schema["enum"]) found |= e == v;
    if (!found) return path + ": enum";
  }
  if (v.is_number()) {
    const double x = v.get<double>();
    if (schema.contains("minimum") && x < schema["minimum"].get<double>()) return path + ": minimum";
    if (schema.contains("exclusiveMinimum") && x <= schema["exclusiveMinimum"].get<double>())
      return path + ": exclusiveMinimum";
    if (schema.contains("exclusiveMaximum") && x >= schema["exclusiveMaximum"].get<double>())
      return path + ": exclusiveMaximum";
  }
  if (v.is_string() && schema.contains("minLength") &&
      v.get<std::string>().size() < schema["minLength"].get<std::size_t>())
    return path + ": minLength";
  if (v.is_array()) {
    if (schema.contains("minItems") && v.size() < schema["minItems"].get<std::size_t>()) return path + ": minItems";
    if (schema.value("uniqueItems", false))
      for (std::size_t i = 0; i < v.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          if (v[i] == v[j]) return path + ": uniqueItems";
    if (schema.contains("items"))
      for (std::size_t i = 0; i < v.size(); ++i) {
        auto e = check(root, schema["items"], v[i], path + "[" + std::to_string(i) + "]");
        if (!e.empty()) return e;
      }
  }
  if (v.is_object()) {
    if (schema.contains("required"))
      for (const auto& key : schema["required"])
        if (!v.contains(key.get<std::string>())) return path + ": required " + key.get<std::string>();
    for (const auto& [key, value] : v.items()) {
      if (schema.contains("properties") && schema["properties"].contains(key)) {
        auto e = check(root, schema["properties"][key], value, path + "." + key);
        if (!e.empty()) return e;
      } else if (schema.contains("additionalProperties") && schema["additionalProperties"] == false) {
        return path + "." + key + ": additionalProperties";
      }
    }
  }
  if (schema.contains("not") && check(root, schema["not"], v, path).empty()) return path + ": not";
  if (schema.contains("oneOf")) {
    int matches = 0;
    for (const auto& s : schema["oneOf"]) matches += check(root, s, v, path).empty();
    if (matches != 1) return path + ": oneOf";
  }
  return "";
}

inline std::string validate(const json& schema, const json& document) { return check(schema, schema, document, "$"); }

}  // namespace bssrdf::test_schema
