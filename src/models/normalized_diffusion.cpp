#include "bssrdf/models/normalized_diffusion.hpp"

#include <map>
#include <mutex>
#include <tuple>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"

namespace bssrdf::normalized_diffusion {

std::string Model::name() const {
  switch (scaling_) {
    case Scaling::searchlight_mfp:
      return "burley";
    case Scaling::diffuse_mfp:
      return "burley-diffuse";
    case Scaling::searchlight_dmfp:
      return "burley-dmfp";
  }
  return "burley";
}

std::string Model::description() const {
  const char* fit = scaling_ == Scaling::searchlight_mfp ? "searchlight mfp fit"
                    : scaling_ == Scaling::diffuse_mfp   ? "diffuse-transmission mfp fit"
                                                         : "searchlight dmfp fit";
  return std::string("normalized diffusion (Christensen & Burley 2015), ") + fit + "; surface albedo " +
         (surface_albedo_ ? "given: " + format_number(*surface_albedo_) : "from quantized diffusion");
}

double Model::surface_albedo(const Reduced<double>& m) const {
  if (surface_albedo_) return *surface_albedo_;
  // From quantized diffusion: of the physical models, the smallest measured total error against
  // adding-doubling for alpha' >= 0.8 (tests/test_adding_doubling.cpp), and one smooth function of
  // alpha', so that albedo inversion and fitting through Burley stay well-posed. The total depends
  // on (alpha', eta) only, so it is cached.
  static std::mutex mutex;
  static std::map<std::tuple<double, double, double>, double> cache;
  const auto key = std::tuple{m.albedo_prime, m.g, m.eta};
  std::lock_guard lock(mutex);
  auto it = cache.find(key);
  if (it == cache.end()) {
    const auto optical = reduced_optical(m.albedo_prime, m.g, m.eta);
    it = cache.emplace(key, quantized_diffusion::Model().total_reflectance(optical)).first;
  }
  return it->second;
}

double Model::shape_parameter(const Reduced<double>& m) const {
  return normalized_diffusion::shape_parameter(scaling_, m, surface_albedo(m));
}

double Model::reflectance(const Reduced<double>& m, double r) const {
  return profile(surface_albedo(m), shape_parameter(m), r);
}

double Model::total_reflectance(const Reduced<double>& m) const { return surface_albedo(m); }

double Model::cumulative_reflectance(const Reduced<double>& m, double r) const {
  return surface_albedo(m) * cdf(shape_parameter(m), r);
}

ValidityReport Model::check_validity(const Reduced<double>& m) const {
  ValidityReport report;
  if (scaling_ == Scaling::searchlight_dmfp && !(m.sigma_a > 0))
    report.push_back({Severity::invalid, "no_absorption",
                      "sigma_a = 0: the diffuse mean free path is infinite, so the dmfp fit has no scale"});
  if (std::abs(m.eta - 1) > 0.01)
    report.push_back(
        {Severity::warning, "index_mismatch",
         "eta = " + format_number(m.eta) + ": the scaling fits were made for an index-matched boundary (eta = 1)"});
  for (auto& note : diffusion_validity(m, measured_limits(name())))
    if (note.code != "near_field") report.push_back(std::move(note));
  report.push_back({Severity::note, "singular_at_origin", "R(r) ~ 1/r as r -> 0: integrable, but R(0) is infinite"});
  return report;
}

}  // namespace bssrdf::normalized_diffusion
