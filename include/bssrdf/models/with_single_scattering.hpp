// Any multiple-scattering model plus the exact single-scattering term (single_scattering.hpp),
// for models that omit it: R(r) = R_model(r) + R_ss(r). Named "<model>+ss". The single-scattering
// quadrature order is the smallest (8 ... 64 Gauss-Legendre points) whose R(r) agrees with the next
// order to `tolerance` (relative to the whole R) at 1e-3 ... 30 ell, calibrated once per medium
// like photon beam diffusion's: as accurate as a fixed 64 points where it matters, and cheaper.
#pragma once

#include <memory>

#include "bssrdf/model.hpp"

namespace bssrdf {

class WithSingleScattering final : public Model {
 public:
  // Throws InvalidInput if `base` already includes single scattering.
  explicit WithSingleScattering(std::unique_ptr<Model> base, double tolerance = 1e-4);
  std::string name() const override { return base_->name() + "+ss"; }
  std::string description() const override;
  bool includes_single_scattering() const override { return true; }
  double reflectance(const Reduced<double>& m, double r) const override;  // r = 0: infinite (R_ss ~ 1/r)
  double total_reflectance(const Reduced<double>& m) const override;
  ValidityReport check_validity(const Reduced<double>& m) const override;
  const Model& base() const { return *base_; }
  int samples(const Reduced<double>& m) const;  // the single-scattering order used for m

 private:
  std::unique_ptr<Model> base_;
  double tolerance_;
};

}  // namespace bssrdf
