#include "bssrdf/models/with_single_scattering.hpp"

#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

#include "bssrdf/error.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "bssrdf/single_scattering.hpp"

namespace bssrdf {

WithSingleScattering::WithSingleScattering(std::unique_ptr<Model> base, double tolerance)
    : base_(std::move(base)), tolerance_(tolerance) {
  if (!(tolerance > 0 && tolerance < 1))
    throw InvalidInput("single-scattering tolerance", format_number(tolerance), "0 < tolerance < 1");
  if (base_->includes_single_scattering())
    throw InvalidInput("model", "'" + base_->name() + "+ss'",
                       "a model without single scattering: " + base_->name() + " already includes it");
}

std::string WithSingleScattering::description() const {
  return base_->description() + ", plus exact single scattering (Gauss-Legendre order for relative tolerance " +
         format_number(tolerance_) + ")";
}

int WithSingleScattering::samples(const Reduced<double>& m) const {
  static std::mutex mutex;
  static std::map<std::tuple<std::string, double, double, double, double, double>, int> cache;
  const auto key = std::tuple{base_->name(), m.albedo_prime, m.albedo(), m.g, m.eta, tolerance_};
  std::lock_guard lock(mutex);
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  constexpr int kOrders[] = {8, 12, 16, 24, 32, 48, 64};
  int chosen = kOrders[std::size(kOrders) - 1];
  for (std::size_t k = 0; k + 1 < std::size(kOrders) && chosen == kOrders[std::size(kOrders) - 1]; ++k) {
    bool converged = true;
    for (double r : {1e-3, 1e-2, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0}) {
      const double x = r * m.ell,
                   whole = base_->reflectance(m, x) + single_scattering_reflectance(m, x, kOrders[k + 1]);
      converged &=
          std::abs(single_scattering_reflectance(m, x, kOrders[k]) -
                   single_scattering_reflectance(m, x, kOrders[k + 1])) <= tolerance_ * std::abs(whole) + 1e-300;
    }
    if (converged) chosen = kOrders[k];
  }
  cache.emplace(key, chosen);
  return chosen;
}

double WithSingleScattering::reflectance(const Reduced<double>& m, double r) const {
  if (!(r > 0)) return std::numeric_limits<double>::infinity();
  return base_->reflectance(m, r) + single_scattering_reflectance(m, r, samples(m));
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
