// bssrdf profile: R(r) of a material or of given coefficients under one model.
#include <iostream>
#include <memory>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/normalized_diffusion.hpp"
#include "bssrdf/profile_report.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {

Action register_profile(CLI::App& app) {
  struct Options {
    MediumOptions medium;
    OutputOptions output;
    std::string model = "better-dipole", radii, r_min, r_max, spacing = "log";
    int samples = 64;
    bool single_scattering = false;
    std::string surface_albedo;
  };
  auto options = std::make_shared<Options>();
  auto* sub = app.add_subcommand("profile", "Radial diffusion profile R(r) per channel (per unit entered flux)");
  options->medium.add_to(*sub);
  sub->add_option("--model", options->model,
                  "Model: dipole, better-dipole, pbd, quantized, burley, burley-diffuse, burley-dmfp; "
                  "'bssrdf models' lists them [better-dipole]");
  sub->add_flag("--single-scattering", options->single_scattering,
                "Add exact single scattering to a model that omits it (same as --model NAME+ss)");
  sub->add_option("--surface-albedo", options->surface_albedo,
                  "Burley models: the surface albedo A, given directly (0 < A < 1) [from the most accurate physical model]");
  auto* radii = sub->add_option("--radii", options->radii, "Explicit radii in --unit, comma-separated, increasing");
  auto* rmin = sub->add_option("--r-min", options->r_min, "Smallest radius [1e-3 of the smallest transport mfp]");
  auto* rmax = sub->add_option("--r-max", options->r_max, "Largest radius [the largest 99.9 %-energy radius]");
  auto* samples = sub->add_option("--samples", options->samples, "Number of radii [64]");
  auto* spacing = sub->add_option("--spacing", options->spacing, "Radius spacing: log or linear [log]")
                      ->check(CLI::IsMember({"log", "linear"}));
  radii->excludes(rmin)->excludes(rmax)->excludes(samples)->excludes(spacing);
  options->output.add_to(*sub);

  return [options] {
    const auto resolved = options->medium.resolve();
    auto model = make_model(options->model + (options->single_scattering ? "+ss" : ""));
    if (!options->surface_albedo.empty()) {
      const double A = parse_number(options->surface_albedo, "--surface-albedo");
      if (!(A > 0 && A < 1)) throw InvalidInput("--surface-albedo", format_number(A), "0 < A < 1");
      const auto* burley = dynamic_cast<const normalized_diffusion::Model*>(model.get());
      if (!burley) throw InvalidInput("--surface-albedo: only the burley models take a surface albedo, not " + model->name());
      model = std::make_unique<normalized_diffusion::Model>(burley->scaling(), A);
    }
    const double mm = millimetres_per(resolved.unit);
    std::vector<double> radii_mm;
    if (!options->radii.empty()) {
      SampledProfile check;
      check.radius = parse_number_list(options->radii, "--radii");
      check.value.assign(check.radius.size(), 0.0);
      if (check.radius.size() == 1) check.radius.push_back(check.radius[0]);  // let validate() name it
      try {
        check.validate();
      } catch (const InvalidInput& e) {
        throw InvalidInput(std::string("--radii: ") + e.what());
      }
      for (double r : parse_number_list(options->radii, "--radii")) radii_mm.push_back(r * mm);
    } else {
      if (options->samples < 2 || options->samples > 1000000)
        throw InvalidInput("--samples", std::to_string(options->samples), "2 to 1000000");
      const auto n = static_cast<std::size_t>(options->samples);
      const auto defaults = default_radii_mm(resolved.medium, *model, n);
      double lo = options->r_min.empty() ? defaults.front() : parse_number(options->r_min, "--r-min") * mm;
      double hi = options->r_max.empty() ? defaults.back() : parse_number(options->r_max, "--r-max") * mm;
      if (options->spacing == "linear" && options->r_min.empty()) lo = 0;
      if (options->spacing == "log" && !(lo > 0))
        throw InvalidInput("--r-min", format_number(lo / mm), "> 0 with log spacing");
      if (!(hi > lo)) throw InvalidInput("--r-max", format_number(hi / mm), "> --r-min = " + format_number(lo / mm));
      radii_mm = options->spacing == "log" ? log_spaced(lo, hi, n) : linear_spaced(lo, hi, n);
    }
    auto report = compute_profile_report(resolved.medium, *model, radii_mm, resolved.unit);
    report.material = resolved.material;
    std::string content;
    switch (options->output.file_format()) {
      case Format::json: content = to_json(report); break;
      case Format::csv: content = to_csv(report); break;
      case Format::table: content = to_table(report); break;
    }
    emit(options->output, content, to_table(report));
  };
}

}  // namespace bssrdf::cli
