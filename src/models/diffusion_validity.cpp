#include "bssrdf/models/diffusion_validity.hpp"

#include <cmath>

#include "bssrdf/error.hpp"

namespace bssrdf {

DiffusionLimits dipole_limits() { return {0.1, "40 %", 0.8, "5 %", 1.0, 1.5}; }
DiffusionLimits better_dipole_limits() { return {0.1, "40 %", 0.8, "5 %", 1.0, 1.5}; }

ValidityReport diffusion_validity(const Reduced<double>& m, const DiffusionLimits& limits) {
  ValidityReport report;
  const double a = m.albedo_prime;
  const std::string a_text = "alpha' = " + format_number(std::round(a * 1e4) / 1e4);
  if (a < limits.invalid_below_albedo_prime) {
    report.push_back({Severity::invalid, "low_albedo",
                      a_text + " < " + format_number(limits.invalid_below_albedo_prime) +
                          ": diffusion not valid (total reflectance off by more than " +
                          limits.invalid_error + " against adding-doubling)"});
  } else if (a < limits.warn_below_albedo_prime) {
    report.push_back({Severity::warning, "low_albedo",
                      a_text + " < " + format_number(limits.warn_below_albedo_prime) +
                          ": total reflectance may be off by more than " + limits.warn_error +
                          " against adding-doubling"});
  }
  if (m.eta < limits.eta_min || m.eta > limits.eta_max)
    report.push_back({Severity::warning, "eta_unvalidated",
                      "eta = " + format_number(m.eta) + " is outside the range [" +
                          format_number(limits.eta_min) + ", " + format_number(limits.eta_max) +
                          "] this model was checked over"});
  if (std::abs(m.g) >= 0.5)
    report.push_back({Severity::note, "similarity",
                      "g = " + format_number(m.g) +
                          ": reduced by similarity; totals hold to a few %, but R(r) within one "
                          "transport mean free path can be off by 2-3x"});
  report.push_back({Severity::note, "near_field",
                    "R(r) for r below one transport mean free path (ell = 1/sigma_t') is outside "
                    "the diffusion regime"});
  return report;
}

}  // namespace bssrdf
