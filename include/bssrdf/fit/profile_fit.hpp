// Fit sigma_a and sigma_s' per channel (optionally a shared eta and an unknown overall scale) to a
// measured radial profile, with any model of the family as the forward model.
//
//   auto data = read_profile_csv("spot.csv");
//   ProfileFitOptions options;  options.model = "pbd";  options.fit_scale = true;
//   FitReport report = fit_profile(data, options);
//   std::cout << report.full_report();
//
// Parameters are fitted as logarithms (positivity without bounds); eta within [eta_min, eta_max].
// Residuals are (scale R_model(r_i) - R_i) / sigma_i with sigma_i the file's standard errors, or,
// without them, relative residuals (sigma_i = R_i): profiles span decades and every radius counts.
// Without standard errors the covariance is scaled by the reduced chi-square. The forward model is
// the registry's fit form (model_registry.hpp): the dipoles, photon beam diffusion and quantized
// diffusion (and their +ss forms) are differentiated automatically (ceres::Jet through the same
// templated code), a model with a numeric form (the burley models) numerically.
#pragma once

#include <string>
#include <vector>

#include "bssrdf/fit/fit_report.hpp"
#include "bssrdf/io/profile_csv.hpp"

namespace bssrdf {

struct ProfileFitOptions {
  std::string
      model;  // empty: the registry's default for these g and eta (default_model_over_albedos: exact in its domain)
  double eta = 1.3;  // fixed, or the starting value when fit_eta
  bool fit_eta = false;
  double eta_min = 1.0, eta_max = 2.0;
  bool fit_scale = false;     // an unknown overall scale (uncalibrated camera)
  std::vector<double> g;      // per channel (fixed; the profile cannot separate g from sigma_s); empty: 0
  std::string loss = "none";  // "none", "huber" or "cauchy" (robust to outliers)
  double loss_scale = 1.0;    // in units of the weighted residual
  int max_iterations = 200;

  void validate(std::size_t channels) const;  // throws InvalidInput
};

FitReport fit_profile(const MeasuredProfile& data, const ProfileFitOptions& options);

}  // namespace bssrdf
