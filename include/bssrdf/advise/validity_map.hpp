// Where each model holds: heatmaps of every profile model's error over a parameter plane, and a
// map of the cheapest model within a tolerance at each point, with the database's material
// channels marked. SVG or PNG (io canvas, no plotting library).
//
// Planes: albedo,eta (g = 0) and albedo,g (eta = 1.3). Models: every `--model auto` candidate but
// the exact model itself. Metrics:
//  - "total" (|relative error of the total reflectance|) and "profile" (relative L2 of r R(r), the
//    worse of inside and beyond one transport mfp): measured live against the exact model
//    (model_choice.hpp's model_errors_vs_exact) on a dense grid, alpha' 0.3-0.999 x eta 1-1.6 or x
//    g 0-0.99; tolerance relative.
//  - "image": the image-space error (image_error.hpp, 8-bit sRGB code values at a shadow edge and a
//    one-pixel line) against `reference` at each cell of a coarse grid (alpha' 0.5-0.999 x eta 1,
//    1.3, 1.4, 1.5 or x g 0, 0.9, 0.95; a medium with sigma_t' = 1/mm, so `pixel` is in transport
//    mean free paths); tolerance in code values.
//
//   ValidityMapOptions o{.over = "albedo,eta", .metric = "profile", .tolerance = 0.05};
//   write_file_atomically("map.png", render_validity_map(o, database.all(), nullptr));
#pragma once

#include <string>
#include <vector>

#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/materials.hpp"

namespace bssrdf {

struct ValidityMapOptions {
  std::string over = "albedo,eta";  // or "albedo,g"
  std::string metric = "profile";   // "total", "profile" or "image"
  double tolerance = 0.05;         // relative error (total, profile) or code values (image), for the cheapest-model map
  double pixel = 1;                // image: pixel size in transport mean free paths
  std::string extension = ".svg";  // ".svg" or ".png"
};

// Throws InvalidInput naming "--over", "--metric", "--tolerance", "--pixel" or "--map" for values
// outside those listed. `reference` is needed for the image metric (else unused; may be null).
std::string render_validity_map(const ValidityMapOptions& options, const std::vector<Material>& materials,
                                const ReferenceProfile* reference = nullptr);

}  // namespace bssrdf
