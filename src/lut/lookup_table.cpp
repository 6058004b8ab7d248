#include "bssrdf/lut/lookup_table.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"

namespace bssrdf {

void LookupTable::add_channel(std::string name, std::string description, std::vector<double> values) {
  if (values.size() != width * height)
    throw InvalidInput("table channel " + name, std::to_string(values.size()) + " values",
                       std::to_string(width * height) + " (width x height)");
  for (const auto& c : channels)
    if (c.name == name) throw InvalidInput("table channel", "'" + name + "'", "a name not used yet");
  channels.push_back({std::move(name), std::move(description), std::move(values)});
}

void LookupTable::set(const std::string& name, AttributeValue value) {
  for (auto& a : attributes)
    if (a.name == name) {
      a.value = std::move(value);
      return;
    }
  attributes.push_back({name, std::move(value)});
}

const TableChannel& LookupTable::channel(const std::string& name) const {
  for (const auto& c : channels)
    if (c.name == name) return c;
  throw InvalidInput("table channel", "'" + name + "'", "one of the table's channels");
}

const AttributeValue* LookupTable::attribute(const std::string& name) const {
  for (const auto& a : attributes)
    if (a.name == name) return &a.value;
  return nullptr;
}

std::string to_json(const LookupTable& table) {
  // ordered_json keeps the attribute order as written, so the file reads top-down.
  nlohmann::ordered_json doc;
  doc["format"] = "bssrdf-lut";
  doc["version"] = 1;
  doc["kind"] = table.kind;
  doc["width"] = table.width;
  doc["height"] = table.height;
  auto& attributes = doc["attributes"] = nlohmann::ordered_json::object();
  for (const auto& a : table.attributes) std::visit([&](const auto& v) { attributes[a.name] = v; }, a.value);
  for (const auto* axis : {&table.x_axis, &table.y_axis})
    if (!axis->values.empty())
      doc["axes"][axis == &table.x_axis ? "x" : "y"] = {{"name", axis->name}, {"values", axis->values}};
  doc["channels"] = nlohmann::ordered_json::array();
  for (const auto& c : table.channels) {
    nlohmann::ordered_json values = nlohmann::ordered_json::array();
    for (double v : c.values)
      values.push_back(std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr));
    doc["channels"].push_back({{"name", c.name}, {"description", c.description}, {"values", std::move(values)}});
  }
  return doc.dump(1) + "\n";
}

std::string to_csv(const LookupTable& table) {
  std::ostringstream out;
  // Which model produced the numbers, why when it was not the exact one, and the colour integration of a spectral
  // medium: leading comments.
  for (const char* key : {"bssrdf:model", "bssrdf:model_choice", "bssrdf:colour"})
    if (const auto* v = table.attribute(key); v && std::holds_alternative<std::string>(*v))
      out << "# " << (key + 7) << ": " << std::get<std::string>(*v) << '\n';
  const bool two_d = table.height > 1;
  const bool y_axis = two_d && table.y_axis.values.size() == table.height,
             x_axis = two_d && table.x_axis.values.size() == table.width;
  if (two_d) out << "row,column";
  if (y_axis) out << ',' << table.y_axis.name;
  if (x_axis) out << ',' << table.x_axis.name;
  for (std::size_t i = 0; i < table.channels.size(); ++i) out << (i || two_d ? "," : "") << table.channels[i].name;
  out << '\n';
  for (std::size_t y = 0; y < table.height; ++y)
    for (std::size_t x = 0; x < table.width; ++x) {
      if (two_d) out << y << ',' << x;
      if (y_axis) out << ',' << format_number(table.y_axis.values[y]);
      if (x_axis) out << ',' << format_number(table.x_axis.values[x]);
      for (std::size_t i = 0; i < table.channels.size(); ++i)
        out << (i || two_d ? "," : "") << format_number(table.channels[i].values[y * table.width + x]);
      out << '\n';
    }
  return out.str();
}

}  // namespace bssrdf
