#include "bssrdf/model_selection.hpp"

#include <algorithm>
#include <cmath>

#include "bssrdf/error.hpp"

namespace bssrdf {

void check_model_accuracy(double accuracy, const std::string& field) {
  if (!(accuracy > 0 && accuracy < 10))
    throw InvalidInput(field, format_number(accuracy), "0 < accuracy < 10 (relative error, e.g. 0.05)");
}

std::string describe_choice(const ModelChoice& choice, double accuracy) {
  const auto percent = [](double v) { return format_number(std::round(v * 1000) / 10) + " %"; };
  std::string rejected;
  for (const auto& e : choice.estimates) {
    if (e.model == choice.model) break;
    rejected +=
        (rejected.empty() ? "" : ", ") + e.model + " " + (e.invalid.empty() ? percent(e.error()) : "invalid here");
  }
  const auto& chosen = *std::find_if(choice.estimates.begin(), choice.estimates.end(),
                                     [&](const auto& e) { return e.model == choice.model; });
  return "auto: " + choice.model + ", the cheapest measured within " + short_number(accuracy * 100) +
         " % of Monte Carlo for this medium (worst channel: total " + percent(chosen.total_error) + ", profile L2 " +
         percent(chosen.profile_error) + ")" + (rejected.empty() ? "" : "; cheaper but worse: " + rejected);
}

SelectedModel select_model(const std::string& name, std::optional<double> accuracy, const Medium& medium,
                           const std::string& accuracy_field, const std::string& model_field) {
  if (name != "auto") {
    if (accuracy)
      throw InvalidInput(accuracy_field + ": only with " + model_field + " auto (it chooses the model to meet it)");
    if (!name.empty()) return {name, ""};
    const auto chosen = default_model(medium);
    return {chosen.name, chosen.reason.empty() ? "" : "default: " + chosen.reason};
  }
  const double a = accuracy.value_or(kDefaultModelAccuracy);
  check_model_accuracy(a, accuracy_field);
  const auto choice = choose_model(medium, a);
  return {choice.model, describe_choice(choice, a)};
}

std::string measured_domain(const ModelEntry& entry) {
  // The validity domain as measured: the lowest alpha' where the total is within 5 %.
  const auto within = [](const std::vector<AccuracyBand>& bands, double tolerance) {
    double lowest = 1;
    for (const auto& band : bands)
      if (band.worst_error <= tolerance)
        lowest = band.min_albedo_prime;
      else
        break;
    return lowest;
  };
  std::string domain = "total not measured against adding-doubling";
  if (const auto& limits = entry.limits) {
    const double iso = within(limits->isotropic_bands, 0.05), fwd = within(limits->forward_bands, 0.05);
    domain = "total within 5 % of adding-doubling for alpha' >= " + format_number(iso) +
             " (g = 0), >= " + format_number(fwd) + " (g = 0.9); eta 1-1.4";
    if (iso == 1 && fwd == 1) domain = "total not within 5 % of adding-doubling anywhere measured";
  }
  if (const auto& accuracy = entry.reference_accuracy) {  // the reference itself: its measured band
    const auto pc = [](double v) { return format_number(std::round(1000 * v) / 10) + " %"; };
    domain = "against fresh Monte Carlo: total within " + pc(accuracy->total) + ", r R(r) within " +
             pc(accuracy->profile) + " (relative L2 beyond the runs' noise) in its domain";
    for (const auto& r : accuracy->regions)
      domain += "; " + pc(r.total) + " and " + pc(r.profile) + " in " + r.name + " (" +
                format_number(r.albedo_prime_min) + " <= alpha' <= " + format_number(r.albedo_prime_max) + ", " +
                format_number(r.g_min) + " <= g <= " + format_number(r.g_max) + ", " + format_number(r.eta_min) +
                " <= eta <= " + format_number(r.eta_max) + ")";
  }
  return domain;
}

}  // namespace bssrdf
