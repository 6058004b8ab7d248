// Numerical integration used across the library: a fixed Gauss-Legendre rule (templated on the
// integrand's scalar so it runs under ceres::Jet) and an adaptive Gauss-Kronrod (7, 15) rule for
// double-precision integrals to a stated tolerance, including semi-infinite radial integrals.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

namespace bssrdf {

// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] (computed once, cached).
struct GaussLegendreRule {
  std::vector<double> nodes, weights;
};
const GaussLegendreRule& gauss_legendre(std::size_t n);

// Fixed n-point Gauss-Legendre integral of f over [a, b].
template <class T, class F>
T integrate_gauss_legendre(F&& f, T a, T b, std::size_t n = 32) {
  const auto& rule = gauss_legendre(n);
  const T half = (b - a) * 0.5, mid = (b + a) * 0.5;
  T sum = T(0);
  for (std::size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * f(mid + half * rule.nodes[i]);
  return sum * half;
}

struct QuadratureResult {
  double value = 0;
  double error_estimate = 0;
  int evaluations = 0;
  bool converged = false;
};

// Adaptive Gauss-Kronrod (7, 15) on [a, b] until |error| <= max(abs_tol, rel_tol |value|).
QuadratureResult integrate_adaptive(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-10,
                                    double abs_tol = 0.0, int max_intervals = 2000, int initial_pieces = 8);

// The radial integral of a profile, int_{r0}^{r1} 2 pi r R(r) dr, computed in u = ln r so that
// profiles spanning many decades of radius are resolved. r0 = 0 integrates from (scale * 1e-12),
// r1 = infinity up to (scale * 1e9); `scale` is the medium's characteristic length (e.g. ell).
QuadratureResult integrate_radial(const std::function<double(double)>& R, double r0, double r1, double scale,
                                  double rel_tol = 1e-10);

}  // namespace bssrdf
