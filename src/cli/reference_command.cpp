// bssrdf reference: the Monte Carlo ground truth for a medium (shared options), a layer stack
// (--layers FILE.json) or the runs of an MCML input file (--mci FILE.mci).
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/io/mci.hpp"
#include "bssrdf/io/mco.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "bssrdf/spectral/colour_reference.hpp"
#include "cli_common.hpp"
#include "colour_options.hpp"
#include "commands.hpp"
#include "launched_process_group.hpp"

namespace bssrdf::cli {

Action register_reference(CLI::App& app) {
  struct Options {
    MediumOptions medium;
    ColourOptions colour;
    OutputOptions output;
    std::string thickness, layers, mci, mco_dir = ".", r_max, r_min, spacing = "linear", absorption = "implicit";
    std::uint64_t photons = 1'000'000, seed = 1;
    unsigned threads = 0;
    std::size_t bins = 100, depth_bins = 0;
    std::string roulette_threshold, roulette_survival;  // parsed here: CLI11 reads '' as 0
  };
  auto options = std::make_shared<Options>();
  auto* sub = app.add_subcommand(
      "reference",
      "Monte Carlo reference: R_d, T_t, R(r), T(r) with standard errors (radiative transfer, exact phase function)");
  options->medium.add_to(*sub);
  options->colour.add_to(*sub);
  auto* thickness = sub->add_option("--thickness", options->thickness, "Slab thickness in --unit [semi-infinite]");
  auto* layers = sub->add_option("--layers", options->layers, "Layer stack file (JSON, format bssrdf-layers)");
  auto* mci = sub->add_option("--mci", options->mci, "Run the cases of an MCML input file (cm, 1/cm; outputs in cm)");
  sub->add_option("--mco-dir", options->mco_dir,
                  "--mci: directory for each run's MCML output file (.mco, the name in the .mci) [., as MCML]");
  add_count_option(*sub, "--photons,-n", options->photons, 1, kMaxPhotons,
                   "Photons per channel (per run with --mci: default the file's) [1000000]; cost grows linearly, and "
                   "as 1/sigma_a' for near-conservative media");
  add_count_option(*sub, "--seed", options->seed, 0, kMaxSeed,
                   "Random seed; the result depends only on inputs and seed [1]");
  add_count_option(*sub, "--threads,-j", options->threads, 0, kMaxThreads,
                   "Worker threads, 0 = all cores; never changes the result [0]");
  sub->add_option("--r-max", options->r_max, "Largest radius of R(r) in --unit [10 transport mfp; --mci: nr*dr]");
  sub->add_option("--r-min", options->r_min, "Log spacing: outer radius of the first bin [r_max/1000]");
  add_count_option(*sub, "--bins", options->bins, 2, kMaxBins, "Radial bins [100; --mci: nr]");
  sub->add_option("--bin-spacing", options->spacing, "Radial bins: linear or log [linear]")
      ->check(CLI::IsMember({"linear", "log"}));
  add_count_option(*sub, "--depth-bins", options->depth_bins, 0, kMaxBins,
                   "Absorbed fraction by depth in this many bins [0: off; --mci: nz]");
  sub->add_option("--absorption", options->absorption,
                  "Absorption estimator: implicit (weights + roulette) or analog [implicit]")
      ->check(CLI::IsMember({"implicit", "analog"}));
  auto* threshold_option = sub->add_option(
      "--roulette-threshold", options->roulette_threshold,
      "Implicit capture: Russian roulette below this weight, 1e-12 to < 1 (unbiased for any value; cost grows as "
      "its logarithm falls; MCML: 1e-4) [" +
          format_number(MonteCarloOptions{}.roulette_threshold) + "]");
  auto* survival_option =
      sub->add_option("--roulette-survival", options->roulette_survival,
                      "Implicit capture: probability of surviving the roulette, 0 < p <= 1 (MCML: 0.1) [" +
                          format_number(MonteCarloOptions{}.roulette_survival) + "]");
  options->output.add_to(*sub);
  layers->excludes(thickness)->excludes(mci);
  mci->excludes(thickness);
  auto* unit_option = sub->get_option("--unit");
  auto* photons_option = sub->get_option("--photons");
  auto* bins_option = sub->get_option("--bins");
  auto* depth_option = sub->get_option("--depth-bins");

  return [options, unit_option, photons_option, bins_option, depth_option, threshold_option, survival_option] {
    const auto& o = *options;
    if (!o.layers.empty() || !o.mci.empty()) {
      if (!o.medium.material.empty() || !o.medium.sigma_a.empty() || !o.medium.sigma_s.empty() || !o.medium.g.empty() ||
          !o.medium.eta.empty())
        throw InvalidInput(
            std::string(o.mci.empty() ? "--layers" : "--mci") +
            " describes the medium: do not combine it with --material, --sigma-a, --sigma-s, --g or --eta");
    }
    MonteCarloOptions base;
    base.photons = o.photons;
    base.seed = o.seed;
    base.threads = o.threads;
    base.bins = o.bins;
    base.spacing = o.spacing == "log" ? BinSpacing::log : BinSpacing::linear;
    base.depth_bins = o.depth_bins;
    base.absorption = o.absorption == "analog" ? AbsorptionEstimator::analog : AbsorptionEstimator::implicit_capture;
    if (threshold_option->count()) {  // given, even as '' (which parse_number refuses)
      // 0 would trace every photon until its weight underflows (thousands of interactions each).
      base.roulette_threshold = parse_number(o.roulette_threshold, "--roulette-threshold");
      if (!(base.roulette_threshold >= 1e-12 && base.roulette_threshold < 1))
        throw InvalidInput("--roulette-threshold", o.roulette_threshold, "1e-12 <= threshold < 1");
    }
    if (survival_option->count()) {
      base.roulette_survival = parse_number(o.roulette_survival, "--roulette-survival");
      if (!(base.roulette_survival > 0 && base.roulette_survival <= 1))
        throw InvalidInput("--roulette-survival", o.roulette_survival, "0 < survival <= 1");
    }

    struct Case {
      std::string label;
      LayerStack stack;
      MonteCarloOptions options;
      std::string mco;  // --mci: the run's MCML output file
      int angle_bins = 1;
    };
    std::vector<Case> cases;
    LengthUnit unit = LengthUnit::millimetre;
    std::vector<double> wavelengths;  // of a spectral medium or layer stack: --colour integrates them
    const auto lengths = [&](MonteCarloOptions& mc, LengthUnit u) {
      if (!o.r_max.empty()) {
        mc.r_max = to_mm(parse_length(o.r_max, "--r-max"), u);
        // Bins of at least 1e-9 mm: narrower ones round R(r) = weight / area to infinity.
        if (!(mc.r_max >= 1e-9 * static_cast<double>(mc.bins)))
          throw InvalidInput("--r-max", o.r_max, "> 0 and at least 1e-9 mm per bin");
      }
      if (!o.r_min.empty()) {
        mc.r_min = to_mm(parse_length(o.r_min, "--r-min"), u);
        if (!(mc.r_min >= 1e-9)) throw InvalidInput("--r-min", o.r_min, "> 0 and at least 1e-9 mm");
      }
    };
    if (!o.mci.empty()) {
      unit = unit_option->count() ? parse_length_unit(o.medium.unit, "--unit") : LengthUnit::centimetre;
      const MciFile file = read_mci(o.mci);
      for (std::size_t k = 0; k < file.runs.size(); ++k) {
        const MciRun& run = file.runs[k];
        MonteCarloOptions mc = base;
        if (!photons_option->count()) mc.photons = run.photons;
        if (!bins_option->count()) {
          mc.bins = static_cast<std::size_t>(std::max(2, run.nr));
          mc.r_max = run.dr * static_cast<double>(mc.bins);
          mc.spacing = BinSpacing::linear;
        }
        if (!depth_option->count()) {
          mc.depth_bins = static_cast<std::size_t>(run.nz);
          mc.z_max = run.dz * run.nz;
        }
        lengths(mc, unit);
        cases.push_back(
            {"run " + std::to_string(k + 1) + " (" + run.output_file + ")", run.stack, mc, run.output_file, run.na});
      }
    } else if (!o.layers.empty()) {
      const LayersFile file = read_layers_json(o.layers);
      unit = unit_option->count() ? parse_length_unit(o.medium.unit, "--unit") : file.unit;
      MonteCarloOptions mc = base;
      lengths(mc, unit);
      cases.push_back({o.layers, file.stack, mc, "", 1});
      wavelengths = spectral::wavelengths_from_channel_names(file.stack.channel_names);
    } else {
      const auto resolved = o.medium.resolve();
      unit = resolved.unit;
      wavelengths = resolved.medium.wavelength_nm;
      double thickness_mm = kSemiInfinite;
      if (!o.thickness.empty()) {
        const double t = parse_length(o.thickness, "--thickness");
        if (!(t > 0)) throw InvalidInput("--thickness", o.thickness, "> 0 (omit for semi-infinite)");
        thickness_mm = to_mm(t, unit);
      }
      MonteCarloOptions mc = base;
      lengths(mc, unit);
      LayerStack stack = LayerStack::slab(resolved.medium, thickness_mm);
      if (resolved.material) stack.layers[0].name = resolved.material->name;
      cases.push_back({resolved.material ? resolved.material->name : "medium", stack, mc, "", 1});
    }
    for (auto& c : cases) c.options.validate();  // every case checked before any photon is traced
    if (!o.mci.empty() && (!o.colour.colour.empty() || !o.colour.illuminant.empty()))
      throw InvalidInput("--colour: not with --mci (MCML runs have no wavelengths)");
    const auto colour = o.colour.resolve(wavelengths);

    // Under mpirun or srun every rank runs the same cases and traces its share; rank 0 writes.
    ProcessGroup* group = launched_process_group();
    std::vector<MonteCarloResult> results;
    for (auto& c : cases) {
      c.options.progress = progress_bar(c.label);
      c.options.group = group;
      results.push_back(run_monte_carlo(c.stack, c.options));
    }
    if (!results[0].gathered) return;
    if (colour) {  // R, G, B per radial bin from the wavelengths' estimates
      results[0] = spectral::colour_reference(results[0], wavelengths, *colour);
      const auto note = spectral::colour_note(wavelengths, *colour);
      emit(
          o.output, [&] { return spectral::colour_reference_json(results[0], unit, note); },
          [&] { return spectral::colour_reference_csv(results[0], unit, note); },
          spectral::colour_reference_report(results[0], unit, note));
      return;
    }

    std::string content, table;
    for (std::size_t k = 0; k < results.size(); ++k) {
      if (results.size() > 1) table += "=== " + cases[k].label + " ===\n";
      table += results[k].report(unit) + (k + 1 < results.size() ? "\n" : "");
    }
    switch (o.output.file_format()) {
      case Format::json:
        if (!o.mci.empty()) {
          // An MCML file may hold several runs: always an array, so scripts need one code path.
          nlohmann::json doc;
          doc["source"] = o.mci;
          doc["runs"] = nlohmann::json::array();
          for (std::size_t k = 0; k < results.size(); ++k) {
            auto run = nlohmann::json::parse(to_json(results[k], unit));
            run["label"] = cases[k].label;
            doc["runs"].push_back(std::move(run));
          }
          content = doc.dump(2) + "\n";
        } else {
          content = to_json(results[0], unit);
        }
        break;
      case Format::csv:
        for (std::size_t k = 0; k < results.size(); ++k) {
          if (results.size() > 1) content += "# " + cases[k].label + "\n";
          content += to_csv(results[k], unit);
        }
        break;
      case Format::table:
        content = table;
        break;
    }
    // Every run is formatted before any file is written, so a refusal leaves none behind.
    std::vector<std::pair<std::filesystem::path, std::string>> mco_files;
    for (std::size_t k = 0; k < results.size(); ++k)
      if (!cases[k].mco.empty())
        mco_files.emplace_back(std::filesystem::path(o.mco_dir) / cases[k].mco,
                               format_mco(results[k], cases[k].mco, cases[k].angle_bins));
    emit(o.output, content, table);
    for (const auto& [path, text] : mco_files) write_file_atomically(path, text);
  };
}

}  // namespace bssrdf::cli
