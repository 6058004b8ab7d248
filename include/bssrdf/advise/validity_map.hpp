// Where each model holds: heatmaps of every profile model's measured error against the Monte Carlo
// reference over a parameter plane, and a map of the cheapest model within a tolerance at each
// point, with the database's material channels marked. SVG, no plotting library.
//
// The errors are the measured validation cases behind model_choice.hpp (alpha' 0.5-0.999 x eta 1,
// 1.3, 1.4, 1.5 x g 0, 0.9, 0.95; Monte Carlo noise about 1.5 % in L2): one cell per measured case,
// never interpolated. Planes: albedo,eta (g = 0) and albedo,g (eta = 1.3). Metrics: "total"
// (|relative error of the total reflectance|) or "profile" (area-weighted relative L2 error of R(r)).
//
//   ValidityMapOptions o{.over = "albedo,eta", .metric = "profile", .tolerance = 0.05};
//   write_file_atomically("map.svg", render_validity_map(o, database.all()));
#pragma once

#include <string>
#include <vector>

#include "bssrdf/materials.hpp"

namespace bssrdf {

struct ValidityMapOptions {
  std::string over = "albedo,eta";  // or "albedo,g"
  std::string metric = "profile";   // or "total"
  double tolerance = 0.05;          // relative error, for the cheapest-model map
};

// Throws InvalidInput naming "--over", "--metric" or "--tolerance" for values outside those listed.
std::string render_validity_map(const ValidityMapOptions& options, const std::vector<Material>& materials);

}  // namespace bssrdf
