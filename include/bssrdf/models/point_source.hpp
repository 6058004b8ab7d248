// Exitance kernels of an isotropic point source at depth z in an infinite diffusive medium, and
// their closed-form radial integrals. Dipoles and multipoles are sums of these. Templated on the
// scalar; the 1/(4 pi) is included.
//
//   flux(z, r)    = z (1 + s d) e^{-s d} / (4 pi d^3)     (the -D dphi/dz term), d = sqrt(r^2 + z^2)
//   fluence(z, r) = e^{-s d} / (4 pi D d)
//   int_0^rho 2 pi r flux dr    = sgn(z) e^{-s|z|}/2 - z e^{-s d(rho)} / (2 d(rho))
//   int_0^rho 2 pi r fluence dr = (e^{-s|z|} - e^{-s d(rho)}) / (2 D s)
#pragma once

#include <cmath>
#include <limits>
#include <numbers>

namespace bssrdf::point_source {

// (1 - e^{-x}) / x, finite and accurate as x -> 0 (where it tends to 1).
template <class T>
T one_minus_exp_over_x(T x) {
  using std::exp;
  if (x < T(1e-4)) return T(1) - x * (T(0.5) - x * (T(1) / T(6)));
  return (T(1) - exp(-x)) / x;
}

template <class T>
T flux(T z, T sigma_tr, T r) {
  using std::exp;
  using std::sqrt;
  const T d = sqrt(r * r + z * z);
  return z * (T(1) + sigma_tr * d) * exp(-sigma_tr * d) / (T(4) * std::numbers::pi * d * d * d);
}

template <class T>
T fluence(T z, T sigma_tr, T D, T r) {
  using std::exp;
  using std::sqrt;
  const T d = sqrt(r * r + z * z);
  return exp(-sigma_tr * d) / (T(4) * std::numbers::pi * D * d);
}

// Radial integral of flux() from 0 to rho (rho = infinity allowed).
template <class T>
T flux_cumulative(T z, T sigma_tr, T rho) {
  using std::abs;
  using std::exp;
  using std::sqrt;
  const T az = abs(z);
  const T near = (z < T(0) ? T(-0.5) : T(0.5)) * exp(-sigma_tr * az);
  if (!(rho < std::numeric_limits<double>::infinity())) return near;
  const T d = sqrt(rho * rho + z * z);
  return near - z * exp(-sigma_tr * d) / (T(2) * d);
}

// Radial integral of fluence() from 0 to rho (rho = infinity allowed; diverges if sigma_tr = 0).
template <class T>
T fluence_cumulative(T z, T sigma_tr, T D, T rho) {
  using std::abs;
  using std::exp;
  using std::sqrt;
  const T az = abs(z);
  if (!(rho < std::numeric_limits<double>::infinity())) return exp(-sigma_tr * az) / (T(2) * D * sigma_tr);
  const T d = sqrt(rho * rho + z * z);
  const T span = d - az;
  return exp(-sigma_tr * az) * span * one_minus_exp_over_x(sigma_tr * span) / (T(2) * D);
}

}  // namespace bssrdf::point_source
