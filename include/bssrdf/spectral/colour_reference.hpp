// The Monte Carlo reference of a spectral medium or layer stack in colour: per radial bin (and for every total), a
// colour channel's estimate is sum_i w_ci X_i with the ColourIntegrator weights w (spectral/colour.hpp), the same
// integration as colour_profile, and its standard error sqrt(sum_i w_ci^2 se_i^2): each wavelength is traced with its
// own random stream (Rng(seed, channel, batch)), so the wavelengths' errors are independent.
#pragma once

#include <string>
#include <vector>

#include "bssrdf/montecarlo.hpp"
#include "bssrdf/profile_report.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf::spectral {

// One colour channel of per-wavelength rows v_i (w: that channel's weight of each wavelength): per entry k,
// sum_i w_i v_i[k], or with `errors` (v_i standard errors of independent estimates) sqrt(sum_i w_i^2 v_i[k]^2).
std::vector<double> combine_bins(const std::vector<const std::vector<double>*>& v, const std::vector<double>& w,
                                 bool errors);

// `result`'s channels are the wavelengths `wavelength_nm` (InvalidInput naming "wavelengths" otherwise); returns R, G,
// B channels in settings.space. The stack and run options stay the spectral ones (the report lists the coefficients
// per wavelength).
MonteCarloResult colour_reference(const MonteCarloResult& result, const std::vector<double>& wavelength_nm,
                                  const ColourSettings& settings);

// A colour result's JSON (with "colour": {observer, illuminant, space, wavelength_nm}), CSV (a leading "# colour:"
// line) and report (a "Colour:" line first).
std::string colour_reference_json(const MonteCarloResult& result, LengthUnit unit, const ColourNote& note);
std::string colour_reference_csv(const MonteCarloResult& result, LengthUnit unit, const ColourNote& note);
std::string colour_reference_report(const MonteCarloResult& result, LengthUnit unit, const ColourNote& note);

}  // namespace bssrdf::spectral
