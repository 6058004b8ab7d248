#include "bssrdf/model_choice.hpp"

#include <algorithm>
#include <cmath>

#include "bssrdf/error.hpp"
#include "model_error_table.hpp"

namespace bssrdf {
namespace {

// One R(r) evaluation, ns: bench_models medians on the 2-core development machine (alpha' 0.9,
// g 0, eta 1.3, 64 radii over 0.01-20 ell). Only their order matters to the choice.
double cost_ns(std::string_view model) {
  if (model == "dipole") return 19;
  if (model == "better-dipole") return 26;
  if (model == "burley" || model == "burley-diffuse" || model == "burley-dmfp") return 28;
  if (model == "dipole+ss") return 530;
  if (model == "better-dipole+ss") return 540;
  if (model == "pbd") return 1195;
  if (model == "quantized") return 8285;
  return 9069;  // quantized+ss
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
  for (std::size_t k = 0; k < detail::kCandidateModels; ++k) {
    ModelErrorEstimate est{std::string(detail::kCandidateNames[k]), cost_ns(detail::kCandidateNames[k])};
    for (const auto& c : detail::kMeasuredCases)
      if (in(c.albedo_prime, *a) && in(c.eta, *e) && in(c.g, *g)) {
        est.total_error = std::max(est.total_error, c.error[k].total);
        est.profile_error = std::max(est.profile_error, c.error[k].profile);
      }
    out.push_back(est);
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.cost_ns < y.cost_ns; });
  return out;
}

std::vector<MeasuredModel> measured_models() {
  std::vector<MeasuredModel> out;
  for (std::size_t k = 0; k < detail::kCandidateModels; ++k) {
    MeasuredModel m{std::string(detail::kCandidateNames[k]), cost_ns(detail::kCandidateNames[k]), {}, {}};
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
      continue;
    }
    for (std::size_t k = 0; k < estimates->size(); ++k) {  // same order: sorted by a fixed cost
      worst[k].total_error = std::max(worst[k].total_error, (*estimates)[k].total_error);
      worst[k].profile_error = std::max(worst[k].profile_error, (*estimates)[k].profile_error);
    }
  }
  return worst;
}

std::optional<std::string> cheapest_within(const std::vector<ModelErrorEstimate>& estimates, double accuracy) {
  for (const auto& e : estimates)
    if (e.error() <= accuracy) return e.model;
  return std::nullopt;
}

ModelChoice choose_model(const Medium& medium, double accuracy) {
  if (!(accuracy > 0) || !std::isfinite(accuracy)) throw InvalidInput("accuracy", format_number(accuracy), "> 0 (relative, e.g. 0.05)");
  ModelChoice choice{"", estimate_model_errors(medium)};
  if (const auto model = cheapest_within(choice.estimates, accuracy)) {
    choice.model = *model;
    return choice;
  }
  const auto best = *std::min_element(choice.estimates.begin(), choice.estimates.end(),
                                      [](const auto& x, const auto& y) { return x.error() < y.error(); });
  throw InvalidInput("accuracy", format_number(accuracy),
                     ">= " + format_number(std::ceil(best.error() * 1000) / 1000) + " for this medium: the most accurate model, " + best.model +
                         ", was measured within that of the Monte Carlo reference here");
}

}  // namespace bssrdf
