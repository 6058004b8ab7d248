#include "bssrdf/model_choice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bssrdf/error.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/validity.hpp"
#include "model_error_table.hpp"

namespace bssrdf {
namespace {

// The `--model auto` candidates (model registry order) with their column of the measured error table.
struct Candidate {
  const ModelEntry* entry;
  std::size_t column;
};
const std::vector<Candidate>& candidates() {
  static const std::vector<Candidate> list = [] {
    std::vector<Candidate> out;
    for (const auto& e : model_registry()) {
      if (!e.auto_candidate) continue;
      const auto it = std::find(detail::kCandidateNames.begin(), detail::kCandidateNames.end(), e.name);
      if (it == detail::kCandidateNames.end())
        throw std::logic_error("model " + e.name + " is an auto candidate without a column in the measured error table");
      out.push_back({&e, static_cast<std::size_t>(it - detail::kCandidateNames.begin())});
    }
    return out;
  }();
  return list;
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

}  // namespace

std::optional<std::vector<ModelErrorEstimate>> estimate_model_errors(const Reduced<double>& m) {
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
    ModelErrorEstimate est;
    est.model = entry->name;
    est.cost_ns = entry->cost_ns;
    for (const auto& c : detail::kMeasuredCases)
      if (in(c.albedo_prime, *a) && in(c.eta, *e) && in(c.g, *g)) {
        est.total_error = std::max(est.total_error, c.error[k].total);
        est.profile_error = std::max(est.profile_error, c.error[k].profile);
      }
    for (const auto& note : entry->make()->validity(m))
      if (note.severity == Severity::invalid) {
        est.invalid = note.code + ": " + note.message;
        break;
      }
    out.push_back(est);
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.cost_ns < y.cost_ns; });
  return out;
}

std::vector<MeasuredModel> measured_models() {
  std::vector<MeasuredModel> out;
  for (const auto& [entry, k] : candidates()) {
    MeasuredModel m{entry->name, entry->cost_ns, {}, {}};
    for (const auto& c : detail::kMeasuredCases) {
      m.total_error.push_back(c.error[k].total);
      m.profile_error.push_back(c.error[k].profile);
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
      throw InvalidInput("channel " + medium.channel_names[c] + " (alpha', eta, g)",
                         format_number(m.albedo_prime) + ", " + format_number(m.eta) + ", " + format_number(m.g),
                         "alpha' >= 0.5, 1 <= eta <= 1.5 and 0 <= g <= 0.95, where the models were measured against Monte Carlo; "
                         "outside it choose the model yourself (bssrdf models)");
    if (worst.empty()) {
      worst = *estimates;
      for (auto& e : worst)
        if (!e.invalid.empty()) e.invalid = "channel " + medium.channel_names[c] + ": " + e.invalid;
      continue;
    }
    for (std::size_t k = 0; k < estimates->size(); ++k) {  // same order: sorted by a fixed cost
      worst[k].total_error = std::max(worst[k].total_error, (*estimates)[k].total_error);
      worst[k].profile_error = std::max(worst[k].profile_error, (*estimates)[k].profile_error);
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
  if (!(accuracy > 0) || !std::isfinite(accuracy)) throw InvalidInput("accuracy", format_number(accuracy), "> 0 (relative, e.g. 0.05)");
  ModelChoice choice{"", estimate_model_errors(medium)};
  if (const auto model = cheapest_within(choice.estimates, accuracy)) {
    choice.model = *model;
    return choice;
  }
  // The most accurate valid model (an invalid one is never offered).
  const auto best = *std::min_element(choice.estimates.begin(), choice.estimates.end(), [](const auto& x, const auto& y) {
    return std::pair{!x.invalid.empty(), x.error()} < std::pair{!y.invalid.empty(), y.error()};
  });
  if (!best.invalid.empty())
    throw InvalidInput("--model auto: every measured model marks itself invalid for this medium (" + best.model + ": " +
                       best.invalid + "); choose the model yourself (bssrdf models)");
  std::string excluded;
  for (const auto& e : choice.estimates)
    if (!e.invalid.empty()) excluded += (excluded.empty() ? "" : ", ") + e.model;
  throw InvalidInput("accuracy", format_number(accuracy),
                     ">= " + format_number(std::ceil(best.error() * 1000) / 1000) + " for this medium: the most accurate valid model, " +
                         best.model + ", was measured within that of the Monte Carlo reference here" +
                         (excluded.empty() ? "" : " (" + excluded + " mark themselves invalid here and are never chosen)"));
}

}  // namespace bssrdf
