// A lookup table as renderers consume it: a width x height grid of named float channels plus
// metadata that says what every number is (units, distance convention, normalisation, grid,
// interpolation, tolerance, material, model, tool version). Every table kind (radial,
// albedo-radius, transmission, pre-integrated, separable kernel, Gaussian mixture) converts to
// this one form, so the OpenEXR, JSON and CSV writers are shared.
//
//   LookupTable t{"radial", n, 1};
//   t.add_channel("R", "R(r), 1/mm^2", values);
//   t.set("bssrdf:unit", "mm");
//   write_file_atomically("skin.json", to_json(t));
//   write_file_atomically("skin.exr", encode_exr(t));   // io/exr_table.hpp
#pragma once

#include <cstddef>
#include <string>
#include <variant>
#include <vector>

namespace bssrdf {

struct TableChannel {
  std::string name;            // OpenEXR channel name, e.g. "R", "radius", "cdf.R"
  std::string description;     // what it holds, with its unit
  std::vector<double> values;  // row-major, width * height
};

using AttributeValue = std::variant<std::string, double, int>;

struct TableAttribute {
  std::string name;  // "bssrdf:unit", ...
  AttributeValue value;
};

// The coordinate of every column (x) or row (y) of a 2D table, for plots: written by CSV and JSON
// beside the channels (OpenEXR records the axes as attributes).
struct TableAxis {
  std::string name;            // e.g. "n_dot_l", "curvature (1/mm)"
  std::vector<double> values;  // width (x) or height (y) entries; empty: no axis
};

struct LookupTable {
  std::string kind;
  std::size_t width = 0, height = 1;
  TableAxis x_axis, y_axis;
  std::vector<TableChannel> channels;      // in the order written
  std::vector<TableAttribute> attributes;  // in the order written

  // Throws InvalidInput when the size does not match width * height or the name repeats.
  void add_channel(std::string name, std::string description, std::vector<double> values);
  void set(const std::string& name, AttributeValue value);         // replaces an existing attribute
  const TableChannel& channel(const std::string& name) const;      // throws InvalidInput
  const AttributeValue* attribute(const std::string& name) const;  // nullptr when absent
};

// {"format": "bssrdf-lut", "version": 1, "kind", "width", "height", "attributes": {...},
//  "axes": {"x": {"name", "values"}, "y": {...}} (2D tables with axes), "channels": [{"name",
//  "description", "values": [...]}]}; pretty-printed, trailing newline.
std::string to_json(const LookupTable& table);
// A leading "# model: NAME" comment (and "# model_choice: WHY" when the table records one), then
// one line per cell: "row,column," (2D tables only), the y and x axis values where the table has
// them, then one column per channel; a header line.
std::string to_csv(const LookupTable& table);

}  // namespace bssrdf
