// bssrdf models: the profile models the tool knows (materials: materials_command.cpp).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {

namespace {

// For a given medium: every model's measured error there and its cost, and the cheapest that meets
// --accuracy (what --model auto picks).
void print_estimates(const MediumOptions& options, const std::string& accuracy_text, bool json) {
  const auto resolved = options.resolve();
  const double accuracy = accuracy_text.empty() ? 0.1 : parse_number(accuracy_text, "--accuracy");
  if (!(accuracy > 0 && accuracy < 10)) throw InvalidInput("--accuracy", format_number(accuracy), "0 < accuracy < 10");
  std::string chosen;
  std::vector<ModelErrorEstimate> estimates;
  try {
    const auto choice = choose_model(resolved.medium, accuracy);
    chosen = choice.model;
    estimates = choice.estimates;
  } catch (const InvalidInput&) {
    // Outside the measured ranges the message says why; with no model accurate enough, list them all.
    for (std::size_t c = 0; c < resolved.medium.channels(); ++c)
      if (!estimate_model_errors(resolved.medium.reduced(c))) throw;
    estimates = choose_model(resolved.medium, 1e9).estimates;
  }
  if (json) {
    nlohmann::json doc = {{"accuracy", accuracy}, {"chosen", chosen.empty() ? nlohmann::json(nullptr) : nlohmann::json(chosen)}};
    for (const auto& e : estimates)
      doc["models"].push_back({{"name", e.model}, {"cost_ns", e.cost_ns}, {"total_error", e.total_error}, {"profile_l2_error", e.profile_error}});
    std::cout << doc.dump(2) << '\n';
    return;
  }
  std::cout << "measured against Monte Carlo at the cases bracketing this medium (worst channel), cheapest first:\n"
            << "  model               ns/eval   total   R(r) L2\n";
  for (const auto& e : estimates) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-18s %8.0f  %5.1f %%  %6.1f %%", e.model.c_str(), e.cost_ns, 100 * e.total_error, 100 * e.profile_error);
    std::cout << line << (e.model == chosen ? "   <- cheapest within " + format_number(100 * accuracy) + " %" : "") << '\n';
  }
  if (chosen.empty()) std::cout << "no model is measured within " << format_number(100 * accuracy) << " % here\n";
}

}  // namespace

Action register_models(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto medium = std::make_shared<MediumOptions>();
  auto accuracy = std::make_shared<std::string>();
  auto* sub = app.add_subcommand("models", "List the profile models: what each includes and where it holds; with a medium, "
                                           "each one's measured error there and the cheapest within --accuracy");
  sub->add_flag("--json", *json, "Print JSON");
  medium->add_to(*sub);
  sub->add_option("--accuracy", *accuracy, "With a medium: relative error allowed (total and R(r) L2) [0.1]");
  return [json, medium, accuracy] {
    if (!medium->material.empty() || !medium->sigma_a.empty()) return print_estimates(*medium, *accuracy, *json);
    if (!accuracy->empty()) throw InvalidInput("--accuracy: give a medium (--material or --sigma-a/--sigma-s) too");
    nlohmann::json list = nlohmann::json::array();
    for (const auto& name : model_names()) {
      const auto model = make_model(name);
      const auto& limits = measured_limits(name);
      // The validity domain as measured: the lowest alpha' where the total is within 5 %.
      const auto within = [&](const std::vector<AccuracyBand>& bands, double tolerance) {
        double lowest = 1;
        for (const auto& band : bands)
          if (band.worst_error <= tolerance) lowest = band.min_albedo_prime;
          else break;
        return lowest;
      };
      const double iso = within(limits.isotropic_bands, 0.05), fwd = within(limits.forward_bands, 0.05);
      std::string domain = "total within 5 % of adding-doubling for alpha' >= " + format_number(iso) +
                           " (g = 0), >= " + format_number(fwd) + " (g = 0.9); eta 1-1.4";
      if (iso == 1 && fwd == 1) domain = "total not within 5 % of adding-doubling anywhere measured";
      if (*json) {
        list.push_back({{"name", name},
                        {"description", model->description()},
                        {"includes_single_scattering", model->includes_single_scattering()},
                        {"validity_domain", domain}});
      } else {
        std::cout << name << "\n    " << model->description() << "\n    single scattering: "
                  << (model->includes_single_scattering() ? "included" : "omitted (add with --single-scattering)")
                  << "\n    " << domain << "\n";
      }
    }
    if (*json) std::cout << list.dump(2) << '\n';
  };
}

}  // namespace bssrdf::cli
