#include "bssrdf/models/diffusion_validity.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "bssrdf/error.hpp"

namespace bssrdf {

double documented_total_error(const DiffusionLimits& limits, double albedo_prime, double g) {
  for (const auto& band : g >= 0.5 ? limits.forward_bands : limits.isotropic_bands)
    if (albedo_prime >= band.min_albedo_prime) return band.worst_error;
  return std::numeric_limits<double>::infinity();
}

namespace {
std::string percent(double fraction) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.0f %%", fraction * 100);
  return buffer;
}
}  // namespace

ValidityReport diffusion_validity(const Reduced<double>& m, const DiffusionLimits& limits) {
  ValidityReport report;
  const double a = m.albedo_prime;
  const std::string a_text = "alpha' = " + format_number(std::round(a * 1e4) / 1e4);
  const double error = documented_total_error(limits, a, m.g);
  const std::string measured = std::isfinite(error) ? "total reflectance error up to " + percent(error) +
                                                          " against adding-doubling at this albedo" + limits.context
                                                    : "total reflectance error not bounded by any measurement";
  if (a < limits.invalid_below_albedo_prime) {
    report.push_back({Severity::invalid, "low_albedo",
                      a_text + " < " + format_number(limits.invalid_below_albedo_prime) +
                          ": diffusion not valid, absorption dominates scattering (" + measured + ")"});
  } else if (!(error <= limits.invalid_above_error)) {
    report.push_back({Severity::invalid, "low_albedo", a_text + ": model not reliable here (" + measured + ")"});
  } else if (error > limits.warn_above_error) {
    report.push_back({Severity::warning, "low_albedo", a_text + ": " + measured});
  }
  if (m.eta < limits.eta_min || m.eta > limits.eta_max)
    report.push_back({Severity::warning, "eta_unvalidated",
                      "eta = " + format_number(m.eta) + " is outside the range [" + format_number(limits.eta_min) +
                          ", " + format_number(limits.eta_max) + "] over which the accuracy was measured"});
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

namespace bssrdf {

namespace {
// T_total error of a d = 2 ell slab (alpha' 0.99, eta 1.3) against Monte Carlo: +30.9 %
// (tests/test_multipole_montecarlo.cpp).
constexpr const char* kThinSlabTError = "31 %";
}  // namespace

ValidityReport slab_validity(const Reduced<double>& m, const SlabState& state) {
  ValidityReport report;
  const double t = state.thickness_over_ell;
  const std::string d_text = "d = " + format_number(std::round(t * 1000) / 1000) + " ell";
  if (t < 1)
    report.push_back({Severity::invalid, "source_outside_slab",
                      d_text + " < 1 ell: the real source (depth ell) lies outside the slab"});
  // Worst |error| of the totals against adding-doubling slabs (alpha' 0.9 and 0.99, eta 1 and 1.4,
  // g = 0; classical A), measured and asserted by tests/test_multipole.cpp.
  if (t < 2) {
    report.push_back({Severity::invalid, "thin_slab",
                      d_text + " < 2 ell: the multipole is not valid in thin slabs (at d = 1 ell its totals are off "
                               "by up to 31 % (R) and 171 % (T) against adding-doubling)"});
  } else if (t < 4) {
    report.push_back({Severity::warning, "thin_slab",
                      d_text + " < 4 ell: near the multipole's thin-slab limit (T_total off by up to " +
                          std::string(kThinSlabTError) +
                          " at d = 2 ell against Monte Carlo; at 4 ell R_total within "
                          "10.6 % and T_total within 7.0 % against adding-doubling)"});
  } else {
    report.push_back({Severity::note, "slab_accuracy",
                      "against adding-doubling slabs at d = 4 and 16 ell (alpha' 0.9-0.99, eta 1-1.4): R_total within "
                      "10.6 %, T_total within 7.0 % (at 16 ell, 37 % of a T_total below 3e-4)"});
  }
  if (state.total_transmittance < 0 || state.min_transmittance < 0)
    report.push_back({Severity::invalid, "negative_transmittance",
                      "the multipole's transmittance is negative here (T_total = " +
                          format_number(std::round(state.total_transmittance * 1e5) / 1e5) + ")"});
  if (state.min_reflectance < 0)
    report.push_back({Severity::invalid, "negative_reflectance", "the multipole's R(r) is negative at some radius"});
  if (!state.converged)
    report.push_back({Severity::warning, "pairs_not_converged",
                      "the dipole-pair sum did not reach the tolerance " + format_number(state.tolerance) +
                          " (remaining " + format_number(state.truncation_error) +
                          "): without absorption it converges only in the limit"});
  auto rest = diffusion_validity(m, measured_limits("dipole"));
  report.insert(report.end(), rest.begin(), rest.end());
  return report;
}

}  // namespace bssrdf
