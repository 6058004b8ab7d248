#include "bssrdf/models/photon_beam_diffusion.hpp"

#include <map>
#include <mutex>
#include <tuple>

#include "bssrdf/error.hpp"
#include "bssrdf/models/diffusion_validity.hpp"

namespace bssrdf::photon_beam_diffusion {
namespace {

constexpr int kOrders[] = {8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256};

}  // namespace

int samples_for_tolerance(double albedo_prime, double g, double eta, double tolerance) {
  // Optical units (sigma_t' = 1); the unreduced coefficients keep g for the single-scattering part.
  const auto m = reduced_optical(albedo_prime, g, eta);
  const auto& b = improved_boundary(eta);
  const double radii[] = {1e-3, 1e-2, 0.1, 0.3, 1, 3, 10, 30};
  std::vector<double> previous;
  for (std::size_t k = 0; k < std::size(kOrders); ++k) {
    std::vector<double> current;
    for (double r : radii) current.push_back(reflectance(m, b, r, kOrders[k]));
    if (!previous.empty()) {
      bool converged = true;
      for (std::size_t i = 0; i < current.size(); ++i)
        converged &= std::abs(current[i] - previous[i]) <= tolerance * std::abs(current[i]) + 1e-300;
      if (converged) return kOrders[k - 1];
    }
    previous = std::move(current);
  }
  return kOrders[std::size(kOrders) - 1];
}

int Model::samples(const Reduced<double>& m) const {
  // Calibrated once per (alpha', g, eta, tolerance): profiles evaluate many radii of one medium.
  static std::mutex mutex;
  static std::map<std::tuple<double, double, double, double>, int> cache;
  const auto key = std::tuple{m.albedo_prime, m.g, m.eta, tolerance_};
  std::lock_guard lock(mutex);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, samples_for_tolerance(m.albedo_prime, m.g, m.eta, tolerance_)).first;
  return it->second;
}

std::string Model::description() const {
  return "photon beam diffusion (Habel et al. 2013): better-dipole kernel integrated along the beam "
         "+ exact single scattering; Gauss-Legendre order chosen for relative tolerance " +
         format_number(tolerance_);
}

double Model::reflectance(const Reduced<double>& m, double r) const {
  return photon_beam_diffusion::reflectance(m, cached_improved_boundary(m.eta), r, samples(m));
}

double Model::total_reflectance(const Reduced<double>& m) const {
  const int n = samples(m);
  const auto& b = cached_improved_boundary(m.eta);
  const double ms = integrate_radial([&](double r) { return multiple_scattering(m, b, r, n); }, 0.0,
                                     std::numeric_limits<double>::infinity(), m.ell, 1e-8)
                        .value;
  return ms + single_scattering_total(m.albedo(), m.g, m.eta);
}

ValidityReport Model::check_validity(const Reduced<double>& m) const {
  auto report = diffusion_validity(m, measured_limits(name()));
  report.push_back({Severity::note, "quadrature",
                    "beam integrals by " + std::to_string(samples(m)) + "-point Gauss-Legendre (relative tolerance " +
                        format_number(tolerance_) + ")"});
  return report;
}

}  // namespace bssrdf::photon_beam_diffusion
