#include "bssrdf/spectral/colour_transmission.hpp"

#include <cmath>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "bssrdf/spectral/colour_reference.hpp"

namespace bssrdf::spectral {

TransmissionTable colour_transmission(const TransmissionTable& table, const ColourIntegrator& colour) {
  const auto& w = colour.rgb_weights();
  BSSRDF_CHECK(table.channel_names.size() == w.size() && table.transmittance.size() == w.size());
  TransmissionTable out = table;
  out.channel_names = {"R", "G", "B"};
  out.transmittance.clear();
  out.standard_error.clear();
  std::vector<const std::vector<double>*> values, errors;
  for (std::size_t i = 0; i < w.size(); ++i) {
    values.push_back(&table.transmittance[i]);
    errors.push_back(&table.standard_error[i]);
  }
  for (std::size_t c = 0; c < 3; ++c) {
    std::vector<double> weight;
    for (const auto& wi : w) weight.push_back(wi[c]);
    out.transmittance.push_back(combine_bins(values, weight, false));
    out.standard_error.push_back(combine_bins(errors, weight, true));
  }
  // Validity: every wavelength's notes once, the first wavelength that has each named.
  std::string notes;
  for (std::size_t i = 0; i < table.validity.size(); ++i) {
    if (table.validity[i].rfind("no warnings", 0) == 0 || notes.find(table.validity[i]) != std::string::npos) continue;
    notes += (notes.empty() ? "" : "; ") + table.channel_names[i] + ": " + table.validity[i];
  }
  const std::string quiet = table.validity.empty() ? std::string() : table.validity.front();
  out.validity.assign(table.validity.empty() ? 0 : 3, notes.empty() ? quiet : notes);
  return out;
}

std::string colour_transmission_line(const TransmissionTable& table, const ColourIntegrator& colour) {
  const auto& options = table.options;
  const bool exact = options.model == "adding-doubling" && !options.reference_everywhere;
  std::string line = describe(colour_note(colour.wavelengths(), colour.settings())) +
                     "; T_c(d) = sum over 1 nm of T(d, lambda) S(lambda) cbar(lambda) / sum of S(lambda) "
                     "ybar(lambda), per thickness, each wavelength's own slab (" +
                     (exact ? std::string("adding-doubling") : std::string("multipole, Monte Carlo where asked")) + ")";
  for (std::size_t c = 0; c < table.channel_names.size(); ++c)
    for (std::size_t j = 0; j < table.size(); ++j)
      if (table.transmittance[c][j] < 0) {
        line += "; " + table.channel_names[c] + " < 0 from " + format_number(table.thickness[j]) +
                " mm (the light passing there has a colour outside " + std::string(to_string(colour.settings().space)) +
                "; not clipped)";
        break;
      }
  return line;
}

}  // namespace bssrdf::spectral
