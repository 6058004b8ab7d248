#include "bssrdf/models/with_single_scattering.hpp"

#include <limits>

#include "bssrdf/error.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "bssrdf/single_scattering.hpp"

namespace bssrdf {

WithSingleScattering::WithSingleScattering(std::unique_ptr<Model> base) : base_(std::move(base)) {
  if (base_->includes_single_scattering())
    throw InvalidInput("model", "'" + base_->name() + "+ss'",
                       "a model without single scattering: " + base_->name() + " already includes it");
}

std::string WithSingleScattering::description() const {
  return base_->description() + ", plus exact single scattering";
}

double WithSingleScattering::reflectance(const Reduced<double>& m, double r) const {
  if (!(r > 0)) return std::numeric_limits<double>::infinity();
  return base_->reflectance(m, r) + single_scattering_reflectance(m, r);
}

double WithSingleScattering::total_reflectance(const Reduced<double>& m) const {
  return base_->total_reflectance(m) + single_scattering_total(m.albedo(), m.g, m.eta);
}

ValidityReport WithSingleScattering::check_validity(const Reduced<double>& m) const {
  auto report = diffusion_validity(m, measured_limits(name()));
  report.push_back({Severity::note, "singular_at_origin",
                    "single scattering makes R(r) ~ 1/r as r -> 0: integrable, but R(0) is infinite"});
  return report;
}

}  // namespace bssrdf
