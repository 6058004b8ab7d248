#include "bssrdf/advise/auto_reference.hpp"

#include <chrono>
#include <cmath>

#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/transport_total.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {
namespace {

// The analytic model with the smallest measured profile error at m (the Monte Carlo table), if any.
std::optional<ModelErrorEstimate> best_tabulated_shape(const Reduced<double>& m) {
  const auto table = tabulated_model_errors(m);
  if (!table) return std::nullopt;
  std::optional<ModelErrorEstimate> best;
  for (const auto& e : *table)
    if (!model_entry(e.model).reference_accuracy && (!best || e.profile_error < best->profile_error)) best = e;
  return best;
}

bool inside_exact(const Reduced<double>& m) { return worst(make_model("exact")->validity(m)) != Severity::invalid; }

}  // namespace

std::string auto_reference_source(const Reduced<double>& m) {
  if (inside_exact(m)) return "exact";
  if (m.albedo_prime > 0.5)
    if (const auto shape = best_tabulated_shape(m)) return shape->model;
  return "montecarlo";
}

AutoReference::AutoReference(MonteCarloReferenceOptions monte_carlo) : monte_carlo_(monte_carlo) {
  models_["exact"] = make_model("exact");
  for (const auto& measured : measured_models()) models_[measured.model] = make_model(measured.model);
}

ReferenceProfiles AutoReference::profiles(const Medium& medium) const {
  const auto start = std::chrono::steady_clock::now();
  ReferenceProfiles out;
  out.channels.resize(medium.channels());
  out.sources.resize(medium.channels());
  // The Monte Carlo channels first, alone: their bins fix the annuli every channel shares.
  Medium traced{{}, {}, {}, {}, medium.eta, {}};
  std::vector<std::size_t> traced_index;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    out.sources[c].name = auto_reference_source(medium.reduced(c));
    if (out.sources[c].name != "montecarlo") continue;
    traced.channel_names.push_back(medium.channel_names[c]);
    traced.sigma_a.push_back(medium.sigma_a[c]);
    traced.sigma_s.push_back(medium.sigma_s[c]);
    traced.g.push_back(medium.g[c]);
    traced_index.push_back(c);
  }
  std::vector<double> edges = reference_annuli(medium);
  if (!traced_index.empty()) {
    auto traced_profiles = monte_carlo_annuli(traced, edges, monte_carlo_);
    edges = traced_profiles.front().edges;
    for (std::size_t k = 0; k < traced_index.size(); ++k) out.channels[traced_index[k]] = std::move(traced_profiles[k]);
  }
  std::string description;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    ReferenceSource& source = out.sources[c];
    const auto m = medium.reduced(c);
    std::string label = source.name;
    if (source.name == "exact") {
      const Model* exact = models_.at("exact").get();
      const auto band = model_entry("exact").reference_accuracy->at(m);
      source.total_band = band.total;
      source.profile_band = band.profile;
      source.reflectance = [exact, m](double r) { return exact->reflectance(m, r); };
      out.channels[c] = annuli_of(edges, source.reflectance, exact->total_reflectance(m));
    } else if (source.name != "montecarlo") {
      const Model* shape = models_.at(source.name).get();
      // Outside the exact table: adding-doubling, or 1 exactly without absorption (Spectralon).
      const TransportTotal transport = transport_total(m);
      const double total = transport.value, scale = total / shape->total_reflectance(m);
      source.total_band = kAddingDoublingTotalBand;
      source.profile_band = best_tabulated_shape(m)->profile_error;
      source.reflectance = [shape, m, scale](double r) { return scale * shape->reflectance(m, r); };
      out.channels[c] = annuli_of(edges, source.reflectance, total);
      label = source.name + " shape, " +
              (transport.source == std::string("adding-doubling") ? "adding-doubling total"
                                                                  : "total 1 (" + std::string(transport.source) + ")");
    } else {
      label =
          "Monte Carlo " + std::to_string(monte_carlo_.photons) + " photons, seed " + std::to_string(monte_carlo_.seed);
    }
    description += (c ? "; " : "") + medium.channel_names[c] + ": " + label;
  }
  out.description = "auto (" + description + ")";
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace bssrdf
