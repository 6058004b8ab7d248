#include "bssrdf/model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/quadrature.hpp"
#include "bssrdf/root_finding.hpp"

namespace bssrdf {

double Model::cumulative_reflectance(const Reduced<double>& m, double r) const {
  if (!(r > 0)) return 0;
  return integrate_radial([&](double x) { return reflectance(m, x); }, 0.0, r, m.ell, 1e-9).value;
}

double Model::albedo_prime_from_total(double total, double eta, double g) const {
  const auto total_at = [&](double a) { return total_reflectance(reduced_optical(a, g, eta)); };
  const double lowest = total_at(0.0), highest = total_at(1.0);
  if (!(total >= lowest && total <= highest) || !std::isfinite(total))
    throw InvalidInput("total_reflectance", format_number(total),
                       "[" + format_number(lowest) + ", " + format_number(highest) + "] for the " + name() +
                           " model at eta = " + format_number(eta) + ", g = " + format_number(g));
  // The total rises monotonically with alpha'.
  return illinois_root([&](double a) { return total_at(a) - total; }, 0.0, 1.0, lowest - total, highest - total, 1e-15,
                       0.0, 1e-15 * total)
      .x;
}

double Model::radius_for_fraction(const Reduced<double>& m, double fraction) const {
  if (!(fraction > 0 && fraction < 1))
    throw InvalidInput("energy fraction", format_number(fraction), "0 < fraction < 1");
  const double target = fraction * total_reflectance(m);
  if (target == 0) return 0;  // nothing scatters (alpha' = 0): no light to hold
  const auto R = [&](double r) { return reflectance(m, r); };
  // C(b) - C(a) by integrating over [a, b] only: no step re-integrates from 0 (for models without a
  // closed-form C, forty bisection steps from 0 cost tens of milliseconds).
  const auto piece = [&](double a, double b) {
    return a < b ? integrate_radial(R, a, b, m.ell, 1e-11).value : -integrate_radial(R, b, a, m.ell, 1e-11).value;
  };
  // A bracket [lo, hi], a factor 2 wide, from one cumulative value at ell.
  double lo = m.ell, c_lo = cumulative_reflectance(m, lo), hi = lo, c_hi = c_lo;
  for (int k = 0; c_hi < target; ++k) {
    if (k == 60) return std::numeric_limits<double>::infinity();
    lo = hi;
    c_lo = c_hi;
    hi = 2 * lo;
    c_hi = c_lo + piece(lo, hi);
  }
  for (int k = 0; c_lo >= target && k < 60; ++k) {
    hi = lo;
    c_hi = c_lo;
    lo = hi / 2;
    c_lo = c_hi - piece(lo, hi);
  }
  if (c_lo >= target) return lo;
  BSSRDF_CHECK(lo < hi && c_lo < target && target <= c_hi);  // the bracket the two searches above built
  // Newton on C(r) = target (C' = 2 pi r R) from the secant point, bisecting in log r whenever a
  // step would leave the bracket.
  double r = lo + (target - c_lo) / (c_hi - c_lo) * (hi - lo), c = c_lo + piece(lo, r);
  for (int i = 0; i < 100 && hi / lo - 1 > 1e-13; ++i) {
    (c < target ? lo : hi) = r;
    double next = r - (c - target) / (2 * std::numbers::pi * r * R(r));
    if (!(next > lo && next < hi)) next = std::sqrt(lo * hi);
    c += piece(r, next);
    const double step = std::abs(next - r);
    r = next;
    if (step <= 1e-13 * r) break;
  }
  return r;
}

double radius_where(const std::function<double(double)>& cumulative, double target, double start, double precision) {
  double lo = 0, hi = start;
  for (int doubling = 0; cumulative(hi) < target; ++doubling) {
    if (doubling == 60) return std::numeric_limits<double>::infinity();
    lo = hi;
    hi *= 2;
  }
  // Bisect in log r: radii span decades.
  if (lo == 0) lo = hi * precision;
  BSSRDF_CHECK(lo < hi);
  while (hi / lo - 1 > precision) {
    const double mid = std::sqrt(lo * hi);
    (cumulative(mid) < target ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

ValidityReport Model::validity(const Reduced<double>& m) const {
  auto report = check_validity(m);
  // A model that cannot evaluate here (a table's domain) has said so; there is no total to check.
  if (worst(report) == Severity::invalid) return report;
  const double total = total_reflectance(m);
  if (total > 1)
    report.insert(report.begin(), {Severity::invalid, "energy",
                                   "total reflectance " + format_number(std::round(total * 1e5) / 1e5) +
                                       " exceeds 1: the model creates energy here"});
  return report;
}

SampledProfile Model::sample(const Reduced<double>& m, const std::vector<double>& radii) const {
  SampledProfile p;
  p.radius = radii;
  p.value.reserve(radii.size());
  for (double r : radii) p.value.push_back(reflectance(m, r));
  return p;
}

}  // namespace bssrdf
