#include "bssrdf/models/quantized_diffusion.hpp"

#include <map>
#include <mutex>
#include <numeric>
#include <tuple>

#include "bssrdf/error.hpp"
#include "bssrdf/models/diffusion_validity.hpp"

namespace bssrdf::quantized_diffusion {

double ratio_for_tolerance(double albedo_prime, double eta, double tolerance) {
  const auto m = reduced_optical(albedo_prime, eta);
  const auto b = improved_boundary(eta);
  const double radii[] = {1e-2, 0.1, 0.3, 1,
                          3,    10};  // beyond ~10 ell a Gaussian mixture cannot follow the exponential tail closely
  const auto evaluate = [&](double ratio) {
    const auto mix = mixture(m, b, ratio);
    std::vector<double> values;
    for (double r : radii) values.push_back(reflectance(mix, r));
    values.push_back(std::accumulate(mix.weight.begin(), mix.weight.end(), 0.0));
    return values;
  };
  double ratio = (1 + std::sqrt(5.0)) / 2;
  auto coarse = evaluate(ratio);
  for (int k = 0; k < 5; ++k) {
    const double finer = std::sqrt(ratio);
    const auto fine = evaluate(finer);
    bool converged = true;
    for (std::size_t i = 0; i < fine.size(); ++i)
      converged &= std::abs(fine[i] - coarse[i]) <= tolerance * std::abs(fine[i]) + 1e-300;
    // Second-order convergence: the finer mixture's error is about a third of the difference.
    if (converged) return finer;
    ratio = finer;
    coarse = fine;
  }
  return ratio;
}

double ratio_for_tolerance(double eta, double tolerance) {
  // One ratio per (eta, tolerance), the finest needed over the albedos that matter: the model is
  // then one smooth function of the coefficients (fits differentiate it).
  double ratio = 2;
  for (double a : {0.5, 0.9, 0.99}) ratio = std::min(ratio, ratio_for_tolerance(a, eta, tolerance));
  return ratio;
}

double Model::ratio(const Reduced<double>& m) const {
  static std::mutex mutex;
  static std::map<std::pair<double, double>, double> cache;
  const auto key = std::pair{m.eta, tolerance_};
  std::lock_guard lock(mutex);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, ratio_for_tolerance(m.eta, tolerance_)).first;
  return it->second;
}

Mixture<double> Model::gaussians(const Reduced<double>& m) const {
  // Profiles evaluate many radii of one medium: keep the last mixture.
  thread_local std::tuple<double, double, double, double> key{-1, -1, -1, -1};
  thread_local Mixture<double> cached;
  const auto k = std::tuple{m.sigma_a, m.sigma_s_prime, m.eta, tolerance_};
  if (k != key) {
    cached = mixture(m, improved_boundary(m.eta), ratio(m));
    key = k;
  }
  return cached;
}

std::string Model::description() const {
  return "quantized diffusion (d'Eon & Irving 2011): improved diffusion as a sum of 2D Gaussians, "
         "multiple scattering only; bin ratio chosen for relative tolerance " +
         format_number(tolerance_);
}

double Model::reflectance(const Reduced<double>& m, double r) const {
  return quantized_diffusion::reflectance(gaussians(m), r);
}

double Model::total_reflectance(const Reduced<double>& m) const {
  const auto mix = gaussians(m);
  return std::accumulate(mix.weight.begin(), mix.weight.end(), 0.0);
}

ValidityReport Model::check_validity(const Reduced<double>& m) const {
  auto report = diffusion_validity(m, measured_limits(name()));
  const auto mix = gaussians(m);
  report.push_back({Severity::note, "quadrature",
                    std::to_string(mix.variance.size()) + " Gaussians, bin ratio " +
                        format_number(std::round(ratio(m) * 1e4) / 1e4) + " (relative tolerance " +
                        format_number(tolerance_) + ")"});
  return report;
}

}  // namespace bssrdf::quantized_diffusion
