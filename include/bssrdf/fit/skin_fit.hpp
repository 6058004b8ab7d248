// Fitting the two-layer skin model (skin/skin_model.hpp) to a measured total diffuse reflectance spectrum, or to a
// target colour, with Ceres (Levenberg-Marquardt within each parameter's range, forward-difference Jacobian).
//
// Both start Levenberg-Marquardt from the best point of a coarse grid of starts (the problems have several minima).
// Spectrum: least squares of R_model(lambda) - R_measured(lambda) over the measured wavelengths within
// [min_nm, max_nm] (and the chromophores' 250-1000 nm), solved on every k-th of them so that the solved ones are at
// least `solve_step_nm` apart (the fitted spectrum, RMS and colour difference are then reported at all of them).
// Fitted: melanin, eumelanin share, blood, oxygenation, epidermal thickness, scattering a and power b; water, g and
// eta held at their given values. Each parameter's 1-sigma error is from the covariance of the solved residuals,
// scaled by their variance. The colour difference is CIEDE2000 between the measured and fitted spectra under D65
// (the measured spectrum held at its end values beyond its range).
//
// Colour: the melanin, eumelanin share and blood whose total reflectance under D65 has the target's L*a*b*; the
// remaining CIEDE2000 is reported (nonzero where the target is outside the skin's gamut).
#pragma once

#include <string>
#include <vector>

#include "bssrdf/io/spectrum_file.hpp"
#include "bssrdf/skin/skin_model.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf {

struct SkinFitOptions {
  skin::SkinParameters start;     // start values, and the values of the parameters not fitted
  bool specular_included = true;  // the measurement includes the surface's specular reflection
  double min_nm = 400, max_nm = 1000;
  double solve_step_nm = 20;  // spacing of the wavelengths the solver uses (31 over 400-1000 nm)
  int points = 8;             // adding-doubling angles per hemisphere (error below 1e-3 in R, docs/skin.md)
};

struct SkinFitParameter {
  std::string name, unit;
  double value = 0, stderr_ = 0;  // stderr_: 1 sigma, NaN when the covariance is rank-deficient
  bool at_bound = false;          // at an end of its range: the sigma means nothing there
};

struct SkinFitResult {
  std::string source;  // "FILE (column)" or "srgb R,G,B"
  std::vector<double> wavelength_nm, measured, fitted;
  skin::SkinParameters parameters;
  std::vector<SkinFitParameter> reported;  // the fitted parameters
  double rms = 0;                          // reflectance units, over every reported wavelength
  double delta_e2000 = 0;
  std::string status;  // "converged", "no_convergence", "failed"
  int iterations = 0, residual_evaluations = 0;
  double cpu_seconds = 0, wall_seconds = 0;
  bool specular_included = true;

  std::string to_json() const;  // keys: wavelength_nm, measured, fitted, rms, delta_e2000, parameters, status, ...
  std::string to_table() const;
};

// InvalidInput when fewer wavelengths than fitted parameters lie within the range.
SkinFitResult fit_skin_spectrum(const ReflectanceSpectrum& spectrum, const SkinFitOptions& options = {});
// `linear_srgb`: the target's linear sRGB (D65) total reflectance colour, each within (0, 1).
SkinFitResult fit_skin_colour(const spectral::Vec3& linear_srgb, const SkinFitOptions& options = {});

}  // namespace bssrdf
