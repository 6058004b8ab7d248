#include "bssrdf/hankel.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "bssrdf/quadrature.hpp"

namespace bssrdf {

double bessel_j0_zero(int m) {
  // McMahon's expansion, then Newton on J0 (J0' = -J1).
  const double beta = (m - 0.25) * std::numbers::pi, b8 = 8 * beta;
  double x = beta + 1 / b8 - 124 / (3 * b8 * b8 * b8) + 120928 / (15 * std::pow(b8, 5));
  for (int i = 0; i < 3; ++i) x += std::cyl_bessel_j(0.0, x) / std::cyl_bessel_j(1.0, x);
  return x;
}

double hankel_transform(const std::function<double(double)>& f, double q, double scale, double rel_tol) {
  if (q == 0) {
    return integrate_radial(f, 0.0, std::numeric_limits<double>::infinity(), scale, rel_tol).value /
           (2 * std::numbers::pi);
  }
  const auto integrand = [&](double x) { return f(x) * std::cyl_bessel_j(0.0, q * x) * x; };
  // Half-waves between zeros of J0(q x); the alternating pieces are summed until three in a row
  // are negligible against the sum (or against the largest piece, when the sum itself is tiny).
  double sum = 0, largest = 0, a = 0;
  int quiet = 0;
  for (int m = 1; m < 2'000'000; ++m) {
    const double b = bessel_j0_zero(m) / q;
    const double piece = integrate_adaptive(integrand, a, b, rel_tol * 1e-2, 1e-3 * rel_tol * largest, 200, 1).value;
    sum += piece;
    largest = std::max(largest, std::abs(piece));
    const bool negligible = std::abs(piece) <= rel_tol * std::abs(sum) || std::abs(piece) <= 1e-16 * largest;
    quiet = negligible ? quiet + 1 : 0;
    if (quiet >= 3) break;
    a = b;
  }
  return sum;
}

}  // namespace bssrdf
