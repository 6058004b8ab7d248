// --colour and --illuminant: turn a spectral output into colour channels (spectral/colour.hpp).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bssrdf/medium.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf::cli {

struct ColourOptions {
  std::string colour, illuminant;

  void add_to(CLI::App& app);
  // nullopt when neither is given; InvalidInput when given for a medium without wavelengths, or a bad name.
  std::optional<spectral::ColourSettings> resolve(const Medium& medium) const { return resolve(medium.wavelength_nm); }
  // The same for outputs whose channels are at these wavelengths (empty: not spectral).
  std::optional<spectral::ColourSettings> resolve(const std::vector<double>& wavelength_nm) const;
};

}  // namespace bssrdf::cli
