#include "bssrdf/spectral/colour_profile.hpp"

#include <cmath>
#include <limits>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/spectral/colour_medium.hpp"

namespace bssrdf::spectral {

ProfileReport colour_profile(const ProfileReport& report, const std::vector<double>& wavelength_nm,
                             const ColourSettings& settings) {
  if (report.channels.size() != wavelength_nm.size())
    throw InvalidInput("wavelengths: " + std::to_string(wavelength_nm.size()) + " given for " +
                       std::to_string(report.channels.size()) + " channels");
  const ColourIntegrator colour(wavelength_nm, settings);
  const auto& w = colour.rgb_weights();
  ProfileReport out = report;
  out.channels.clear();
  out.colour = colour_note(wavelength_nm, settings);
  const auto& first = report.channels.front();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int c = 0; c < 3; ++c) {
    ChannelProfile ch;
    ch.name = std::string(1, "RGB"[c]);
    ch.sigma_a = ch.sigma_s = ch.g = ch.sigma_s_prime = ch.albedo_prime = ch.transport_mfp = ch.diffuse_mfp = nan;
    ch.radius_99 = nan;
    ch.profile.radius = first.profile.radius;
    ch.profile.value.assign(first.profile.radius.size(), 0.0);
    if (first.total_transmittance) {
      ch.total_transmittance = 0.0;
      ch.transmittance.assign(first.transmittance.size(), 0.0);
    }
    for (std::size_t i = 0; i < report.channels.size(); ++i) {
      const auto& s = report.channels[i];
      BSSRDF_CHECK(s.profile.radius == first.profile.radius);
      for (std::size_t k = 0; k < s.profile.value.size(); ++k) ch.profile.value[k] += w[i][c] * s.profile.value[k];
      ch.total_reflectance += w[i][c] * s.total_reflectance;
      if (ch.total_transmittance) {
        *ch.total_transmittance += w[i][c] * s.total_transmittance.value_or(0.0);
        for (std::size_t k = 0; k < s.transmittance.size(); ++k) ch.transmittance[k] += w[i][c] * s.transmittance[k];
      }
    }
    out.channels.push_back(std::move(ch));
  }
  return out;
}

}  // namespace bssrdf::spectral
