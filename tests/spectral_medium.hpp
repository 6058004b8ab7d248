// A spectral medium for the colour tests: skin-like, absorption falling with wavelength, scattering a power law,
// every `step` nm from 400 to 700.
#pragma once

#include <cmath>

#include "bssrdf/medium.hpp"

namespace bssrdf::test_spectral {

inline Medium skin_like_medium(double step = 20) {
  Medium m;
  for (double nm = 400; nm <= 700; nm += step) {
    m.wavelength_nm.push_back(nm);
    m.sigma_a.push_back(0.02 + 2.0 * std::exp(-(nm - 400) / 40));
    m.sigma_s.push_back(10 * std::pow(nm / 500, -1.2));
    m.g.push_back(0.8);
  }
  m.channel_names = wavelength_channel_names(m.wavelength_nm);
  m.eta = 1.4;
  m.validate();
  return m;
}

}  // namespace bssrdf::test_spectral
