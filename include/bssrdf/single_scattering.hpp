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
//   R_ss(r) = (sigma_s / r) int_{v_c}^inf e^{-sigma_t r e^v} p(-tanh v) (1 - F_r(tanh v)) sinh v / cosh^2 v dv
#pragma once

#include <cmath>
#include <numbers>

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

// R_ss(r) by `samples`-point Gauss-Legendre in s, v = v_c + (v_max - v_c) s^2 (the square removes
// the square-root onset of transmission at the critical angle); v_max where e^{-sigma_t r e^v}
// < 1e-17. r = 0 is singular (R_ss ~ 1/r): callers evaluate r > 0.
template <class T>
T single_scattering_reflectance(const Reduced<T>& m, T r, int samples = 64) {
  using std::exp;
  using std::log;
  using std::sinh;
  const T sigma_t = m.sigma_t();
  const T v_c = m.eta > T(1) ? inverse_cosh(m.eta) : T(0);
  T v_max = log(T(40) / (sigma_t * r));
  if (v_max < v_c + T(4)) v_max = v_c + T(4);  // the integrand still decays as e^{-v} up there
  const T span = v_max - v_c;
  const auto integrand = [&](T s) {
    const T v = v_c + span * s * s;
    // One transcendental call: cosh v = sqrt(1 + sinh^2 v), tanh = sinh / cosh, e^v = sinh + cosh.
    const T sh = sinh(v), c = sqrt(T(1) + sh * sh), mu = sh / c;
    return exp(-sigma_t * r * (sh + c)) * henyey_greenstein(-mu, m.g) * (T(1) - fresnel_reflectance(mu, m.eta)) * sh /
           (c * c) * T(2) * span * s;
  };
  return m.sigma_s / r * integrate_gauss_legendre<T>(integrand, T(0), T(1), static_cast<std::size_t>(samples));
}

}  // namespace bssrdf
