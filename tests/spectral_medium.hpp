// Spectral media for the colour tests. skin_like_medium: skin-like, absorption falling with wavelength, scattering a
// power law, every `step` nm from 400 to 700.
#pragma once

#include <cmath>
#include <string>

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

// A small spectral medium (five wavelengths, absorption falling towards the red) and the same medium as
// command-line options, so a test can compare the CLI's output with the library's for one medium.
inline const std::string kTintOptions =
    "--wavelengths 450,500,550,600,650 --sigma-a 0.5,0.2,0.1,0.03,0.02 --sigma-s 10 --g 0.8 --eta 1.4";

inline Medium tint_medium() {
  Medium m;
  m.wavelength_nm = {450, 500, 550, 600, 650};
  m.sigma_a = {0.5, 0.2, 0.1, 0.03, 0.02};
  m.sigma_s.assign(5, 10.0);
  m.g.assign(5, 0.8);
  m.eta = 1.4;
  m.channel_names = wavelength_channel_names(m.wavelength_nm);
  m.validate();
  return m;
}

}  // namespace bssrdf::test_spectral
