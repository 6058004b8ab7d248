#include "bssrdf/io/layers_json.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "bssrdf/error.hpp"
#include "data_file.hpp"

namespace bssrdf {
namespace {
// A layer's index when the file gives none: soft tissue's (water 1.33, fat and dermis 1.4-1.46), not
// 1, which would make a scattering layer index-matched to air.
constexpr double kDefaultLayerIndex = 1.4;

using json = nlohmann::json;

// A char iterator that counts the lines it has passed, so a SAX pass can tell where each value is.
struct LineCounter {
  int line = 1;
  bool last_was_newline = false;
  // The line of the token just read: the lexer reads one character past a number, which may be
  // the newline ending it.
  int token_line() const { return last_was_newline ? line - 1 : line; }
};

struct CountingIterator {
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  const char* p = nullptr;
  LineCounter* counter = nullptr;
  reference operator*() const { return *p; }
  CountingIterator& operator++() {
    counter->last_was_newline = *p == '\n';
    if (counter->last_was_newline) ++counter->line;
    ++p;
    return *this;
  }
  CountingIterator operator++(int) {
    auto copy = *this;
    ++*this;
    return copy;
  }
  bool operator==(const CountingIterator& o) const { return p == o.p; }
  bool operator!=(const CountingIterator& o) const { return p != o.p; }
};

// Records the line of every value by its JSON pointer ("/layers/1/sigma_a/2").
class Locator : public json::json_sax_t {
 public:
  explicit Locator(const LineCounter& counter) : counter_(counter) {}
  std::map<std::string, int> lines;

  bool null() override { return scalar(); }
  bool boolean(bool) override { return scalar(); }
  bool number_integer(json::number_integer_t) override { return scalar(); }
  bool number_unsigned(json::number_unsigned_t) override { return scalar(); }
  bool number_float(json::number_float_t, const json::string_t&) override { return scalar(); }
  bool string(json::string_t&) override { return scalar(); }
  bool binary(json::binary_t&) override { return scalar(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(json::string_t& k) override {
    frames_.back().key = k;
    lines[path()] = counter_.token_line();
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  struct Frame {
    bool object;
    std::string key;
    std::size_t index = 0;
  };
  std::vector<Frame> frames_;
  const LineCounter& counter_;

  std::string path() const {
    std::string p;
    for (const Frame& f : frames_) p += "/" + (f.object ? f.key : std::to_string(f.index));
    return p;
  }
  void record_element() {
    if (frames_.empty() || !frames_.back().object) lines.emplace(path(), counter_.token_line());
  }
  bool scalar() {
    record_element();
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
    return true;
  }
  bool open(bool object) {
    record_element();
    frames_.push_back({object, {}, 0});
    return true;
  }
  bool close() {
    frames_.pop_back();
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
    return true;
  }
};

class Parser {
 public:
  Parser(const std::string& text, std::string name) : name_(std::move(name)) {
    doc_ = parse_json_document(text, name_);  // bounded depth, so the locator below stays cheap
    LineCounter counter;
    Locator locator(counter);
    CountingIterator first{text.data(), &counter}, last{text.data() + text.size(), &counter};
    json::sax_parse(first, last, &locator);
    lines_ = std::move(locator.lines);
  }

  [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
    std::string p = pointer;
    while (true) {
      auto it = lines_.find(p);
      if (it != lines_.end()) throw FileError(name_, it->second, message);
      if (p.empty()) break;
      p.resize(p.rfind('/'));
    }
    throw FileError(name_, 0, message);
  }

  const json& doc() const { return doc_; }

  // "/layers/1/sigma_a" -> "layers[1].sigma_a" for messages.
  static std::string field(const std::string& pointer) {
    std::string out;
    std::size_t i = 1;
    while (i <= pointer.size() && i > 0) {
      const auto next = pointer.find('/', i);
      const std::string part = pointer.substr(i, next == std::string::npos ? std::string::npos : next - i);
      if (!part.empty() && std::all_of(part.begin(), part.end(), ::isdigit)) {
        out += "[" + part + "]";
      } else {
        out += (out.empty() ? "" : ".") + part;
      }
      if (next == std::string::npos) break;
      i = next + 1;
    }
    return out;
  }

  double number(const json& v, const std::string& pointer) const {
    if (!v.is_number()) fail(pointer, field(pointer) + " = " + json_excerpt(v) + ": expected a number");
    return v.get<double>();
  }

  void check_keys(const json& object, const std::string& pointer, const std::set<std::string>& allowed) const {
    for (const auto& [key, value] : object.items())
      if (!allowed.count(key)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(pointer + "/" + key, "unknown key '" + key + "'" + (pointer.empty() ? "" : " in " + field(pointer)) +
                                      " (accepted: " + list + ")");
      }
  }

 private:
  std::string name_;
  json doc_;
  std::map<std::string, int> lines_;
};

}  // namespace

LayersFile parse_layers_json(const std::string& text, const std::string& name) {
  const Parser parser(text, name);
  const json& doc = parser.doc();
  if (!doc.is_object()) parser.fail("", "expected a JSON object with \"format\": \"bssrdf-layers\"");
  parser.check_keys(
      doc, "",
      {"format", "version", "unit", "ambient_above", "ambient_below", "channels", "layers", "description", "notes"});
  if (!doc.contains("format") || doc["format"] != "bssrdf-layers")
    parser.fail(doc.contains("format") ? "/format" : "", "format: expected \"bssrdf-layers\"");
  if (!doc.contains("version") || !doc["version"].is_number() || doc["version"].get<double>() != 1)
    parser.fail(doc.contains("version") ? "/version" : "", "version: expected 1 (the only version this build reads)");
  LayersFile file;
  if (doc.contains("unit")) {
    if (!doc["unit"].is_string()) parser.fail("/unit", "unit: expected a string such as \"mm\"");
    try {
      file.unit = parse_length_unit(doc["unit"].get<std::string>(), "unit");
    } catch (const InvalidInput& e) {
      parser.fail("/unit", e.what());
    }
  }
  const double mm = millimetres_per(file.unit);
  LayerStack& stack = file.stack;
  const auto positive_index = [&](const char* key, double fallback) {
    if (!doc.contains(key)) return fallback;
    const double v = parser.number(doc[key], std::string("/") + key);
    if (!(v > 0))
      parser.fail(std::string("/") + key, std::string(key) + " = " + format_number(v) + ": accepted range is > 0");
    return v;
  };
  stack.ambient_above = positive_index("ambient_above", 1.0);
  stack.ambient_below = positive_index("ambient_below", 1.0);

  if (!doc.contains("layers") || !doc["layers"].is_array() || doc["layers"].empty())
    parser.fail(doc.contains("layers") ? "/layers" : "", "layers: expected a non-empty array of layer objects");
  const json& layers = doc["layers"];

  // Channel count: from "channels", else the longest per-channel list.
  std::size_t channels = 0;
  if (doc.contains("channels")) {
    const json& names = doc["channels"];
    if (!names.is_array() || names.empty()) parser.fail("/channels", "channels: expected a non-empty array of names");
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!names[i].is_string())
        parser.fail("/channels/" + std::to_string(i), "channels[" + std::to_string(i) + "]: expected a string");
      stack.channel_names.push_back(names[i].get<std::string>());
    }
    channels = stack.channel_names.size();
  } else {
    channels = 1;
    for (const json& layer : layers)
      if (layer.is_object())
        for (const char* key : {"sigma_a", "sigma_s", "g"})
          if (layer.contains(key) && layer[key].is_array()) channels = std::max(channels, layer[key].size());
    stack.channel_names = default_channel_names(channels);
  }

  for (std::size_t i = 0; i < layers.size(); ++i) {
    const std::string at = "/layers/" + std::to_string(i);
    const json& l = layers[i];
    if (!l.is_object()) parser.fail(at, Parser::field(at) + ": expected an object");
    parser.check_keys(l, at, {"name", "thickness", "n", "eta", "sigma_a", "sigma_s", "g", "description", "notes"});
    Layer layer;
    layer.n = kDefaultLayerIndex;
    if (l.contains("name")) {
      if (!l["name"].is_string()) parser.fail(at + "/name", Parser::field(at + "/name") + ": expected a string");
      layer.name = l["name"].get<std::string>();
    }
    if (l.contains("n") && l.contains("eta"))
      parser.fail(at + "/eta", Parser::field(at) + ": give \"n\" or \"eta\", not both");
    for (const char* key : {"n", "eta"})
      if (l.contains(key)) {
        layer.n = parser.number(l[key], at + "/" + key);
        if (!(layer.n > 0))
          parser.fail(at + "/" + key,
                      Parser::field(at + "/" + key) + " = " + format_number(layer.n) + ": accepted range is > 0");
      }
    if (l.contains("thickness") && !l["thickness"].is_null()) {
      const double t = parser.number(l["thickness"], at + "/thickness");
      if (!(t > 0))
        parser.fail(at + "/thickness", Parser::field(at + "/thickness") + " = " + format_number(t) +
                                           ": accepted range is > 0, or null for a semi-infinite last layer");
      layer.thickness = t * mm;
    } else if (i + 1 != layers.size()) {
      parser.fail(l.contains("thickness") ? at + "/thickness" : at,
                  Parser::field(at) + ": thickness missing or null (semi-infinite), allowed only for the last layer");
    }
    const auto per_channel = [&](const char* key, double fallback, bool required) {
      const std::string p = at + "/" + key;
      std::vector<double> values;
      if (!l.contains(key)) {
        if (required) parser.fail(at, Parser::field(at) + ": missing \"" + key + "\"");
        return std::vector<double>(channels, fallback);
      }
      const json& v = l[key];
      if (v.is_array()) {
        for (std::size_t c = 0; c < v.size(); ++c) values.push_back(parser.number(v[c], p + "/" + std::to_string(c)));
        if (values.size() == 1 && channels > 1) values.assign(channels, values[0]);
        if (values.size() != channels)
          parser.fail(p, Parser::field(p) + ": " + std::to_string(values.size()) + " values given, but there are " +
                             std::to_string(channels) + " channels (give one per channel, or one for all)");
      } else {
        values.assign(channels, parser.number(v, p));
      }
      return values;
    };
    layer.sigma_a = per_channel("sigma_a", 0, true);
    layer.sigma_s = per_channel("sigma_s", 0, true);
    layer.g = per_channel("g", 0, false);
    for (std::size_t c = 0; c < channels; ++c) {
      const auto bad = [&](const char* key, double v, const char* range) {
        const std::string p = at + "/" + key;
        const std::string element = l[key].is_array() && l[key].size() > 1 ? p + "/" + std::to_string(c) : p;
        parser.fail(element, Parser::field(p) + "[" + stack.channel_names[c] + "] = " + format_number(v) +
                                 ": accepted range is " + range);
      };
      if (!(layer.sigma_a[c] >= 0)) bad("sigma_a", layer.sigma_a[c], ">= 0");
      if (!(layer.sigma_s[c] >= 0)) bad("sigma_s", layer.sigma_s[c], ">= 0");
      if (!(layer.g[c] > -1 && layer.g[c] < 1)) bad("g", layer.g[c], "-1 < g < 1");
      layer.sigma_a[c] /= mm;
      layer.sigma_s[c] /= mm;
    }
    stack.layers.push_back(std::move(layer));
  }
  try {
    stack.validate();
  } catch (const InvalidInput& e) {
    // What remains (duplicate channel names, a clear semi-infinite layer) concerns the whole file.
    std::string where = "";
    const std::string what = e.what();
    if (what.rfind("layers[", 0) == 0) where = "/layers/" + what.substr(7, what.find(']') - 7);
    if (what.rfind("channels", 0) == 0) where = "/channels";
    parser.fail(where, what);
  }
  return file;
}

LayersFile read_layers_json(const std::filesystem::path& path) {
  return parse_layers_json(read_data_file(path, "the layers file"), path.string());
}

}  // namespace bssrdf

namespace bssrdf {

std::string layers_json(const LayerStack& stack) {
  nlohmann::json doc = {{"format", "bssrdf-layers"},
                        {"version", 1},
                        {"unit", "mm"},
                        {"ambient_above", stack.ambient_above},
                        {"ambient_below", stack.ambient_below},
                        {"channels", stack.channel_names}};
  doc["layers"] = nlohmann::json::array();
  for (const auto& layer : stack.layers)
    doc["layers"].push_back(
        {{"name", layer.name},
         {"thickness", layer.thickness == kSemiInfinite ? nlohmann::json(nullptr) : nlohmann::json(layer.thickness)},
         {"n", layer.n},
         {"sigma_a", layer.sigma_a},
         {"sigma_s", layer.sigma_s},
         {"g", layer.g}});
  return doc.dump(2) + "\n";
}

}  // namespace bssrdf
