#include "bssrdf/model_choice.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "bssrdf/error.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/validity.hpp"
#include "model_error_table.hpp"
#include "model_error_vs_exact.hpp"

namespace bssrdf {
namespace {

// The `--model auto` candidates (model registry order) with their column of the measured error
// table, if they have one (a reference model such as `exact` has its own band instead).
struct Candidate {
  const ModelEntry* entry;
  std::optional<std::size_t> column;
};
const std::vector<Candidate>& candidates() {
  static const std::vector<Candidate> list = [] {
    std::vector<Candidate> out;
    for (const auto& e : model_registry()) {
      if (!e.auto_candidate) continue;
      const auto it = std::find(detail::kCandidateNames.begin(), detail::kCandidateNames.end(), e.name);
      std::optional<std::size_t> column;
      if (it != detail::kCandidateNames.end())
        column = static_cast<std::size_t>(it - detail::kCandidateNames.begin());
      else if (!e.reference_accuracy)
        throw std::logic_error("model " + e.name + " is an auto candidate without measured errors or a reference band");
      out.push_back({&e, column});
    }
    return out;
  }();
  return list;
}

// The model's own verdict at m: its first "invalid" validity note, empty when it has none.
std::string invalid_note(const ModelEntry& entry, const Reduced<double>& m) {
  for (const auto& note : entry.make()->validity(m))
    if (note.severity == Severity::invalid) return note.code + ": " + note.message;
  return "";
}

ModelErrorEstimate estimate_for(const ModelEntry& entry, const Reduced<double>& m, const char* source) {
  ModelErrorEstimate est;
  est.model = entry.name;
  est.cost_ns = entry.cost_ns;
  est.source = source;
  if (entry.reference_accuracy) {
    const auto band = entry.reference_accuracy->at(m);
    est.total_error = band.total;
    est.profile_error = band.profile;
  }
  est.invalid = invalid_note(entry, m);
  return est;
}

void sort_by_cost(std::vector<ModelErrorEstimate>& v) {
  std::stable_sort(v.begin(), v.end(), [](const auto& x, const auto& y) { return x.cost_ns < y.cost_ns; });
}

// The measured grid values bracketing v: {lower, upper}, equal on a grid value; nullopt outside.
std::optional<std::pair<double, double>> bracket(std::vector<double> grid, double v) {
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  for (double x : grid)  // a measured value computed by another route (alpha' from sigma_a, sigma_s, g) is that value
    if (std::abs(v - x) <= 1e-9 * std::max(1.0, std::abs(x))) v = x;
  if (v < grid.front() || v > grid.back()) return std::nullopt;
  const auto hi = std::lower_bound(grid.begin(), grid.end(), v);
  return std::pair{*hi == v ? v : *(hi - 1), *hi};
}

std::vector<double> axis(double detail::MeasuredCase::*field) {
  std::vector<double> v;
  for (const auto& c : detail::kMeasuredCases) v.push_back(c.*field);
  return v;
}

std::string exact_domain_text() {
  const ExactTable& t = bundled_exact_table();
  const auto range = [](const std::vector<double>& axis) {
    return format_number(axis.front()) + " to " + format_number(axis.back());
  };
  return "alpha' 0 to " + format_number(t.albedo_prime.back()) + ", g " + range(t.g) + ", eta " + range(t.eta);
}

}  // namespace

std::optional<std::vector<ModelErrorEstimate>> tabulated_model_errors(const Reduced<double>& m) {
  const auto a = bracket(axis(&detail::MeasuredCase::albedo_prime), std::min(m.albedo_prime, 0.999));
  const auto e = bracket(axis(&detail::MeasuredCase::eta), m.eta);
  const auto g = bracket(axis(&detail::MeasuredCase::g), m.g);
  if (!a || !e || !g) return std::nullopt;
  const auto in = [](double v, std::pair<double, double> r) { return v == r.first || v == r.second; };
  // Every corner around the coefficients must have been measured, or there is no estimate.
  const auto corners = [](std::pair<double, double> r) { return r.first == r.second ? 1u : 2u; };
  std::size_t matched = 0;
  for (const auto& c : detail::kMeasuredCases) matched += in(c.albedo_prime, *a) && in(c.eta, *e) && in(c.g, *g);
  if (matched != corners(*a) * corners(*e) * corners(*g)) return std::nullopt;
  std::vector<ModelErrorEstimate> out;
  for (const auto& [entry, k] : candidates()) {
    ModelErrorEstimate est = estimate_for(*entry, m, "table");
    if (k)
      for (const auto& c : detail::kMeasuredCases)
        if (in(c.albedo_prime, *a) && in(c.eta, *e) && in(c.g, *g)) {
          est.total_error = std::max(est.total_error, c.error[*k].total);
          est.profile_error = std::max(est.profile_error, c.error[*k].profile);
        }
    out.push_back(est);
  }
  sort_by_cost(out);
  return out;
}

namespace {

bool inside_exact_domain(const Reduced<double>& m) {
  return exact_domain(bundled_exact_table(), m.albedo_prime, m.g, m.eta).empty();
}

// One candidate against the exact bins at m; a reference (exact) carries its own band instead.
ModelErrorEstimate measured_vs_exact(const ModelEntry& entry, const Reduced<double>& m,
                                     const std::function<const detail::ExactBins&()>& bins) {
  ModelErrorEstimate est = estimate_for(entry, m, "exact");
  if (!entry.reference_accuracy) {  // measured even where invalid (shown, never chosen)
    const auto error = detail::error_vs_exact(*entry.make(), m, bins());
    est.total_error = error.total;
    est.profile_error = error.profile();
    est.near_error = error.near;
    est.far_error = error.far;
  }
  return est;
}

}  // namespace

std::optional<std::vector<ModelErrorEstimate>> model_errors_vs_exact(const Reduced<double>& m) {
  if (!inside_exact_domain(m)) return std::nullopt;
  const auto bins = detail::exact_bins(ExactProfile(bundled_exact_table(), m.albedo_prime, m.g, m.eta));
  std::vector<ModelErrorEstimate> out;
  for (const auto& c : candidates())
    out.push_back(measured_vs_exact(
        *c.entry, m, [&]() -> const auto& { return bins; }));
  sort_by_cost(out);
  return out;
}

std::optional<std::vector<ModelErrorEstimate>> estimate_model_errors(const Reduced<double>& m) {
  if (auto live = model_errors_vs_exact(m)) return live;
  return tabulated_model_errors(m);
}

std::optional<ModelErrorEstimate> estimate_model_error(const std::string& model, const Reduced<double>& m) {
  const auto c = std::find_if(candidates().begin(), candidates().end(),
                              [&](const Candidate& candidate) { return candidate.entry->name == model; });
  if (c == candidates().end()) return std::nullopt;
  if (inside_exact_domain(m)) {
    std::optional<detail::ExactBins> bins;  // built only for a model measured against it
    return measured_vs_exact(*c->entry, m, [&]() -> const detail::ExactBins& {
      if (!bins) bins = detail::exact_bins(ExactProfile(bundled_exact_table(), m.albedo_prime, m.g, m.eta));
      return *bins;
    });
  }
  if (const auto table = tabulated_model_errors(m))
    for (const auto& e : *table)
      if (e.model == model) return e;
  return std::nullopt;
}

std::vector<MeasuredModel> measured_models() {
  std::vector<MeasuredModel> out;
  for (const auto& [entry, k] : candidates()) {
    if (!k) continue;  // a reference model: no column
    MeasuredModel m{entry->name, entry->cost_ns, {}, {}};
    for (const auto& c : detail::kMeasuredCases) {
      m.total_error.push_back(c.error[*k].total);
      m.profile_error.push_back(c.error[*k].profile);
    }
    out.push_back(std::move(m));
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.cost_ns < y.cost_ns; });
  return out;
}

std::vector<ModelErrorEstimate> estimate_model_errors(const Medium& medium) {
  medium.validate();
  std::vector<ModelErrorEstimate> worst;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    const auto estimates = estimate_model_errors(m);
    if (!estimates)
      throw InvalidInput(
          "channel " + medium.channel_names[c] + " (alpha', eta, g)",
          format_number(m.albedo_prime) + ", " + format_number(m.eta) + ", " + format_number(m.g),
          "the exact model's domain (" + exact_domain_text() +
              ") or, beyond it, alpha' >= 0.5, 1 <= eta <= 1.5 and 0 <= g <= 0.95 where the models were measured "
              "against Monte Carlo; for this channel run the Monte Carlo reference (bssrdf reference)");
    if (worst.empty()) {
      worst = *estimates;
      for (auto& e : worst)
        if (!e.invalid.empty()) e.invalid = "channel " + medium.channel_names[c] + ": " + e.invalid;
      continue;
    }
    for (std::size_t k = 0; k < estimates->size(); ++k) {  // same order: sorted by a fixed cost
      worst[k].total_error = std::max(worst[k].total_error, (*estimates)[k].total_error);
      worst[k].profile_error = std::max(worst[k].profile_error, (*estimates)[k].profile_error);
      worst[k].near_error = std::max(worst[k].near_error, (*estimates)[k].near_error);
      worst[k].far_error = std::max(worst[k].far_error, (*estimates)[k].far_error);
      if (worst[k].source != (*estimates)[k].source) worst[k].source = "exact+table";
      if (worst[k].invalid.empty() && !(*estimates)[k].invalid.empty())
        worst[k].invalid = "channel " + medium.channel_names[c] + ": " + (*estimates)[k].invalid;
    }
  }
  return worst;
}

std::optional<std::string> cheapest_within(const std::vector<ModelErrorEstimate>& estimates, double accuracy) {
  for (const auto& e : estimates)
    if (e.invalid.empty() && e.error() <= accuracy) return e.model;
  return std::nullopt;
}

ModelChoice choose_model(const Medium& medium, double accuracy) {
  if (!(accuracy > 0) || !std::isfinite(accuracy))
    throw InvalidInput("accuracy", format_number(accuracy), "> 0 (relative, e.g. 0.05)");
  ModelChoice choice{"", estimate_model_errors(medium)};
  if (const auto model = cheapest_within(choice.estimates, accuracy)) {
    choice.model = *model;
    return choice;
  }
  // The most accurate valid model (an invalid one is never offered).
  const auto best =
      *std::min_element(choice.estimates.begin(), choice.estimates.end(), [](const auto& x, const auto& y) {
        return std::pair{!x.invalid.empty(), x.error()} < std::pair{!y.invalid.empty(), y.error()};
      });
  if (!best.invalid.empty())
    throw InvalidInput("--model auto: every measured model marks itself invalid for this medium (" + best.model + ": " +
                       best.invalid + "); run the Monte Carlo reference instead (bssrdf reference)");
  std::string excluded;
  for (const auto& e : choice.estimates)
    if (!e.invalid.empty()) excluded += (excluded.empty() ? "" : ", ") + e.model;
  throw InvalidInput(
      "accuracy", format_number(accuracy),
      ">= " + format_number(std::ceil(best.error() * 1000) / 1000) +
          " for this medium: the most accurate valid model, " + best.model +
          ", was measured within that of the Monte Carlo reference here" +
          (excluded.empty() ? "" : " (" + excluded + " mark themselves invalid here and are never chosen)"));
}

DefaultModel default_model(const Medium& medium) {
  medium.validate();
  std::string outside;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    const auto report = exact_domain(bundled_exact_table(), m.albedo_prime, m.g, m.eta);
    if (!report.empty())
      outside += (outside.empty() ? "" : "; ") + ("channel " + medium.channel_names[c] + ": ") + report.front().message;
  }
  if (outside.empty()) return {"exact", ""};
  // Every other candidate's worst error over the channels, from the best source each channel has.
  struct Score {
    const ModelEntry* entry;
    bool invalid = false;
    double worst = 0;
    std::string source;
  };
  std::vector<Score> scores;
  for (const auto& c : candidates()) {
    if (c.entry->reference_accuracy) continue;  // exact: outside its domain in some channel
    Score s{c.entry, false, 0.0, ""};
    const auto model = c.entry->make();
    for (std::size_t ch = 0; ch < medium.channels() && !s.invalid; ++ch) {
      const auto m = medium.reduced(ch);
      s.invalid = worst(model->validity(m)) == Severity::invalid;
      double error = std::numeric_limits<double>::infinity();
      std::string source = "not measured here";
      if (const auto e = estimate_model_error(c.entry->name, m)) {
        error = e->error();
        source = e->source == "exact" ? "against the exact model" : "against Monte Carlo (validation table)";
      } else if (c.entry->limits) {
        error = documented_total_error(*c.entry->limits, m.albedo_prime, m.g);
        source = "total against adding-doubling (its bands)";
      }
      if (!(error <= s.worst)) {
        s.worst = error;
        s.source = source;
      }
    }
    scores.push_back(s);
  }
  // Valid first, then the smallest worst error; ties keep the registry's order.
  const auto best = std::min_element(scores.begin(), scores.end(), [](const Score& x, const Score& y) {
    return std::pair{x.invalid, x.worst} < std::pair{y.invalid, y.worst};
  });
  std::string why = outside + "; " + best->entry->name;
  if (best->invalid)
    why +=
        " is the first model here, though every model marks itself invalid for this medium: run the Monte Carlo "
        "reference (bssrdf reference)";
  else if (std::isfinite(best->worst))
    why += " is the most accurate model measured here (worst channel " +
           format_number(std::round(best->worst * 1000) / 10) + " %, " + best->source + ")";
  else
    why += " is the first valid model: no model's accuracy is measured here";
  return {best->entry->name, why};
}

DefaultModel default_model(const Reduced<double>& m) {
  return default_model(Medium::single_channel(m.sigma_a, m.sigma_s, m.g, m.eta));
}

DefaultModel default_model_over_albedos(const std::vector<double>& g, double eta_min, double eta_max) {
  const ExactTable& table = bundled_exact_table();
  const std::vector<double> gs = g.empty() ? std::vector<double>{0.0} : g;
  bool inside = true;
  for (double gc : gs)
    for (double eta : {eta_min, eta_max}) inside = inside && exact_domain(table, 0.5, gc, eta).empty();
  if (inside) return {"exact", ""};
  Medium judged;
  for (std::size_t c = 0; c < gs.size(); ++c) {
    judged.sigma_a.push_back(0.1);
    judged.sigma_s.push_back(0.9 / (1 - gs[c]));
    judged.g.push_back(gs[c]);
    judged.channel_names.push_back(gs.size() == 1 ? "all" : "c" + std::to_string(c));
  }
  judged.eta = eta_max;
  DefaultModel d = default_model(judged);
  d.reason = "judged at alpha' 0.9 (the fit finds the albedo): " + d.reason;
  return d;
}

}  // namespace bssrdf
