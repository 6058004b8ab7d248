// A homogeneous scattering medium, per colour channel: absorption sigma_a, scattering sigma_s and
// Henyey-Greenstein anisotropy g (all in 1/mm), with one relative index of refraction
// eta = n_medium / n_outside. Construct, then validate(): the rest of the library assumes a
// validated medium.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bssrdf/reduced.hpp"

namespace bssrdf {

// Refractive indices, absolute or relative, that a physicist would accept: real media lie between 1
// and about 4 (germanium), so any ratio of two lies within [1/5, 5]. Beyond, total internal
// reflection traps light for unbounded times.
inline constexpr double kMinRefractiveIndex = 0.2, kMaxRefractiveIndex = 5;
// Largest coefficient, in 1/unit of whichever unit it is given in: 1e6/mm is a mean free path of 1 nm.
inline constexpr double kMaxCoefficient = 1e6;

struct Medium {
  std::vector<std::string> channel_names;  // e.g. {"R", "G", "B"}
  std::vector<double> sigma_a;             // 1/mm
  std::vector<double> sigma_s;             // 1/mm
  std::vector<double> g;                   // mean cosine, in (-1, 1)
  double eta = 1.0;                        // n_medium / n_outside
  // A spectral medium: the wavelength of each channel in nm, strictly increasing (empty: RGB or unnamed channels).
  // Colour comes from integrating its outputs (spectral/colour.hpp), never from its coefficients.
  std::vector<double> wavelength_nm;

  std::size_t channels() const { return sigma_a.size(); }
  bool spectral() const { return !wavelength_nm.empty(); }

  // Throws InvalidInput naming the first offending field, e.g. "sigma_a[G] = -1: accepted range
  // is >= 0 and finite". Checks: equal channel counts (>= 1), 0 <= sigma_a, sigma_s <= kMaxCoefficient,
  // sigma_a + sigma_s > 0, -1 < g < 1, eta within [kMinRefractiveIndex, kMaxRefractiveIndex],
  // channel names unique and non-empty; wavelengths, when given, one per channel, within
  // [kMinWavelength, kMaxWavelength] nm and strictly increasing.
  void validate() const;

  // The similarity-reduced coefficients of one channel, used by every diffusion model.
  Reduced<double> reduced(std::size_t channel) const;

  // One channel named "x" (coefficients in 1/mm): what references, fits and validations of a single
  // set of coefficients use.
  static Medium single_channel(double sigma_a, double sigma_s, double g, double eta);
};

// The shortest and longest transport mean free path ell = 1 / sigma_t' over the channels, mm: the
// length every default range (radii, slab thicknesses) scales with.
struct TransportMfpRange {
  double min = 0, max = 0;
};
TransportMfpRange transport_mfp_range(const Medium& medium);

// The wavelengths a spectral medium may carry, nm: ultraviolet to mid-infrared.
inline constexpr double kMinWavelength = 200, kMaxWavelength = 20000;

// Channel names of a spectral medium: "400nm", "402.5nm", ...
std::vector<std::string> wavelength_channel_names(const std::vector<double>& wavelength_nm);

// Channel names for n channels: R, G, B for three, c0, c1, ... otherwise.
std::vector<std::string> default_channel_names(std::size_t count);

}  // namespace bssrdf
