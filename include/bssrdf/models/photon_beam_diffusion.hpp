// Photon beam diffusion (Habel, Christensen, Jarosz 2013): the
// better-dipole kernel integrated along the refracted beam, plus exact single scattering.
//
//   R_ms(r) = alpha'^2 int_0^inf sigma_t' e^{-sigma_t' t} kappa(t) E(r; t) dt,
//   E(r; t) = C_phi [fluence(t) - fluence(z_v)] + C_E [flux(t) - flux(z_v)],  z_v = -t - 4 A D_G,
//   kappa(t) = 1 - e^{-2 sigma_t' (d_r + t)}   (damps sources close to the exit point)
//   R(r) = R_ms(r) + R_ss(r)
//
// pbrt-v3/v4 take 100 midpoint samples of the exponential for each integral. Here the beam
// integral uses t = s sinh(v) with s = max(r, 1e-3 ell): d_r = s cosh v is smooth in v, the 1/d
// structure near the exit point is resolved for every r, and the exponential tail is a few points.
// An n-point Gauss-Legendre rule in v converges geometrically; n is chosen from a tolerance per
// (alpha', eta) by doubling until the profile at radii from 1e-3 ell to 30 ell changes less than
// the tolerance (samples_for_tolerance), and reported.
#pragma once

#include <cmath>
#include <numbers>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/image_source.hpp"
#include "bssrdf/models/point_source.hpp"
#include "bssrdf/quadrature.hpp"
#include "bssrdf/scalar_math.hpp"
#include "bssrdf/single_scattering.hpp"

namespace bssrdf::photon_beam_diffusion {

template <class T>
T multiple_scattering(const Reduced<T>& m, const ImprovedBoundary<T>& b, T r, int samples) {
  using std::exp;
  using std::sinh;
  using std::sqrt;
  const T sigma_tp = m.sigma_t_prime, sigma_tr = m.sigma_tr_G, D = m.D_G;
  const T z_b = extrapolation_distance(b.A, D);  // the image of depth t: z_v = image_depth(t, z_b)
  const T s = r > T(1e-3) * m.ell ? r : T(1e-3) * m.ell;
  const T t_max = T(40) * m.ell;  // e^{-40}: beyond double precision relative to the total
  const T v_max = inverse_sinh(t_max / s);
  const T r2 = r * r, inv_4pi = T(1) / (T(4) * std::numbers::pi);
  // point_source::fluence and flux at the real (z = t) and image (z = z_v) sources, written out so
  // that each distance and exponential is computed once (the same expressions, a third of the
  // transcendental calls): d_r is also kappa's distance, cosh v = sqrt(1 + sinh^2 v).
  const auto integrand = [&](T v) {
    const T sh = sinh(v);
    const T t = s * sh;
    const T dt_dv = s * sqrt(T(1) + sh * sh);
    const T d_r = sqrt(r2 + t * t);
    const T z_v = image_depth(t, z_b);
    const T d_v = sqrt(r2 + z_v * z_v);
    const T e_r = exp(-sigma_tr * d_r) / d_r, e_v = exp(-sigma_tr * d_v) / d_v;
    const T kappa = T(1) - exp(T(-2) * sigma_tp * (d_r + t));
    const T phi = (e_r - e_v) * inv_4pi / D;
    const T E =
        (t * (T(1) + sigma_tr * d_r) * e_r / (d_r * d_r) - z_v * (T(1) + sigma_tr * d_v) * e_v / (d_v * d_v)) * inv_4pi;
    return sigma_tp * exp(-sigma_tp * t) * kappa * (b.C_phi * phi + b.C_E * E) * dt_dv;
  };
  return m.albedo_prime * m.albedo_prime *
         integrate_gauss_legendre<T>(integrand, T(0), v_max, static_cast<std::size_t>(samples));
}

template <class T>
T reflectance(const Reduced<T>& m, const ImprovedBoundary<T>& b, T r, int samples) {
  T R = multiple_scattering(m, b, r, samples);
  if (r > T(0)) R += single_scattering_reflectance(m, r, samples);
  return R;
}

// The smallest Gauss-Legendre order (from 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256) whose
// profile agrees with the next order to `tolerance` (relative) at radii 1e-3 ell ... 30 ell.
int samples_for_tolerance(double albedo_prime, double g, double eta, double tolerance);

class Model final : public bssrdf::Model {
 public:
  explicit Model(double tolerance = 1e-4) : tolerance_(tolerance) {}
  std::string name() const override { return "pbd"; }
  std::string description() const override;
  bool includes_single_scattering() const override { return true; }
  double reflectance(const Reduced<double>& m, double r) const override;
  // Accurately integrated (adaptive in log r; r = 0 excluded: R_ss ~ 1/r is integrable).
  double total_reflectance(const Reduced<double>& m) const override;
  ValidityReport check_validity(const Reduced<double>& m) const override;
  // The quadrature order used for these coefficients.
  int samples(const Reduced<double>& m) const;
  double tolerance() const { return tolerance_; }

 private:
  double tolerance_;
};

}  // namespace bssrdf::photon_beam_diffusion
