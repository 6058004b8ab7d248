// bssrdf models: the profile models the tool knows (materials: materials_command.cpp).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "bssrdf/advise/validity_map.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/svg_chart.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/model_selection.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {

namespace {

// For a given medium: every model's measured error there and its cost, and the cheapest that meets
// --accuracy (what --model auto picks).
void print_estimates(const MediumOptions& options, const std::string& accuracy_text, bool json) {
  const auto resolved = options.resolve();
  const double accuracy = parse_accuracy(accuracy_text);
  const auto estimates = estimate_model_errors(resolved.medium);  // outside the measured ranges: the error says why
  const std::string chosen = cheapest_within(estimates, accuracy).value_or("");  // what --model auto picks
  if (json) {
    nlohmann::json doc = {{"accuracy", accuracy},
                          {"chosen", chosen.empty() ? nlohmann::json(nullptr) : nlohmann::json(chosen)}};
    for (const auto& e : estimates)
      doc["models"].push_back({{"name", e.model},
                               {"cost_ns", e.cost_ns},
                               {"total_error", e.total_error},
                               {"profile_l2_error", e.profile_error},
                               {"near_l2_error", e.near_error},
                               {"far_l2_error", e.far_error},
                               {"measured_against", e.source},
                               {"invalid", e.invalid.empty() ? nlohmann::json(nullptr) : nlohmann::json(e.invalid)}});
    std::cout << doc.dump(2) << '\n';
    return;
  }
  const std::string source = estimates.front().source;
  std::cout
      << (source == "exact"
              ? "measured live against the exact model at this medium (worst channel; exact: its own accuracy against "
                "Monte Carlo), R(r) L2 = the larger of near and far field, cheapest first:\n"
          : source == "table"
              ? "measured against Monte Carlo at the cases bracketing this medium (worst channel), cheapest first:\n"
              : "measured against the exact model where a channel is inside its domain, else against Monte Carlo at "
                "the "
                "cases bracketing it (worst channel), cheapest first:\n")
      << "  model               ns/eval   total   R(r) L2\n";
  for (const auto& e : estimates) {
    char line[160];
    std::snprintf(line, sizeof line, "  %-18s %8.0f  %5.1f %%  %6.1f %%", e.model.c_str(), e.cost_ns,
                  100 * e.total_error, 100 * e.profile_error);
    std::cout << line << (e.model == chosen ? "   <- cheapest within " + short_number(100 * accuracy) + " %" : "")
              << (e.invalid.empty()
                      ? ""
                      : "   invalid here (" + e.invalid.substr(0, e.invalid.find(": ", e.invalid.find(": ") + 2)) + ")")
              << '\n';
  }
  if (chosen.empty()) std::cout << "no model is measured within " << short_number(100 * accuracy) << " % here\n";
}

// Cost against accuracy for every model: over all measured cases (median, whiskers from the best to
// the worst case), or at one medium's coefficients (its estimates, worst channel).
Chart speed_accuracy_chart(const std::optional<MediumOptions::Resolved>& medium) {
  Chart chart;
  chart.x_title = "cost of one R(r) evaluation, ns (bench_models)";
  chart.y_title = "relative error against Monte Carlo, %";
  // Legend entries say what each marker is (the total-error squares carry no point labels).
  ChartSeries l2{"R(r) L2 error", "#1f77b4", false, {}}, total{"total error (model: same x)", "#ff7f0e", true, {}};
  const auto percent = [](double v) { return std::max(100 * v, 0.1); };  // below 0.1 % drawn at 0.1 %
  if (medium) {
    const std::string name = medium->material ? medium->material->name : std::string("the given medium");
    chart.title = "Speed against accuracy: " + name;
    const auto estimates = estimate_model_errors(medium->medium);
    chart.notes = estimates.front().source == "exact"
                      ? std::vector<std::string>{"each model's error at these coefficients, measured live against the exact model, worst channel",
                                                 "(exact: its own band against Monte Carlo); errors below 0.1 % drawn at 0.1 %"}
                      : std::vector<std::string>{"each model's error at these coefficients: against the exact model inside its domain, else the worst "
                                                 "measured case around them, worst channel",
                                                 "(tools/validation/models_vs_montecarlo_extended.tsv, 2M photons per case); errors below 0.1 % drawn at 0.1 %"};
    for (const auto& e : estimates) {
      l2.points.push_back({e.model, e.cost_ns, percent(e.profile_error), 0, 0});
      total.points.push_back({"", e.cost_ns, percent(e.total_error), 0, 0});
    }
  } else {
    chart.title = "Speed against accuracy of the profile models";
    chart.notes = {"markers: medians over " + std::to_string(measured_models().front().profile_error.size()) +
                       " Monte Carlo cases (alpha' 0.5-0.999, eta 1-1.5, g 0, 0.9, 0.95, 2M photons each);",
                   "bars: best to worst case of R(r)'s L2 error; errors below 0.1 % drawn at 0.1 % "
                   "(models_vs_montecarlo_extended.tsv)"};
    const auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    };
    l2.name = "R(r) L2, median; bars: range";
    total.name = "total error, median (same x)";
    for (const auto& m : measured_models()) {
      const auto [l2_lo, l2_hi] = std::minmax_element(m.profile_error.begin(), m.profile_error.end());
      l2.points.push_back({m.model, m.cost_ns, percent(median(m.profile_error)), percent(*l2_lo), percent(*l2_hi)});
      total.points.push_back({"", m.cost_ns, percent(median(m.total_error)), 0, 0});
    }
    // The reference models (exact) carry their own band against fresh Monte Carlo instead of a column.
    for (const auto& e : model_registry()) {
      if (!e.reference_accuracy || !e.listed) continue;
      const auto& band = *e.reference_accuracy;
      double lo = band.profile;
      for (const auto& region : band.regions) lo = std::min(lo, region.profile);
      l2.points.push_back({e.name, e.cost_ns, percent(band.profile), percent(lo), percent(band.profile)});
      total.points.push_back({"", e.cost_ns, percent(band.total), 0, 0});
      chart.notes.push_back(e.name +
                            ": its worst error against fresh Monte Carlo over its validation points (bar "
                            "down to its best region's band), not a median");
    }
  }
  chart.series = {l2, total};
  return chart;
}

}  // namespace

Action register_models(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto medium = std::make_shared<MediumOptions>();
  auto accuracy = std::make_shared<std::string>();
  auto* sub = app.add_subcommand("models",
                                 "List the profile models: what each includes and where it holds; with a medium, "
                                 "each one's measured error there and the cheapest within --accuracy");
  auto format = std::make_shared<std::string>("table");
  sub->add_option("--format,-f", *format, "table or json [table]")->check(CLI::IsMember({"table", "json"}));
  sub->add_flag("--json", *json, "Same as -f json (kept for scripts)")->group("");
  medium->add_to(*sub);
  sub->add_option("--accuracy", *accuracy, "With a medium: relative error allowed (total and R(r) L2) [0.1]");
  auto chart = std::make_shared<std::string>();
  sub->add_option("--chart", *chart,
                  "Write an SVG chart of cost against measured error (over all measured cases, or for the medium)");
  auto map = std::make_shared<ValidityMapOptions>();
  auto map_file = std::make_shared<std::string>();
  sub->add_option("--map", *map_file,
                  "Write validity maps (FILE.svg or FILE.png): each model's error over a parameter plane and the "
                  "cheapest within the tolerance, materials marked");
  sub->add_option("--over", map->over, "--map: the plane, albedo,eta (g = 0) or albedo,g (eta = 1.3) [albedo,eta]");
  sub->add_option(
      "--metric", map->metric,
      "--map: total or profile (relative errors measured live against the exact model; cheapest within "
      "--accuracy), or image (8-bit sRGB code values against --map-reference per cell; cheapest within --tolerance) "
      "[profile]");
  auto map_reference = std::make_shared<std::string>("exact");
  sub->add_option("--map-reference", *map_reference,
                  "--map --metric image: the reference, exact (the tabulated transport solution) or montecarlo (a "
                  "run per cell, -n photons) [exact]");
  auto tolerance = std::make_shared<std::string>("1");
  sub->add_option("--tolerance", *tolerance, "--map --metric image: largest acceptable image error, code values [1]");
  sub->add_option("--pixel", map->pixel, "--map --metric image: pixel size in transport mean free paths [1]");
  auto photons = std::make_shared<std::uint64_t>(20'000);
  add_count_option(*sub, "--photons,-n", *photons, 1000, kMaxPhotons,
                   "--map --metric image: Monte Carlo photons per cell [20000]");
  return [json, format, medium, accuracy, chart, map, map_file, tolerance, photons, map_reference] {
    *json = *json || *format == "json";
    if (!map_file->empty()) {  // validity maps (advise/validity_map.hpp)
      map->extension = std::filesystem::path(*map_file).extension().string();
      if (map->extension != ".svg" && map->extension != ".png")
        throw InvalidInput("--map", "'" + *map_file + "'", "a file ending in .svg or .png");
      map->tolerance = map->metric == "image" ? parse_number(*tolerance, "--tolerance") : parse_accuracy(*accuracy);
      const auto database = MaterialDatabase::load_with_user(medium->db);
      if (*map_reference != "exact" && *map_reference != "montecarlo")
        throw InvalidInput("--map-reference", "'" + *map_reference + "'", "exact or montecarlo");
      const MonteCarloReference montecarlo({*photons, 1, 0});
      const ModelReference exact(make_model("exact"));
      const ReferenceProfile& reference =
          *map_reference == "exact" ? static_cast<const ReferenceProfile&>(exact) : montecarlo;
      write_file_atomically(*map_file, render_validity_map(*map, database.all(), &reference));
      std::cout << "map: " << *map_file << '\n';
      return;
    }
    if (!chart->empty()) {
      if (std::filesystem::path(*chart).extension() != ".svg")
        throw InvalidInput("--chart", "'" + *chart + "'", "a file ending in .svg");
      std::optional<MediumOptions::Resolved> resolved;
      if (!medium->material.empty() || !medium->sigma_a.empty()) resolved = medium->resolve();
      write_file_atomically(*chart, render_svg(speed_accuracy_chart(resolved)));
      std::cout << "chart: " << *chart << '\n';
      return;
    }
    if (!medium->material.empty() || !medium->sigma_a.empty()) return print_estimates(*medium, *accuracy, *json);
    if (!accuracy->empty()) throw InvalidInput("--accuracy: give a medium (--material or --sigma-a/--sigma-s) too");
    nlohmann::json list = nlohmann::json::array();
    for (const auto& entry : model_registry()) {
      if (!entry.listed) continue;
      const auto& name = entry.name;
      const auto model = entry.make();
      const std::string domain = measured_domain(entry);
      if (*json) {
        list.push_back({{"name", name},
                        {"description", model->description()},
                        {"includes_single_scattering", entry.includes_single_scattering},
                        {"validity_domain", domain}});
      } else {
        std::cout << name << "\n    " << model->description() << "\n    single scattering: "
                  << (entry.includes_single_scattering ? "included" : "omitted (add with --single-scattering)")
                  << "\n    " << domain << "\n";
      }
    }
    if (*json) std::cout << list.dump(2) << '\n';
  };
}

}  // namespace bssrdf::cli
