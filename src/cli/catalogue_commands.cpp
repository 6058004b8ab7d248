// bssrdf models: the profile models the tool knows (materials: materials_command.cpp).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {

Action register_models(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto* sub = app.add_subcommand("models", "List the profile models: what each includes and where it holds");
  sub->add_flag("--json", *json, "Print JSON");
  return [json] {
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
