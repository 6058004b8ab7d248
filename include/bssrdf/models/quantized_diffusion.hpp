// Quantized diffusion (d'Eon & Irving 2011): the same improved
// diffusion theory as photon beam diffusion, evaluated as a sum of 2D Gaussians by quantising the
// path length ("time") tau into geometric bins. Multiple scattering only.
//
//   bin i = [tau_i, tau_{i+1}]: variance v_i = D (tau_i + tau_{i+1}),
//   weight w_i = (e^{-sigma_a tau_i} - e^{-sigma_a tau_{i+1}}) / sigma_a
//   R(r) = alpha' sum_i w_i W_R(v_i) G2(v_i, r),   G2(v, r) = e^{-r^2/(2v)} / (2 pi v)
//   W_phi(v, d) = (alpha' sigma/2) e^{sigma(d + sigma v/2)} erfc((d + sigma v)/sqrt(2v))   (sigma = sigma_t')
//   W_E(v, d)/D = sigma [ -W_phi(v, d) + alpha' G1(v; d) ],   G1(v, z) = e^{-z^2/(2v)} / sqrt(2 pi v)
//   W_R(v) = C_phi [W_phi(v, 0) - W_phi(v, d_e)] + C_E D [W_E(v, 0)/D + W_E(v, d_e)/D],  d_e = 4 A D
//
// The first bin is [0, tau_0]; bins continue until e^{-sigma_a tau} < 1e-12 or tau > 1e10 ell.
// The bin ratio sets the accuracy: 1.618 (the paper) down to 1.618^(1/16), chosen from a
// tolerance like the photon-beam quadrature. The mixture itself is exposed for sum-of-Gaussians
// renderers (R(r) = sum weight_i G2(variance_i, r); sum weight_i = total reflectance).
#pragma once

#include <cmath>
#include <vector>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/image_source.hpp"
#include "bssrdf/models/point_source.hpp"
#include "bssrdf/scalar_math.hpp"

namespace bssrdf::quantized_diffusion {

template <class T>
struct Mixture {
  std::vector<T> variance;  // length^2
  std::vector<T> weight;    // dimensionless: the total reflectance carried by each Gaussian
};

template <class T>
T gaussian_2d(T variance, T r) {
  using std::exp;
  return exp(-r * r / (T(2) * variance)) / (T(2) * std::numbers::pi * variance);
}

template <class T>
Mixture<T> mixture(const Reduced<T>& m, const ImprovedBoundary<T>& b, double ratio) {
  using std::exp;
  using std::sqrt;
  const T sigma = m.sigma_t_prime, a = m.albedo_prime, D = m.D_G, d_e = T(2) * extrapolation_distance(b.A, D);
  const auto G1 = [](T v, T z) { return exp(-z * z / (T(2) * v)) / sqrt(T(2) * std::numbers::pi * v); };
  // W_phi = (alpha' sigma / 2) e^{-d^2/(2v)} erfcx((d + sigma v)/sqrt(2v)): no overflow.
  const auto W_phi = [&](T v, T d) {
    return a * sigma * T(0.5) * exp(-d * d / (T(2) * v)) * erfcx((d + sigma * v) / sqrt(T(2) * v));
  };
  const auto W_E_over_D = [&](T v, T d) { return sigma * (-W_phi(v, d) + a * G1(v, d)); };
  const auto W_R = [&](T v) {
    return b.C_phi * (W_phi(v, T(0)) - W_phi(v, d_e)) + b.C_E * D * (W_E_over_D(v, T(0)) + W_E_over_D(v, d_e));
  };
  Mixture<T> out;
  const T tau_0 = T(1e-7) * m.ell, tau_end = T(1e10) * m.ell;
  T lo = T(0), hi = tau_0;
  while (true) {
    // int_lo^hi e^{-sigma_a tau} d tau, exact also for sigma_a -> 0.
    const T w = exp(-m.sigma_a * lo) * (hi - lo) * point_source::one_minus_exp_over_x(m.sigma_a * (hi - lo));
    const T v = D * (lo + hi);
    out.variance.push_back(v);
    out.weight.push_back(a * w * W_R(v));
    if (m.sigma_a * hi > T(27.6) || hi > tau_end) break;  // e^{-27.6} = 1e-12
    lo = hi;
    hi = hi * T(ratio);
  }
  return out;
}

template <class T>
T reflectance(const Mixture<T>& mix, T r) {
  T sum = T(0);
  for (std::size_t i = 0; i < mix.variance.size(); ++i) sum += mix.weight[i] * gaussian_2d(mix.variance[i], r);
  return sum;
}

// The bin ratio whose profile agrees with the next finer one (ratio^(1/2)) to `tolerance` at
// radii 1e-2 ell ... 10 ell, and in total (further out the tail is exponential, which Gaussians
// follow only loosely).
double ratio_for_tolerance(double albedo_prime, double eta, double tolerance);
// The finest of those over alpha' in {0.5, 0.9, 0.99}: what the model uses, so that it is one
// smooth function of the coefficients at a given eta.
double ratio_for_tolerance(double eta, double tolerance);

class Model final : public bssrdf::Model {
 public:
  explicit Model(double tolerance = 1e-3) : tolerance_(tolerance) {}
  std::string name() const override { return "quantized"; }
  std::string description() const override;
  bool includes_single_scattering() const override { return false; }
  double reflectance(const Reduced<double>& m, double r) const override;
  double total_reflectance(const Reduced<double>& m) const override;  // sum of the weights
  ValidityReport check_validity(const Reduced<double>& m) const override;
  // The Gaussian mixture for these coefficients (lengths as in m).
  Mixture<double> gaussians(const Reduced<double>& m) const;
  double ratio(const Reduced<double>& m) const;

 private:
  double tolerance_;
};

}  // namespace bssrdf::quantized_diffusion
