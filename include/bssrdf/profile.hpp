// A radial profile sampled at increasing radii, with optional per-sample standard errors (Monte
// Carlo profiles carry them). Integrates 2 pi r R(r) with a cubic Hermite rule that is fourth-order
// accurate on log-spaced radii, finds energy radii, and interpolates.
//
//   auto p = model.sample(m, log_spaced(1e-3, 50.0, 128));
//   double total = p.integrate();                 // int_0^{r_max} 2 pi r R dr
//   double r99 = p.radius_for_fraction(0.99);     // of that total
#pragma once

#include <cstddef>
#include <vector>

namespace bssrdf {

struct SampledProfile {
  std::vector<double> radius;          // strictly increasing, >= 0
  std::vector<double> value;           // R(r) at each radius
  std::vector<double> standard_error;  // empty, or one per radius

  std::size_t size() const { return radius.size(); }

  // Throws InvalidInput for mismatched sizes, fewer than 2 samples, negative, non-finite or
  // non-increasing radii.
  void validate() const;

  // int_0^{r_back} 2 pi r R(r) dr. Between samples the integrand 2 pi r R is a cubic Hermite
  // spline; inside the first radius R is taken as constant (the disc pi r0^2 R(r0)). The tail
  // beyond the last radius is not included: sample far enough out.
  double integrate() const;
  // The same integral from 0 to r (clamped to the sampled range).
  double cumulative(double r) const;
  // Standard error of integrate() from the per-sample errors (independent samples, trapezoid
  // weights); 0 when no errors are stored.
  double integral_standard_error() const;
  // The radius at which cumulative() reaches `fraction` of integrate(); 0 < fraction <= 1.
  double radius_for_fraction(double fraction) const;
  // R(r): monotone-safe cubic Hermite in (ln r, ln R) where all values are positive, in (r, R)
  // otherwise; third order: ~20 samples per decade of radius give relative errors below 1e-3 on
  // a dipole profile. Below the first radius: value[0]; beyond the last: 0.
  double interpolate(double r) const;
};

// n radii from r_min to r_max inclusive, geometric (r_min > 0) or uniform.
std::vector<double> log_spaced(double r_min, double r_max, std::size_t n);
std::vector<double> linear_spaced(double r_min, double r_max, std::size_t n);

}  // namespace bssrdf
