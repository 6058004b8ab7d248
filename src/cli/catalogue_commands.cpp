// bssrdf models / bssrdf materials list: what the tool knows.
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

Action register_materials(CLI::App& app) {
  struct Options {
    std::string db, source, format = "table";
  };
  auto options = std::make_shared<Options>();
  auto* sub = app.add_subcommand("materials", "The measured-media database");
  sub->require_subcommand(1);
  auto* list = sub->add_subcommand("list", "List materials: name, source, eta");
  list->add_option("--db", options->db, "Materials database directory or file [the bundled materials/]");
  list->add_option("--source", options->source, "Only materials from this source (e.g. jensen2001)");
  list->add_option("--format,-f", options->format, "table or json [table]")->check(CLI::IsMember({"table", "json"}));
  return [options, list] {
    if (!list->parsed()) return;
    const auto db = MaterialDatabase::load(options->db.empty() ? default_materials_dir() : std::filesystem::path(options->db));
    nlohmann::json out = nlohmann::json::array();
    for (const auto& m : db.all()) {
      if (!options->source.empty() && m.source != options->source) continue;
      if (options->format == "json") {
        out.push_back({{"name", m.name}, {"source", m.source}, {"eta", m.medium.eta}, {"channels", m.medium.channel_names}});
      } else {
        std::cout << m.name << std::string(m.name.size() < 24 ? 24 - m.name.size() : 1, ' ') << m.source
                  << "  eta " << m.medium.eta << '\n';
      }
    }
    if (options->format == "json") std::cout << out.dump(2) << '\n';
  };
}

}  // namespace bssrdf::cli
