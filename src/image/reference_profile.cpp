#include "bssrdf/image/reference_profile.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "bssrdf/error.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/montecarlo.hpp"

namespace bssrdf {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The Monte Carlo log bins for these annuli: first [0, r_min), then geometric to r_max.
MonteCarloOptions bins_for(const std::vector<double>& edges) {
  MonteCarloOptions mc;
  mc.spacing = BinSpacing::log;
  mc.r_min = edges[1];
  mc.r_max = edges[edges.size() - 2];
  mc.bins = edges.size() - 2;
  return mc;
}

}  // namespace

double profile_extent(const Reduced<double>& m) { return std::max(30 * m.ell, m.sigma_tr > 0 ? 15 / m.sigma_tr : 0.0); }

std::vector<double> reference_annuli(const Medium& medium, std::size_t bins_per_decade) {
  const double r_min = 1e-3 * transport_mfp_range(medium).min;
  double r_max = 0;
  for (std::size_t c = 0; c < medium.channels(); ++c) r_max = std::max(r_max, profile_extent(medium.reduced(c)));
  const auto geometric =
      static_cast<std::size_t>(std::ceil(std::log10(r_max / r_min) * static_cast<double>(bins_per_decade)));
  std::vector<double> edges{0.0};
  for (std::size_t j = 0; j <= geometric; ++j)
    edges.push_back(r_min * std::pow(r_max / r_min, static_cast<double>(j) / static_cast<double>(geometric)));
  edges.push_back(2 * r_max);
  return edges;
}

std::vector<AnnularProfile> monte_carlo_annuli(const Medium& medium, const std::vector<double>& annuli,
                                               const MonteCarloReferenceOptions& options) {
  MonteCarloOptions mc = bins_for(annuli);
  mc.photons = options.photons;
  mc.seed = options.seed;
  mc.threads = options.threads;
  const MonteCarloResult run = run_monte_carlo(LayerStack::half_space(medium), mc);
  // The tracer's geometric edges are its own; use them so the annuli are exactly its bins.
  std::vector<double> edges{0.0};
  for (double r : run.bin_outer) edges.push_back(r);
  edges.push_back(2 * edges.back());
  std::vector<AnnularProfile> out;
  for (const auto& raw : run.channels) {
    const ChannelResult ch = raw.per_entered_flux();
    AnnularProfile p{edges, {}, {}};
    for (std::size_t i = 0; i < ch.reflectance.size(); ++i) {
      const double area = std::numbers::pi * (edges[i + 1] * edges[i + 1] - edges[i] * edges[i]);
      p.energy.push_back(ch.reflectance[i] * area);
      p.energy_stderr.push_back(ch.reflectance_stderr[i] * area);
    }
    p.energy.push_back(ch.reflectance_beyond);
    p.energy_stderr.push_back(0.0);  // tiny (30 ell); its error is in the total's
    out.push_back(std::move(p));
  }
  return out;
}

ReferenceProfiles MonteCarloReference::profiles(const Medium& medium) const {
  const auto start = std::chrono::steady_clock::now();
  ReferenceProfiles out;
  out.channels = monte_carlo_annuli(medium, reference_annuli(medium), options_);
  out.sources.assign(medium.channels(), ReferenceSource{"montecarlo", 0, 0, {}});
  out.description = "Monte Carlo, " + std::to_string(options_.photons) + " photons per channel, seed " +
                    std::to_string(options_.seed);
  out.seconds = seconds_since(start);
  return out;
}

ReferenceProfiles ModelReference::profiles(const Medium& medium) const {
  const auto start = std::chrono::steady_clock::now();
  const auto edges = reference_annuli(medium);
  const ModelEntry* entry = registry_band_ ? find_model_entry(model_->name()) : nullptr;
  ReferenceProfiles out;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    double total_band = 0, profile_band = 0;  // exact's measured accuracy; none for a model taken as the truth
    if (entry && entry->reference_accuracy) {
      const auto band = entry->reference_accuracy->at(m);
      total_band = band.total;
      profile_band = band.profile;
    }
    out.channels.push_back(annuli_of(
        edges, [&](double r) { return model_->reflectance(m, r); }, model_->total_reflectance(m)));
    const Model* model = model_.get();
    out.sources.push_back(
        {model_->name(), total_band, profile_band, [model, m](double r) { return model->reflectance(m, r); }});
  }
  out.description = "model " + model_->name();
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace bssrdf
