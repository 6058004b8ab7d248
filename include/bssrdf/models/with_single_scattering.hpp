// Any multiple-scattering model plus the exact single-scattering term (single_scattering.hpp),
// for models that omit it: R(r) = R_model(r) + R_ss(r). Named "<model>+ss".
#pragma once

#include <memory>

#include "bssrdf/model.hpp"

namespace bssrdf {

class WithSingleScattering final : public Model {
 public:
  // Throws InvalidInput if `base` already includes single scattering.
  explicit WithSingleScattering(std::unique_ptr<Model> base);
  std::string name() const override { return base_->name() + "+ss"; }
  std::string description() const override;
  bool includes_single_scattering() const override { return true; }
  double reflectance(const Reduced<double>& m, double r) const override;  // r = 0: infinite (R_ss ~ 1/r)
  double total_reflectance(const Reduced<double>& m) const override;
  ValidityReport check_validity(const Reduced<double>& m) const override;
  const Model& base() const { return *base_; }

 private:
  std::unique_ptr<Model> base_;
};

}  // namespace bssrdf
