// The colour of a spectral profile: per radius, R_c(r) = sum_i w_ci R(r, lambda_i) with the weights of
// ColourIntegrator (the illuminant-weighted colour matching functions, normalised by the illuminant's Y), so each
// radius carries the exact profile at every wavelength (not a profile of averaged coefficients), and the colour
// channels' totals are the colours of the spectral totals.
#pragma once

#include "bssrdf/profile_report.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf::spectral {

// `report`'s channels are the wavelengths `wavelength_nm` (one each, sharing one radius grid); returns R, G, B
// channels in settings.space with report.colour set. Coefficients of the colour channels are NaN (a colour has
// none); validity notes stay with the spectral channels. InvalidInput when the counts differ.
ProfileReport colour_profile(const ProfileReport& report, const std::vector<double>& wavelength_nm,
                             const ColourSettings& settings);

}  // namespace bssrdf::spectral
