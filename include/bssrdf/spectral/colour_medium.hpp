// A spectral medium in colour, for everything that takes three channels (every table kind, every RGB renderer
// export): R, G, B channels whose profile is the colour integration of the exact per-wavelength profiles,
//   R_c(r) = sum_i w_ci R(r, lambda_i)          (w: ColourIntegrator's weights, spectral/colour.hpp)
// per radius (never a profile of averaged coefficients), and, for consumers that need coefficients, per channel the
// coefficients whose own profile under the same model has the colour channel's total reflectance (exactly) and
// median radius r_50 (exactly); what is left is a shape error, measured and recorded.
//
//   ColourMedium skin = colour_medium(spectral_medium, make_model("exact"), {Illuminant::d65, ColourSpace::srgb});
//   tabulate_radial({material, &skin.rgb, skin.model.get(), unit, "", &skin}, {});   // R, G, B integrated
//
// skin.model evaluates R_c(r), its totals and cumulatives (sums of the per-wavelength ones) for the channels of
// skin.rgb, identified by their coefficients; it refuses others (InternalError).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/profile_report.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf::spectral {

struct ColourMedium {
  Medium rgb;                          // channels R, G, B: the equivalent coefficients (1/mm), g and eta below
  std::shared_ptr<const Model> model;  // R_c(r) integrated per radius, for rgb's channels
  std::string spectral_model;          // the model each wavelength's profile comes from
  ColourNote note;                     // observer, illuminant, space, wavelengths
  // Per channel: the total reflectance (the colour of the spectral totals) and the relative L2 difference
  // sqrt(int r (R_eq - R_c)^2 dr / int r R_c^2 dr) between the equivalent coefficients' profile and R_c.
  std::vector<double> total, shape_error;
  // Per channel: where R_c(r) first turns negative (mm; 0: never) and its negative part int 2 pi r min(R_c, 0) dr as a
  // fraction of the total (>= 0). The light that travels furthest is the least absorbed, often deep red, a colour
  // outside linear sRGB: its blue and green are negative. Never clipped: the totals stay the colour of the totals.
  std::vector<double> negative_from, negative;
  // "; B < 0 from 3.2 mm (...), its negative part 3.7 % of its total" for each such channel; empty if none.
  std::string negative_note() const;

  // One line for metadata and export comments: the colour, the integration, the coefficients' fit and its error
  // ("linear sRGB under D65, ...; R_c(r) = ...; R, G, B coefficients: ...").
  std::string summary() const;
};

// `medium` spectral (InvalidInput naming "colour" otherwise, or when a colour channel's total is not positive or
// beyond what the model can produce: a colour outside the space's gamut). g of the equivalents: the luminance-
// weighted mean of the medium's g; eta: the medium's.
ColourMedium colour_medium(const Medium& medium, std::shared_ptr<const Model> model, const ColourSettings& settings);

// A spectral material for what takes R, G, B (the renderer exports): colour_medium under the registry's default model
// for its medium (default_model); the material keeps its name, source and citation, with the equivalent R, G, B
// coefficients, and the colour summary as its first note.
struct ColourMaterial {
  Material material;
  ColourMedium colour;
};
ColourMaterial colour_material(const Material& material, const ColourSettings& settings);

// The observer, illuminant, space and wavelengths of a colour integration.
ColourNote colour_note(const std::vector<double>& wavelength_nm, const ColourSettings& settings);
// "linear sRGB under D65, CIE 1931 2-degree observer, from 31 wavelengths (400-700 nm)"
std::string describe(const ColourNote& note);

// The wavelengths of channels named as a spectral medium's ("400nm", "402.5nm": wavelength_channel_names);
// empty when any name is not one.
std::vector<double> wavelengths_from_channel_names(const std::vector<std::string>& names);

}  // namespace bssrdf::spectral
