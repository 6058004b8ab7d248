#include "bssrdf/profile.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bssrdf/cubic_hermite.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

// Three-point (second-order) derivative estimates of y(x) on a non-uniform grid.
std::vector<double> hermite_slopes(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<double> d(n);
  if (n == 2) {
    d[0] = d[1] = (y[1] - y[0]) / (x[1] - x[0]);
    return d;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    d[i] = (h1 * h1 * (y[i] - y[i - 1]) + h0 * h0 * (y[i + 1] - y[i])) / (h0 * h1 * (h0 + h1));
  }
  auto one_sided = [&](std::size_t a, std::size_t b, std::size_t c) {
    // Derivative at x[a] of the parabola through points a, b, c.
    const double h0 = x[b] - x[a], h1 = x[c] - x[b];
    return -(2 * h0 + h1) / (h0 * (h0 + h1)) * y[a] + (h0 + h1) / (h0 * h1) * y[b] - h0 / (h1 * (h0 + h1)) * y[c];
  };
  d[0] = one_sided(0, 1, 2);
  // Mirror the grid for the last point.
  {
    const std::size_t a = n - 1, b = n - 2, c = n - 3;
    const double h0 = x[a] - x[b], h1 = x[b] - x[c];
    d[a] = (2 * h0 + h1) / (h0 * (h0 + h1)) * y[a] - (h0 + h1) / (h0 * h1) * y[b] + h0 / (h1 * (h0 + h1)) * y[c];
  }
  return d;
}

// Integral over [x0, x0 + t h] of the cubic Hermite through (x0, y0, d0), (x0 + h, y1, d1).
double hermite_partial_integral(double h, double y0, double y1, double d0, double d1, double t) {
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t;
  const double H00 = t - t3 + t4 / 2, H10 = t2 / 2 - 2 * t3 / 3 + t4 / 4;
  const double H01 = t3 - t4 / 2, H11 = -t3 / 3 + t4 / 4;
  return h * (y0 * H00 + h * d0 * H10 + y1 * H01 + h * d1 * H11);
}

double hermite_value(double h, double y0, double y1, double d0, double d1, double t) {
  const auto [h00, h10, h01, h11] = hermite_basis(t);
  return h00 * y0 + h10 * h * d0 + h01 * y1 + h11 * h * d1;
}

struct Integrand {
  std::vector<double> y, d;  // 2 pi r R(r) and its slopes
};

Integrand radial_integrand(const SampledProfile& p) {
  Integrand f;
  f.y.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) f.y[i] = 2 * std::numbers::pi * p.radius[i] * p.value[i];
  f.d = hermite_slopes(p.radius, f.y);
  return f;
}

double inner_disc(const SampledProfile& p) { return std::numbers::pi * p.radius[0] * p.radius[0] * p.value[0]; }

}  // namespace

void SampledProfile::validate() const {
  if (radius.size() < 2) throw InvalidInput("radius", std::to_string(radius.size()) + " samples", ">= 2 samples");
  if (value.size() != radius.size())
    throw InvalidInput("profile: " + std::to_string(value.size()) + " values for " + std::to_string(radius.size()) +
                       " radii");
  if (!standard_error.empty() && standard_error.size() != radius.size())
    throw InvalidInput("profile: " + std::to_string(standard_error.size()) + " standard errors for " +
                       std::to_string(radius.size()) + " radii");
  for (std::size_t i = 0; i < radius.size(); ++i) {
    if (!std::isfinite(radius[i]) || radius[i] < 0)
      throw InvalidInput("radius[" + std::to_string(i) + "]", format_number(radius[i]), ">= 0 and finite");
    if (i > 0 && !(radius[i] > radius[i - 1]))
      throw InvalidInput(
          "radius[" + std::to_string(i) + "]", format_number(radius[i]),
          "> radius[" + std::to_string(i - 1) + "] = " + format_number(radius[i - 1]) + " (radii must increase)");
    if (!std::isfinite(value[i]))
      throw InvalidInput("reflectance[" + std::to_string(i) + "]", format_number(value[i]), "finite");
  }
}

double SampledProfile::integrate() const { return cumulative(radius.back()); }

double SampledProfile::cumulative(double r) const {
  if (size() < 2) return 0;
  if (r <= radius[0]) {
    const double c = std::max(r, 0.0);
    return std::numbers::pi * c * c * value[0];
  }
  const Integrand f = radial_integrand(*this);
  double sum = inner_disc(*this);
  for (std::size_t i = 0; i + 1 < size(); ++i) {
    const double h = radius[i + 1] - radius[i];
    const double t = std::min(1.0, (r - radius[i]) / h);
    sum += hermite_partial_integral(h, f.y[i], f.y[i + 1], f.d[i], f.d[i + 1], t);
    if (t < 1) break;
  }
  return sum;
}

double SampledProfile::integral_standard_error() const {
  if (standard_error.empty() || size() < 2) return 0;
  double variance = 0;
  for (std::size_t i = 0; i < size(); ++i) {
    const double left = i > 0 ? radius[i] - radius[i - 1] : 2 * radius[0];
    const double right = i + 1 < size() ? radius[i + 1] - radius[i] : 0;
    const double weight = 2 * std::numbers::pi * radius[i] * 0.5 * (left + right) +
                          (i == 0 ? std::numbers::pi * radius[0] * radius[0] : 0);
    variance += weight * weight * standard_error[i] * standard_error[i];
  }
  return std::sqrt(variance);
}

double SampledProfile::radius_for_fraction(double fraction) const {
  if (!(fraction > 0 && fraction <= 1))
    throw InvalidInput("energy fraction", format_number(fraction), "0 < fraction <= 1");
  const double target = fraction * integrate();
  double lo = 0, hi = radius.back();
  // cumulative() is continuous and, for non-negative profiles, non-decreasing: bisect.
  for (int iter = 0; iter < 200 && hi - lo > 1e-14 * radius.back(); ++iter) {
    const double mid = 0.5 * (lo + hi);
    (cumulative(mid) < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double SampledProfile::interpolate(double r) const {
  if (size() == 0) return 0;
  if (r <= radius.front()) return value.front();
  if (r > radius.back()) return 0;
  const bool log_log = radius.front() > 0 && std::all_of(value.begin(), value.end(), [](double v) { return v > 0; });
  std::vector<double> x(radius), y(value);
  if (log_log) {
    for (auto& v : x) v = std::log(v);
    for (auto& v : y) v = std::log(v);
  }
  const double u = log_log ? std::log(r) : r;
  const std::size_t i = std::min<std::size_t>(size() - 2, std::upper_bound(x.begin(), x.end(), u) - x.begin() - 1);
  const auto d = hermite_slopes(x, y);
  const double h = x[i + 1] - x[i];
  const double v = hermite_value(h, y[i], y[i + 1], d[i], d[i + 1], (u - x[i]) / h);
  return log_log ? std::exp(v) : v;
}

std::vector<double> log_spaced(double r_min, double r_max, std::size_t n) {
  if (!(r_min > 0) || !std::isfinite(r_min)) throw InvalidInput("r_min", format_number(r_min), "> 0 for log spacing");
  if (!(r_max > r_min) || !std::isfinite(r_max))
    throw InvalidInput("r_max", format_number(r_max), "> r_min = " + format_number(r_min));
  if (n < 2) throw InvalidInput("samples", std::to_string(n), ">= 2");
  std::vector<double> r(n);
  const double ratio = std::log(r_max / r_min) / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) r[i] = r_min * std::exp(ratio * static_cast<double>(i));
  r.back() = r_max;
  return r;
}

std::vector<double> linear_spaced(double r_min, double r_max, std::size_t n) {
  if (!(r_min >= 0) || !std::isfinite(r_min)) throw InvalidInput("r_min", format_number(r_min), ">= 0");
  if (!(r_max > r_min) || !std::isfinite(r_max))
    throw InvalidInput("r_max", format_number(r_max), "> r_min = " + format_number(r_min));
  if (n < 2) throw InvalidInput("samples", std::to_string(n), ">= 2");
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i)
    r[i] = r_min + (r_max - r_min) * static_cast<double>(i) / static_cast<double>(n - 1);
  return r;
}

}  // namespace bssrdf
