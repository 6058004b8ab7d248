#include "bssrdf/models/diffusion_validity.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "bssrdf/error.hpp"

namespace bssrdf {

// Worst |error| of the closed-form total against adding-doubling over eta in {1, 1.4}, for
// alpha' at or above each bound (alpha' from the similarity relation), rounded up to 0.1 %.
// Measured by tests/test_adding_doubling.cpp, which fails if a band stops holding or is padded.
DiffusionLimits dipole_limits() {
  DiffusionLimits limits;
  limits.isotropic_bands = {{0.99, 0.014}, {0.95, 0.040}, {0.9, 0.104}, {0.8, 0.212}, {0.7, 0.288},
                            {0.5, 0.372},  {0.3, 0.404},  {0.1, 0.407}, {0.01, 0.407}};
  limits.forward_bands = {{0.99, 0.012}, {0.95, 0.059}, {0.9, 0.167}, {0.8, 0.387}, {0.7, 0.616},
                          {0.5, 1.147},  {0.3, 1.874},  {0.1, 2.902}, {0.01, 3.465}};
  return limits;
}

// The better dipole omits single scattering; these errors compare it with totals that include it,
// which is how wrong a renderer using it alone would be.
DiffusionLimits better_dipole_limits() {
  DiffusionLimits limits;
  limits.isotropic_bands = {{0.99, 0.027}, {0.95, 0.102}, {0.9, 0.173}, {0.8, 0.304}, {0.7, 0.414},
                            {0.5, 0.601},  {0.3, 0.766},  {0.1, 0.923}, {0.01, 0.993}};
  limits.forward_bands = {{0.99, 0.025}, {0.95, 0.082}, {0.9, 0.125}, {0.8, 0.184}, {0.7, 0.256},
                          {0.5, 0.397},  {0.3, 0.570},  {0.1, 0.824}, {0.01, 0.981}};
  limits.context = "; the model omits single scattering, much of this error at g near 0";
  return limits;
}

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
                      "eta = " + format_number(m.eta) + " is outside the range [" +
                          format_number(limits.eta_min) + ", " + format_number(limits.eta_max) +
                          "] over which the accuracy was measured"});
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
