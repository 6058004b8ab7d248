// Better dipole (d'Eon 2012): Grosjean D_G, the improved boundary
// condition A = (1 + 3C2)/(1 - 2C1) from the exact internal Fresnel moments, exitance from both
// fluence and flux, source strength alpha'^2 (multiple scattering only; add single scattering
// separately). z_r = 1/sigma_t', z_v = -(z_r + 4 A D_G) (image_source.hpp).
//
//   R(r) = alpha'^2 { C_phi [fluence(z_r) - fluence(z_v)] + C_E [flux(z_r) - flux(z_v)] }
//   R_total = (alpha'^2/2) e^{-sigma_tr z_r} [ C_E (1 + e^{-4 A sigma_tr D}) + (C_phi/(sigma_tr D)) (1 - e^{-4 A
//   sigma_tr D}) ]
#pragma once

#include <cmath>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/image_source.hpp"
#include "bssrdf/models/point_source.hpp"

namespace bssrdf::better_dipole {

template <class T>
struct Sources {
  T z_r, z_v, sigma_tr, D, C_phi, C_E, A;
};

template <class T>
Sources<T> sources(const Reduced<T>& m, const ImprovedBoundary<T>& b) {
  return {m.ell, image_depth(m.ell, extrapolation_distance(b.A, m.D_G)), m.sigma_tr_G, m.D_G, b.C_phi, b.C_E, b.A};
}

template <class T>
T reflectance(const Reduced<T>& m, const ImprovedBoundary<T>& b, T r) {
  using namespace point_source;
  const auto s = sources(m, b);
  const T phi = fluence(s.z_r, s.sigma_tr, s.D, r) - fluence(s.z_v, s.sigma_tr, s.D, r);
  const T E = flux(s.z_r, s.sigma_tr, r) - flux(s.z_v, s.sigma_tr, r);
  return m.albedo_prime * m.albedo_prime * (s.C_phi * phi + s.C_E * E);
}

template <class T>
T reflectance(const Reduced<T>& m, T r) {
  return reflectance(m, improved_boundary(m.eta), r);
}

template <class T>
T cumulative_reflectance(const Reduced<T>& m, const ImprovedBoundary<T>& b, T r) {
  using namespace point_source;
  const auto s = sources(m, b);
  // fluence_cumulative(z_r) - fluence_cumulative(z_v) written without cancellation as sigma_tr -> 0
  T phi;
  if (!(r < std::numeric_limits<double>::infinity())) {
    const T x = T(2) * extrapolation_distance(s.A, s.D);  // |z_v| - z_r
    using std::exp;
    phi = exp(-s.sigma_tr * s.z_r) * x * one_minus_exp_over_x(s.sigma_tr * x) / (T(2) * s.D);
  } else {
    phi = fluence_cumulative(s.z_r, s.sigma_tr, s.D, r) - fluence_cumulative(s.z_v, s.sigma_tr, s.D, r);
  }
  const T E = flux_cumulative(s.z_r, s.sigma_tr, r) - flux_cumulative(s.z_v, s.sigma_tr, r);
  return m.albedo_prime * m.albedo_prime * (s.C_phi * phi + s.C_E * E);
}

// Closed-form total; depends only on alpha' and the boundary (eta).
template <class T>
T total_reflectance(T albedo_prime, const ImprovedBoundary<T>& b) {
  using std::exp;
  using std::sqrt;
  const T a = albedo_prime;
  const T sigma_tr_D = sqrt((T(1) - a) * (T(2) - a) / T(3));
  const T x = T(4) * b.A * sigma_tr_D;
  return a * a * T(0.5) * exp(-sqrt(T(3) * (T(1) - a) / (T(2) - a))) *
         (b.C_E * (T(1) + exp(-x)) + b.C_phi * T(4) * b.A * point_source::one_minus_exp_over_x(x));
}

template <class T>
T total_reflectance(T albedo_prime, T eta) {
  return total_reflectance(albedo_prime, improved_boundary(eta));
}

class Model final : public bssrdf::Model {
 public:
  std::string name() const override { return "better-dipole"; }
  std::string description() const override;
  bool includes_single_scattering() const override { return false; }
  double reflectance(const Reduced<double>& m, double r) const override;
  double total_reflectance(const Reduced<double>& m) const override;
  double cumulative_reflectance(const Reduced<double>& m, double r) const override;
  ValidityReport check_validity(const Reduced<double>& m) const override;
};

}  // namespace bssrdf::better_dipole
