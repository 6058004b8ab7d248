// Albedo inversion: alpha' from the total by exact root finding on the model's total, then the
// reduced extinction from the distance in its convention.
#include <chrono>
#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "fit_common.hpp"

namespace bssrdf {

DistanceConvention parse_distance_convention(const std::string& text) {
  if (text == "mfp") return DistanceConvention::mfp;
  if (text == "transport-mfp" || text == "transport_mfp") return DistanceConvention::transport_mfp;
  if (text == "dmfp") return DistanceConvention::dmfp;
  throw InvalidInput("distance convention", "'" + text + "'",
                     "mfp (1/sigma_t), transport-mfp (1/sigma_t') or dmfp (1/sigma_tr)");
}

std::string_view to_string(DistanceConvention convention) {
  switch (convention) {
    case DistanceConvention::mfp:
      return "mfp";
    case DistanceConvention::transport_mfp:
      return "transport-mfp";
    case DistanceConvention::dmfp:
      return "dmfp";
  }
  return "mfp";
}

AlbedoInversion invert_albedo(const std::string& model_name, double total, double distance,
                              DistanceConvention convention, double eta, double g) {
  if (!(distance > 0) || !std::isfinite(distance)) throw InvalidInput("distance", format_number(distance), "> 0");
  thread_local std::string cached_name;
  thread_local std::unique_ptr<Model> model;
  if (!model || cached_name != model_name) {
    model = make_model(model_name);
    cached_name = model_name;
  }
  const double a = model->albedo_prime_from_total(total, eta, g);
  double sigma_t_prime = 0;
  switch (convention) {
    case DistanceConvention::transport_mfp:
      sigma_t_prime = 1 / distance;
      break;
    case DistanceConvention::mfp:  // sigma_t = sigma_a + sigma_s'/(1 - g) = sigma_t' (1 - a + a/(1 - g))
      sigma_t_prime = 1 / (distance * (1 - a + a / (1 - g)));
      break;
    case DistanceConvention::dmfp:  // sigma_tr = sigma_t' sqrt(3 (1 - alpha'))
      if (!(a < 1))
        throw InvalidInput("albedo", format_number(total),
                           "below the model's maximum: at alpha' = 1 the diffuse mean free path is infinite");
      sigma_t_prime = 1 / (distance * std::sqrt(3 * (1 - a)));
      break;
  }
  return {(1 - a) * sigma_t_prime, a * sigma_t_prime, a};
}

FitReport fit_albedo(const std::vector<ChannelInput>& channels, DistanceConvention convention, LengthUnit unit,
                     const std::string& given_model, double eta) {
  const auto start = std::chrono::steady_clock::now();
  FitReport report;
  report.kind = "albedo";
  std::string model = given_model;
  if (model.empty()) {
    std::vector<double> g;
    for (const auto& c : channels) g.push_back(c.g);
    const auto chosen = default_model_over_albedos(g, eta, eta);
    model = chosen.name;
    report.model_choice = chosen.reason;
  }
  report.model = model;
  report.data_source = "surface albedo and " + std::string(to_string(convention)) + " per channel";
  report.termination = "exact";
  report.converged = true;
  report.eta = eta;
  for (const auto& c : channels) report.g.push_back(c.g);
  report.length_unit = symbol(unit);
  const std::string per_unit = "1/" + std::string(symbol(unit));
  for (const auto& c : channels) {
    AlbedoInversion x;
    try {
      x = invert_albedo(model, c.value, c.distance, convention, eta, c.g);
    } catch (const InvalidInput& e) {
      throw InvalidInput("channel " + c.name + ": " + e.what());
    }
    report.parameters.push_back({"sigma_a", c.name, x.sigma_a, 0, per_unit});
    report.parameters.push_back({"sigma_s_prime", c.name, x.sigma_s_prime, 0, per_unit});
    report.parameters.push_back({"albedo_prime", c.name, x.albedo_prime, 0, ""});
    const auto m = make_model(model);
    const double back = m->total_reflectance(reduce(x.sigma_a, x.sigma_s_prime / (1 - c.g), c.g, eta));
    report.residuals.push_back({c.name, 0, c.value, back, 0});
  }
  report.warnings.push_back(
      "two numbers per channel determine sigma_a and sigma_s' exactly: no uncertainty can be "
      "estimated from them (the errors of the model itself are in 'bssrdf models')");
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace bssrdf
