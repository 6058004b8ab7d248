#include "colour_options.hpp"

#include "bssrdf/error.hpp"

namespace bssrdf::cli {

void ColourOptions::add_to(CLI::App& app) {
  app.add_option("--colour,--color", colour,
                 "A spectral medium's output as colour: srgb (linear), acescg or rec2020, integrated per radius "
                 "against the CIE 1931 2-degree observer [srgb when --illuminant is given]");
  app.add_option("--illuminant", illuminant, "Illuminant for --colour: d65, d50, a or e [d65]");
}

std::optional<spectral::ColourSettings> ColourOptions::resolve(const std::vector<double>& wavelength_nm) const {
  if (colour.empty() && illuminant.empty()) return std::nullopt;
  if (wavelength_nm.empty())
    throw InvalidInput(std::string(colour.empty() ? "--illuminant" : "--colour") +
                       ": needs a spectral medium (--wavelengths, a material with wavelengths, or layers whose "
                       "channels are named by wavelength, e.g. 550nm)");
  spectral::ColourSettings settings;
  if (!colour.empty()) settings.space = spectral::parse_colour_space(colour, "--colour");
  if (!illuminant.empty()) settings.illuminant = spectral::parse_illuminant(illuminant, "--illuminant");
  return settings;
}

}  // namespace bssrdf::cli
