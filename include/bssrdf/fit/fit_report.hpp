// What every fit returns, in the spirit of Ceres' Solver::Summary::FullReport: the parameters with
// 1-sigma uncertainties, how well the model explains the data, how the solver ended, warnings about
// what the data cannot determine, and the residual of every data point.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "bssrdf/units.hpp"

namespace bssrdf {

struct FitParameter {
  std::string name;     // e.g. "sigma_a", "sigma_s_prime", "eta", "scale", "burley_d"
  std::string channel;  // empty for shared parameters
  double value = 0;
  double standard_error = 0;  // 1 sigma; NaN when it could not be computed
  std::string unit;           // e.g. "1/mm", "mm", "" (dimensionless)
};

struct FitResidual {
  std::string channel;
  double x = 0;  // radius, or the index of the quantity fitted
  double measured = 0;
  double model = 0;
  double weighted = 0;  // (model - measured) / sigma
};

struct FitReport {
  std::string kind;          // "profile", "albedo", "slab", "gaussians", "burley"
  std::string model;         // forward model
  std::string model_choice;  // why this model when it is the default and not `exact` (default_model); else empty
  std::string data_source;   // the data file, or a description of the inputs
  std::vector<FitParameter> parameters;
  std::vector<FitResidual> residuals;
  double residual_rms = 0;  // of the weighted residuals
  double relative_rms = 0;  // RMS of (model - measured)/measured over the points
  int iterations = 0;
  std::string termination;  // "CONVERGENCE", "exact", ...
  bool converged = false;
  double seconds = 0;
  std::vector<std::string> warnings;
  std::string solver_report;  // Ceres' FullReport, when Ceres was used
  // A fit of sigma_a and sigma_s' (profile, albedo, slab) describes a complete medium: what it held
  // fixed beside the fitted parameters, so that its JSON can become a material without retyping.
  // NaN eta: not a medium fit (gaussians, burley).
  double eta = NAN;         // the fitted (a parameter "eta") or the assumed relative index
  std::vector<double> g;    // per channel in parameter order, where no parameter "g" was fitted
  std::string length_unit;  // of the coefficients, e.g. "mm"

  const FitParameter* find(const std::string& name, const std::string& channel = "") const;

  std::string full_report() const;  // for people
  // {"kind", "model", ..., "channels": [{"name", "sigma_a": {"value","stderr"}, ...}]}; a medium fit also
  // gives "unit", "eta" and per channel "g" and "sigma_s" (sigma_s' / (1 - g)).
  std::string to_json() const;
};

}  // namespace bssrdf
