// What every exported table records about where it came from: tool version, material, model and
// the conventions its numbers follow. Written as "bssrdf:*" attributes by describe().
#pragma once

#include <optional>
#include <string>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/profile_report.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

// The colour integration a table's R, G, B channels come from (a spectral medium's wavelengths summed with the colour
// weights: spectral/colour_medium.hpp for profiles, spectral/colour_transmission.hpp for slab totals).
struct TableColour {
  ColourNote note;   // observer, illuminant, space, wavelengths
  std::string line;  // one line: the colour, what was integrated and how
};

struct TableContext {
  std::optional<Material> material;  // when the medium came from the database
  const Medium* medium = nullptr;    // the coefficients tabulated (1/mm); optional
  const Model* model = nullptr;      // optional (transmission tables come from Monte Carlo)
  LengthUnit unit = LengthUnit::millimetre;
  std::string model_choice{};  // why this model when it is not `exact` by default or was chosen by auto; else empty
  // A colour table of a spectral medium. Profile kinds: `medium` is the colour stand-in and `model` the integrated
  // colour model (spectral/colour_medium.hpp); transmission: `medium` is the spectral medium itself (its coefficients
  // are then per wavelength of colour->note).
  std::optional<TableColour> colour{};
};

// Adds bssrdf:tool, bssrdf:kind, bssrdf:material (+ source, citation), bssrdf:model (+ description,
// single scattering, and bssrdf:model_choice when the context gives one), bssrdf:eta, bssrdf:channels and
// bssrdf:coefficients (sigma_a, sigma_s, g in 1/unit), and bssrdf:normalization; for a colour table,
// bssrdf:colour (one line) and bssrdf:colour_observer, _illuminant, _space, _wavelength_nm.
void describe(LookupTable& table, const TableContext& context);

// A width x height table of `kind`, described, with bssrdf:unit naming the context's length unit.
LookupTable described_table(std::string kind, std::size_t width, std::size_t height, const TableContext& context);

}  // namespace bssrdf
