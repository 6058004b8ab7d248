// A spectral medium at other wavelengths: sigma_a, sigma_s and g interpolated linearly in wavelength between the
// medium's own (no extrapolation: each wavelength must lie within the medium's range).
#pragma once

#include <vector>

#include "bssrdf/medium.hpp"

namespace bssrdf::spectral {

// InvalidInput naming "wavelengths" when `medium` has none, or a wavelength lies outside its range.
Medium resample(const Medium& medium, const std::vector<double>& wavelength_nm);

// Linear interpolation of samples y(x) at `at` (x strictly increasing, at within [x.front(), x.back()]).
double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double at);

}  // namespace bssrdf::spectral
