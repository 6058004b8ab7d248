// Fresnel reflection at a smooth dielectric boundary and the diffuse quantities diffusion theory
// builds from it (Egan & Hilgeman 1979 fit of F_dr; d'Eon & Irving 2011 fits of the moments C1, C2). Templated on the
// scalar for ceres::Jet.
//
// Argument convention: x = n_incident / n_transmitted, the ratio seen by light *arriving* at the
// boundary. Light inside a medium of relative index eta = n_medium / n_outside meets the boundary
// with x = eta: the diffusion boundary condition (A, C_phi, C_E) uses these *internal* moments.
// Light entering from outside sees x = 1/eta (the *external* moments).
#pragma once

#include <cmath>
#include <cstddef>

#include "bssrdf/quadrature.hpp"

namespace bssrdf {

// Unpolarised reflectance for incidence cosine cos_i (in [0, 1]); 1 under total internal reflection.
template <class T>
T fresnel_reflectance(T cos_i, T x) {
  using std::sqrt;
  const T sin2_t = x * x * (T(1) - cos_i * cos_i);
  if (sin2_t >= T(1)) return T(1);
  const T cos_t = sqrt(T(1) - sin2_t);
  const T rs = (x * cos_i - cos_t) / (x * cos_i + cos_t);
  const T rp = (cos_i - x * cos_t) / (cos_i + x * cos_t);
  return (rs * rs + rp * rp) * T(0.5);
}

// Exact moment C_n(x) = int_0^1 F_r(mu) mu^n dmu. Under total internal reflection (x > 1) the part
// below the critical cosine mu_c is integrated in closed form; above it, mu = mu_c + (1 - mu_c)s^2
// removes the square-root kink at mu_c, so a 48-point Gauss-Legendre rule reaches ~1e-13.
template <class T>
T fresnel_moment(int n, T x) {
  using std::pow;
  using std::sqrt;
  T mu_c = T(0);
  if (x > T(1)) mu_c = sqrt(T(1) - T(1) / (x * x));
  const T below = pow(mu_c, n + 1) / T(n + 1);
  const T span = T(1) - mu_c;
  const auto integrand = [&](T s) {
    const T mu = mu_c + span * s * s;
    return fresnel_reflectance(mu, x) * pow(mu, n) * T(2) * span * s;
  };
  return below + integrate_gauss_legendre<T>(integrand, T(0), T(1), 48);
}

// d'Eon & Irving (2011) polynomial fits of 2 C1 and 3 C2, argument x as above. Measured absolute
// error against the exact moments over x in [0.5, 2] (tests/test_fresnel.cpp): 2C1 < 0.0045,
// 3C2 < 0.007. The library's own models use the exact moments.
inline constexpr double kFitErrorTwoC1 = 0.0045;
inline constexpr double kFitErrorThreeC2 = 0.007;
template <class T>
T fresnel_2c1_fit(T x) {
  if (x < T(1))
    return T(0.919317) + x * (T(-3.4793) + x * (T(6.75335) + x * (T(-7.80989) + x * (T(4.98554) + x * T(-1.36881)))));
  return T(-9.23372) + x * (T(22.2272) + x * (T(-20.9292) + x * (T(10.2291) + x * (T(-2.54396) + x * T(0.254913)))));
}
template <class T>
T fresnel_3c2_fit(T x) {
  if (x < T(1))
    return T(0.828421) + x * (T(-2.62051) + x * (T(3.36231) + x * (T(-1.95284) + x * (T(0.236494) + x * T(0.145787)))));
  const T inv = T(1) / x;
  return T(-1641.1) + inv * (T(1376.53) + inv * (T(-656.175) + inv * T(135.926))) +
         x * (T(1213.67) + x * (T(-568.556) + x * (T(164.798) + x * (T(-27.0181) + x * T(1.91826)))));
}

// Egan-Hilgeman fit of the internal diffuse reflectance F_dr(eta), as used by Jensen et al. 2001.
// Measured absolute error against the exact 2 C1(eta) over eta in [1, 2]: < 0.002.
inline constexpr double kFitErrorEganHilgeman = 0.002;
template <class T>
T diffuse_reflectance_egan_hilgeman(T eta) {
  if (eta < T(1)) return T(-0.4399) + T(0.7099) / eta - T(0.3319) / (eta * eta) + T(0.0636) / (eta * eta * eta);
  return T(-1.440) / (eta * eta) + T(0.710) / eta + T(0.668) + T(0.0636) * eta;
}

// Boundary parameter A: classical (1 + F_dr)/(1 - F_dr) with the Egan-Hilgeman F_dr.
template <class T>
T boundary_A_classical(T eta) {
  const T f = diffuse_reflectance_egan_hilgeman(eta);
  return (T(1) + f) / (T(1) - f);
}

// The improved boundary condition of d'Eon 2012 from the internal moments:
// A = (1 + 3 C2)/(1 - 2 C1), C_phi = (1 - 2 C1)/4, C_E = (1 - 3 C2)/2.
template <class T>
struct ImprovedBoundary {
  T two_c1, three_c2, A, C_phi, C_E;
};

template <class T>
ImprovedBoundary<T> improved_boundary(T eta) {
  ImprovedBoundary<T> b;
  b.two_c1 = T(2) * fresnel_moment(1, eta);
  b.three_c2 = T(3) * fresnel_moment(2, eta);
  b.A = (T(1) + b.three_c2) / (T(1) - b.two_c1);
  b.C_phi = (T(1) - b.two_c1) * T(0.25);
  b.C_E = (T(1) - b.three_c2) * T(0.5);
  return b;
}

// improved_boundary(eta) for the last eta seen on this thread: the two moment quadratures are the
// dominant cost when a profile evaluates many radii of one medium.
const ImprovedBoundary<double>& cached_improved_boundary(double eta);

}  // namespace bssrdf
