// Exact single scattering below a smooth planar boundary for a normally incident pencil beam, with
// the true Henyey-Greenstein phase function (not the similarity-reduced one) and total internal
// reflection on exit (Habel, Christensen & Jarosz 2013, single-scattering term). Diffusion models omit this part; add
// it (models/with_single_scattering.hpp) before comparing with totals that include it (adding-doubling, Monte Carlo).
// All per unit entered flux.
//
//   R_ss(r) = int_{t_c}^inf sigma_s e^{-sigma_t t} p(-t/d) e^{-sigma_t d} (1 - F_r(t/d)) (t/d) / d^2 dt,
//             d = sqrt(r^2 + t^2), t_c = r sqrt(eta^2 - 1)
//   R_ss    = alpha int_0^1 2 pi p(-mu) (1 - F_r(mu)) mu / (1 + mu) dmu
//   eta = 1, g = 0:  R_ss = (alpha / 2)(1 - ln 2)
//
// With t = r sinh v (so d = r cosh v, t + d = r e^v, and total internal reflection below
// v_c = acosh(eta)) the profile becomes a smooth one-dimensional integral:
//   R_ss(r) = (sigma_s / r) int_{v_c}^inf e^{-sigma_t r e^v} f(e^v) dv,
//   f(x)    = p(-mu) (1 - F_r(mu)) sinh v / cosh^2 v   (x = e^v, mu = tanh v: single_scattering_exit)
// The medium enters the angular factor f only through g and eta, the radius only through the
// exponential: single_scattering_reflectance integrates it radius by radius, single_scattering_ln_y
// for a whole log-spaced set of radii at once.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/quadrature.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/scalar_math.hpp"

namespace bssrdf {

// Henyey-Greenstein phase function value for the cosine between propagation directions.
template <class T>
T henyey_greenstein(T cos_theta, T g) {
  using std::sqrt;
  const T denom = T(1) + g * g - T(2) * g * cos_theta;
  return (T(1) - g * g) / (T(4) * std::numbers::pi * denom * sqrt(denom));
}

// Total single-scattering reflectance, semi-infinite medium.
double single_scattering_total(double albedo, double g, double eta);

// C in R_ss(r) -> sigma_s C / r as r -> 0 (the exponential above -> 1): C = int_{v_c}^inf f dv
// = int_0^{theta_c} p(-cos theta) (1 - F_r(cos theta)) cos theta dtheta (mu = tanh v = cos theta,
// sin theta_c = 1 / eta), by 12-point Gauss-Legendre with the square-root onset at theta_c removed
// (within 5e-11 of 64 points at g 0 to 0.999, eta 1 to 2; g >= 0: a backward lobe without a peak).
double single_scattering_singular_coefficient(double g, double eta);

// x_c = e^{v_c} = eta + sqrt(eta^2 - 1), v_c = acosh(eta): light from below leaves only where
// x = (t + d) / r > x_c (total internal reflection under it); 1 when eta <= 1.
template <class T>
T critical_exit_ratio(T eta) {
  using std::sqrt;
  return eta > T(1) ? eta + sqrt(eta * eta - T(1)) : T(1);
}

// The angular factor f(x) per unit v at x = e^v = (t + d) / r, without a transcendental call: light
// leaves with cosine mu = tanh v = (x^2 - 1) / (x^2 + 1) after one Henyey-Greenstein scattering through
// pi - acos(mu), and sinh v / cosh^2 v = 2 x (x^2 - 1) / (x^2 + 1)^2.
template <class T>
T single_scattering_exit(const Reduced<T>& m, T x) {
  const T x2 = x * x, mu = (x2 - T(1)) / (x2 + T(1));
  return henyey_greenstein(-mu, m.g) * (T(1) - fresnel_reflectance(mu, m.eta)) * T(2) * x * (x2 - T(1)) /
         ((x2 + T(1)) * (x2 + T(1)));
}

// R_ss(r) by `samples`-point Gauss-Legendre in s, v = v_c + (v_max - v_c) s^2 (the square removes
// the square-root onset of transmission at the critical angle); v_max where e^{-sigma_t r e^v}
// < 1e-17. r = 0 is singular (R_ss ~ 1/r): callers evaluate r > 0.
template <class T>
T single_scattering_reflectance(const Reduced<T>& m, T r, int samples = 64) {
  using std::exp;
  using std::log;
  const T sigma_t = m.sigma_t();
  const T v_c = log(critical_exit_ratio(m.eta));
  T v_max = log(T(40) / (sigma_t * r));
  if (v_max < v_c + T(4)) v_max = v_c + T(4);  // the integrand still decays as e^{-v} up there
  const T span = v_max - v_c;
  const auto integrand = [&](T s) {
    const T x = exp(v_c + span * s * s);
    return exp(-sigma_t * r * x) * single_scattering_exit(m, x) * T(2) * span * s;
  };
  return m.sigma_s / r * integrate_gauss_legendre<T>(integrand, T(0), T(1), static_cast<std::size_t>(samples));
}

// ln y_ss(r_k), y_ss = 2 pi r^2 R_ss, at the radii r_k = e^{ln_r0 + k d_ln_r}, k < radii: the
// integral above for a whole log-spaced set of radii at once, in logarithms (no underflow far out).
// With x = x_c + e^tau (x_c = e^{v_c}) it is R_ss = (sigma_s / r) e^{-rho x_c} J(rho), rho = sigma_t r,
//   J(rho) = int_{-inf}^{inf} exp(-e^{tau + ln rho}) f(x_c + e^tau) e^tau / (x_c + e^tau) dtau,
// an integrand analytic in a strip about the real axis, decaying double-exponentially on one side and
// as e^{1.5 tau} (the square-root onset at the critical angle) on the other, of the same shape in
// tau + ln rho at every radius. The trapezoidal rule converges exponentially on it (Trefethen &
// Weideman 2014, SIAM Review 56(3) 385, Theorem 5.1: error ~ e^{-2 pi a / h}, a = pi / 2 here).
// Its step is a whole multiple of d_ln_r (or d_ln_r a multiple of it), so that tau_j + ln rho_k
// falls on one grid: the angular factor is evaluated once per node and the kernel exp(-e^s) once
// per grid point, and each radius is a sum of their products. Measured against an adaptive
// integral to 1e-13 (tests/test_extended_models.cpp): relative error < 6e-7 at 12 radii a decade
// (step 0.499), < 4e-6 on other grids (step up to 0.5), g 0 to 0.999, eta 0.8 to 2.
std::vector<double> single_scattering_ln_y(const Reduced<double>& m, double ln_r0, double d_ln_r, std::size_t radii);

}  // namespace bssrdf
