#include "bssrdf/spectral/colour_reference.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/spectral/colour_medium.hpp"

namespace bssrdf::spectral {
namespace {

// sum_i w_i X_i, and the standard error of independent estimates.
Estimate combine(const std::vector<const Estimate*>& x, const std::vector<double>& w) {
  Estimate out;
  double variance = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    out.value += w[i] * x[i]->value;
    variance += w[i] * w[i] * x[i]->standard_error * x[i]->standard_error;
  }
  out.standard_error = std::sqrt(variance);
  return out;
}

}  // namespace

std::vector<double> combine_bins(const std::vector<const std::vector<double>*>& v, const std::vector<double>& w,
                                 bool errors) {
  std::vector<double> out(v.front()->size(), 0.0);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] += errors ? w[i] * w[i] * (*v[i])[k] * (*v[i])[k] : w[i] * (*v[i])[k];
  if (errors)
    for (double& e : out) e = std::sqrt(e);
  return out;
}

MonteCarloResult colour_reference(const MonteCarloResult& result, const std::vector<double>& wavelength_nm,
                                  const ColourSettings& settings) {
  if (result.channels.size() != wavelength_nm.size() || wavelength_nm.empty())
    throw InvalidInput("wavelengths: " + std::to_string(wavelength_nm.size()) + " given for " +
                       std::to_string(result.channels.size()) + " channels");
  const ColourIntegrator colour(wavelength_nm, settings);
  MonteCarloResult out = result;
  out.channels.clear();
  const auto& s = result.channels;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> w;
    for (const auto& weight : colour.rgb_weights()) w.push_back(weight[c]);
    const auto estimates = [&](Estimate ChannelResult::*field) {
      std::vector<const Estimate*> x;
      for (const auto& ch : s) x.push_back(&(ch.*field));
      return combine(x, w);
    };
    const auto bins = [&](std::vector<double> ChannelResult::*field, bool errors) {
      std::vector<const std::vector<double>*> v;
      for (const auto& ch : s) v.push_back(&(ch.*field));
      return combine_bins(v, w, errors);
    };
    const auto scalar = [&](double ChannelResult::*field) {
      double sum = 0;
      for (std::size_t i = 0; i < s.size(); ++i) sum += w[i] * (s[i].*field);
      return sum;
    };
    ChannelResult ch;
    ch.name = std::string(1, "RGB"[c]);
    // One interface index for every wavelength: the same R_sp in each, and the weights of a white sum to 1.
    ch.specular_reflectance = scalar(&ChannelResult::specular_reflectance);
    ch.diffuse_reflectance = estimates(&ChannelResult::diffuse_reflectance);
    ch.single_scattering_reflectance = estimates(&ChannelResult::single_scattering_reflectance);
    ch.unscattered_reflectance = estimates(&ChannelResult::unscattered_reflectance);
    ch.total_transmittance = estimates(&ChannelResult::total_transmittance);
    ch.unscattered_transmittance = estimates(&ChannelResult::unscattered_transmittance);
    ch.absorbed = estimates(&ChannelResult::absorbed);
    ch.lost = scalar(&ChannelResult::lost);
    ch.reflectance = bins(&ChannelResult::reflectance, false);
    ch.reflectance_stderr = bins(&ChannelResult::reflectance_stderr, true);
    ch.reflectance_beyond = scalar(&ChannelResult::reflectance_beyond);
    if (!s.front().transmittance.empty()) {
      ch.transmittance = bins(&ChannelResult::transmittance, false);
      ch.transmittance_stderr = bins(&ChannelResult::transmittance_stderr, true);
      ch.transmittance_beyond = scalar(&ChannelResult::transmittance_beyond);
    }
    if (!s.front().absorbed_by_depth.empty()) {
      ch.absorbed_by_depth = bins(&ChannelResult::absorbed_by_depth, false);
      ch.absorbed_by_depth_stderr = bins(&ChannelResult::absorbed_by_depth_stderr, true);
    }
    for (const auto& x : s) ch.interactions += x.interactions;
    out.channels.push_back(std::move(ch));
  }
  return out;
}

std::string colour_reference_json(const MonteCarloResult& result, LengthUnit unit, const ColourNote& note) {
  auto doc = nlohmann::ordered_json::parse(to_json(result, unit));
  doc["colour"] = {{"observer", note.observer},
                   {"illuminant", note.illuminant},
                   {"space", note.space},
                   {"wavelength_nm", note.wavelength_nm}};
  return doc.dump(2) + "\n";
}

std::string colour_reference_csv(const MonteCarloResult& result, LengthUnit unit, const ColourNote& note) {
  return "# colour: " + describe(note) + "; each bin sum_lambda w_c(lambda) R(r, lambda), standard errors combined\n" +
         to_csv(result, unit);
}

std::string colour_reference_report(const MonteCarloResult& result, LengthUnit unit, const ColourNote& note) {
  return "Colour: " + describe(note) + "; channels R, G, B integrated per radial bin (stack coefficients per " +
         "wavelength)\n\n" + result.report(unit);
}

}  // namespace bssrdf::spectral
