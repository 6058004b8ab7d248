// Normalized diffusion (Christensen & Burley 2015): an empirical
// two-exponential profile with closed-form CDF and inverse CDF, scaled to a physical profile by one
// of three published fits of d against the surface albedo A (which includes single scattering).
//
//   R(r) = A (e^{-r/d} + e^{-r/(3d)}) / (8 pi d r),   int 2 pi r R dr = A
//   CDF(r) = 1 - e^{-r/d}/4 - 3 e^{-r/(3d)}/4
//   r(u) = 3d ln((1 + 1/h + h) / (4(1 - u))),  h = (9 - 16u + 8u^2 + 4(1 - u) sqrt(5 - 8u + 4u^2))^{1/3}
//   searchlight, mfp:           s = 1.85 - A + 7|A - 0.8|^3,   d = ell / s
//   diffuse transmission, mfp:  s = 1.9 - A + 3.5 (A - 0.8)^2,  d = ell / s
//   searchlight, dmfp:          s = 3.5 + 100 (A - 0.33)^4,     d = ell_d / s
//
// "mfp" is taken as the transport mean free path ell = 1/sigma_t' (the fits were made with
// isotropic scattering, where it equals 1/sigma_t); dmfp is the classical ell_d = 1/sigma_tr.
// The surface albedo A is given directly, or taken from quantized diffusion's total (the physical
// model with the smallest measured total error for alpha' >= 0.8, and smooth in alpha'). The fits
// were made for an index-matched boundary.
#pragma once

#include <cmath>
#include <numbers>
#include <optional>

#include "bssrdf/model.hpp"

namespace bssrdf::normalized_diffusion {

enum class Scaling { searchlight_mfp, diffuse_mfp, searchlight_dmfp };

template <class T>
T profile(T A, T d, T r) {
  using std::exp;
  return A * (exp(-r / d) + exp(-r / (T(3) * d))) / (T(8) * std::numbers::pi * d * r);
}

template <class T>
T cdf(T d, T r) {
  using std::exp;
  return T(1) - T(0.25) * exp(-r / d) - T(0.75) * exp(-r / (T(3) * d));
}

template <class T>
T inverse_cdf(T d, T u) {
  using std::cbrt;
  using std::log;
  using std::sqrt;
  const T w = T(1) - u;
  const T h = cbrt(T(9) - T(16) * u + T(8) * u * u + T(4) * w * sqrt(T(5) - T(8) * u + T(4) * u * u));
  return T(3) * d * log((T(1) + T(1) / h + h) / (T(4) * w));
}

template <class T>
T scaling_factor(Scaling scaling, T A) {
  using std::abs;
  switch (scaling) {
    case Scaling::searchlight_mfp:
      return T(1.85) - A + T(7) * abs(A - T(0.8)) * (A - T(0.8)) * (A - T(0.8));
    case Scaling::diffuse_mfp:
      return T(1.9) - A + T(3.5) * (A - T(0.8)) * (A - T(0.8));
    case Scaling::searchlight_dmfp: {
      const T x = A - T(0.33);
      return T(3.5) + T(100) * x * x * x * x;
    }
  }
  return T(1);
}

// Burley's d for a medium with surface albedo A.
template <class T>
T shape_parameter(Scaling scaling, const Reduced<T>& m, T A) {
  const T length = scaling == Scaling::searchlight_dmfp ? m.ell_d : m.ell;
  return length / scaling_factor(scaling, A);
}

class Model final : public bssrdf::Model {
 public:
  // surface_albedo: A given directly (all channels); otherwise quantized diffusion's total.
  explicit Model(Scaling scaling, std::optional<double> surface_albedo = std::nullopt)
      : scaling_(scaling), surface_albedo_(surface_albedo) {}
  std::string name() const override;
  std::string description() const override;
  bool includes_single_scattering() const override { return true; }  // A includes it
  double reflectance(const Reduced<double>& m, double r) const override;
  double total_reflectance(const Reduced<double>& m) const override;  // = A
  double cumulative_reflectance(const Reduced<double>& m, double r) const override;
  ValidityReport check_validity(const Reduced<double>& m) const override;

  double surface_albedo(const Reduced<double>& m) const;
  double shape_parameter(const Reduced<double>& m) const;  // d, in the length unit of m
  Scaling scaling() const { return scaling_; }

 private:
  Scaling scaling_;
  std::optional<double> surface_albedo_;
};

}  // namespace bssrdf::normalized_diffusion
