// --colour and --illuminant: turn a spectral output into colour channels (spectral/colour.hpp).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "bssrdf/medium.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf::cli {

struct ColourOptions {
  std::string colour, illuminant;

  void add_to(CLI::App& app);
  // nullopt when neither is given; InvalidInput when given for a medium without wavelengths, or a bad name.
  std::optional<spectral::ColourSettings> resolve(const Medium& medium) const;
};

}  // namespace bssrdf::cli
