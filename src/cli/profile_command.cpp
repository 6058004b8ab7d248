// bssrdf profile: R(r) of a material or of given coefficients under one model; with --thickness
// (or --layers FILE.json) R(r) and T(r) of a slab or a layer stack under the multipole.
//
// Thin slabs: where the multipole is invalid (a layer thinner than 2 transport mean free paths,
// the real source outside the slab, negative transmittance) the command refuses, exit status 2,
// with one line naming the channel and layer and pointing to the Monte Carlo reference
// (`bssrdf reference --thickness D` / `--layers FILE`), which is exact there.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/layered.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/profile_report.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "bssrdf/spectral/colour_profile.hpp"
#include "cli_common.hpp"
#include "colour_options.hpp"
#include "commands.hpp"

namespace bssrdf::cli {
namespace {

// A model whose R(r) holds its (nonzero) total at no finite radius has no profile to print: R(r)
// would be 0 at every radius while the total is not (burley-dmfp without absorption, whose length
// 1/sigma_tr is infinite). Refused, with the model's own reason.
void refuse_unbounded_profile(const Model& model, const Medium& medium) {
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    const double total = model.total_reflectance(m);
    if (!(total > 0) || std::isfinite(model.radius_for_fraction(m, 0.99))) continue;
    std::string reason;
    for (const auto& note : model.validity(m))
      if (note.severity == Severity::invalid) reason = " (" + note.message + ")";
    throw InvalidInput("channel " + medium.channel_names[c] + ": " + model.name() + " spreads its total reflectance " +
                       format_number(std::round(total * 1e5) / 1e5) + " over no finite radius here" + reason +
                       "; choose another model (bssrdf models)");
  }
}

// The first note that makes the multipole unusable here (not the albedo notes every diffusion
// model carries), or nullptr.
const ValidityNote* breakdown(const ValidityReport& report) {
  for (const auto& note : report)
    if (note.severity == Severity::invalid &&
        (note.code == "thin_slab" || note.code == "thin_layer" || note.code == "source_outside_slab" ||
         note.code == "negative_transmittance" || note.code == "negative_reflectance"))
      return &note;
  return nullptr;
}

}  // namespace

Action register_profile(CLI::App& app) {
  struct Options {
    MediumOptions medium;
    ColourOptions colour;
    OutputOptions output;
    std::string model, radii, r_min, r_max, spacing = "log", thickness, layers;
    double pair_tolerance = 1e-5;
    int samples = 64;
    bool single_scattering = false;
    std::string surface_albedo, accuracy;
  };
  auto options = std::make_shared<Options>();
  auto* sub = app.add_subcommand("profile", "Radial diffusion profile R(r) per channel (per unit entered flux)");
  options->medium.add_to(*sub);
  options->colour.add_to(*sub);
  std::string names;  // the registry's, in its order
  for (const auto& name : model_names()) names += name + ", ";
  sub->add_option("--model", options->model,
                  "Model: " + names +
                      "multipole (slabs: needs --thickness or --layers); 'bssrdf models' lists them [exact, the "
                      "radiative-transfer solution, inside its domain, else the most accurate model measured there; "
                      "multipole with --thickness or --layers]; auto: the cheapest measured within --accuracy of "
                      "the radiative-transfer solution here");
  auto* model_option = sub->get_option("--model");
  sub->add_option(
      "--accuracy", options->accuracy,
      "With --model auto: relative error allowed in the total and in r R(r) (relative L2, inside and beyond one "
      "transport mfp) against the radiative-transfer solution, as measured for each model [0.1]");
  auto* thickness = sub->add_option("--thickness", options->thickness,
                                    "Slab thickness in --unit: R(r) and T(r) of a slab under the multipole "
                                    "(ambient index 1 on both sides)");
  auto* layers = sub->add_option("--layers", options->layers,
                                 "Layer stack file (JSON, format bssrdf-layers, as for 'bssrdf reference --layers'): "
                                 "multipole layers combined by the adding equations");
  sub->add_option("--pair-tolerance", options->pair_tolerance,
                  "Multipole: add dipole pairs until the totals are within this of the infinite series [1e-5]");
  layers->excludes(thickness);
  sub->add_flag("--single-scattering", options->single_scattering,
                "Add exact single scattering to a model that omits it (same as --model NAME+ss)");
  sub->add_option(
      "--surface-albedo", options->surface_albedo,
      "Burley models: the surface albedo A, given directly (0 < A < 1) [from the most accurate physical model]");
  auto* radii = sub->add_option("--radii", options->radii, "Explicit radii in --unit, comma-separated, increasing");
  auto* rmin = sub->add_option("--r-min", options->r_min, "Smallest radius [1e-3 of the smallest transport mfp]");
  auto* rmax = sub->add_option("--r-max", options->r_max, "Largest radius [the largest 99.9 %-energy radius]");
  auto* samples = add_count_option(*sub, "--samples", options->samples, 2, 1000000, "Number of radii [64]");
  auto* spacing = sub->add_option("--spacing", options->spacing, "Radius spacing: log or linear [log]")
                      ->check(CLI::IsMember({"log", "linear"}));
  radii->excludes(rmin)->excludes(rmax)->excludes(samples)->excludes(spacing);
  options->output.add_to(*sub);

  auto* unit_option = sub->get_option("--unit");
  return [options, model_option, unit_option] {
    const bool slab = !options->thickness.empty() || !options->layers.empty();
    if (slab && !options->accuracy.empty())
      throw InvalidInput("--accuracy: only with --model auto, not for slabs or layer stacks");
    if (slab && model_option->count() && options->model != "multipole")
      throw InvalidInput("--model", "'" + options->model + "'",
                         "multipole with " + std::string(options->layers.empty() ? "--thickness" : "--layers"));
    if (!slab && options->model == "multipole")
      throw InvalidInput("--model multipole: give --thickness D (a slab) or --layers FILE.json (a layer stack)");
    if (slab && options->single_scattering)
      throw InvalidInput("--single-scattering: not available for slabs (the multipole omits single scattering)");
    if (!(options->pair_tolerance > 0 && options->pair_tolerance < 1))
      throw InvalidInput("--pair-tolerance", format_number(options->pair_tolerance), "0 < tolerance < 1");
    std::optional<LayersFile> stack_file;
    MediumOptions::Resolved resolved;
    if (!options->layers.empty()) {
      const auto& o = options->medium;
      if (!o.material.empty() || !o.sigma_a.empty() || !o.sigma_s.empty() || !o.g.empty() || !o.eta.empty())
        throw InvalidInput(
            "--layers describes the medium: do not combine it with --material, --sigma-a, --sigma-s, --g or --eta");
      stack_file = read_layers_json(options->layers);
      resolved.unit = unit_option->count() ? parse_length_unit(o.unit, "--unit") : stack_file->unit;
    } else {
      resolved = options->medium.resolve();
    }
    // A layer stack is spectral when its channels are named by wavelength (bssrdf skin --layers-out); a bad --colour
    // is refused before any work (and any validity warning).
    const auto wavelengths = stack_file ? spectral::wavelengths_from_channel_names(stack_file->stack.channel_names)
                                        : resolved.medium.wavelength_nm;
    const auto colour = options->colour.resolve(wavelengths);
    const double mm = millimetres_per(resolved.unit);
    std::unique_ptr<Model> model;
    std::string auto_note;  // --model auto: which model and why
    if (stack_file) {
      for (std::size_t c = 0; c < stack_file->stack.channels(); ++c)
        if (const auto report = layered::Stack(stack_file->stack, c).validity(); const auto* note = breakdown(report))
          throw InvalidInput(
              "--layers " + options->layers + ": channel " + stack_file->stack.channel_names[c] + ": " + note->message +
              "; use 'bssrdf reference --layers " + options->layers +
              "' (Monte Carlo) for thin layers, or 'bssrdf lut --layers FILE --kind radial --reference' for a table");
    } else if (slab) {
      const double d = parse_length(options->thickness, "--thickness");
      if (!(d > 0)) throw InvalidInput("--thickness", options->thickness, "> 0");
      auto slab_model = std::make_unique<multipole::Model>(d * mm, std::nullopt, options->pair_tolerance);
      for (std::size_t c = 0; c < resolved.medium.channels(); ++c)
        if (const auto report = slab_model->validity(resolved.medium.reduced(c)); const auto* note = breakdown(report))
          throw InvalidInput("--thickness", options->thickness + " " + std::string(symbol(resolved.unit)),
                             "at least 2 transport mean free paths in every channel (channel " +
                                 resolved.medium.channel_names[c] + ": " + note->message +
                                 "); use 'bssrdf reference --thickness " + options->thickness +
                                 "' (Monte Carlo) for thin slabs");
      model = std::move(slab_model);
    } else {
      const auto chosen = resolve_model(options->model, options->accuracy, resolved.medium);
      if (options->model == "auto" && options->single_scattering)
        throw InvalidInput("--single-scattering: not with --model auto (the choice includes NAME+ss models)");
      if (options->model.empty() && options->single_scattering && model_entry(chosen.name).includes_single_scattering)
        throw InvalidInput("--single-scattering: the default model here, " + chosen.name +
                           ", includes single scattering already; give --model NAME for one that omits it");
      auto_note = chosen.note;
      model = make_model(chosen.name + (options->single_scattering ? "+ss" : ""));
    }
    if (model && !slab) refuse_unbounded_profile(*model, resolved.medium);
    if (!options->surface_albedo.empty()) {
      const double A = parse_number(options->surface_albedo, "--surface-albedo");
      if (!(A > 0 && A < 1)) throw InvalidInput("--surface-albedo", format_number(A), "0 < A < 1");
      const auto* entry = model ? find_model_entry(model->name()) : nullptr;
      if (!entry || !entry->with_surface_albedo)
        throw InvalidInput("--surface-albedo: only the burley models take a surface albedo, not " +
                           (model ? model->name() : std::string("multipole")));
      model = entry->with_surface_albedo(A);
    }
    std::vector<double> radii_mm;
    if (!options->radii.empty()) {
      SampledProfile check;
      check.radius = parse_length_list(options->radii, "--radii");
      check.value.assign(check.radius.size(), 0.0);
      if (check.radius.size() == 1) {  // one radius is a valid request; validate() checks profiles of two or more
        if (!std::isfinite(check.radius[0]) || check.radius[0] < 0)
          throw InvalidInput("--radii", format_number(check.radius[0]), ">= 0 and finite");
      } else {
        try {
          check.validate();
        } catch (const InvalidInput& e) {
          throw InvalidInput(std::string("--radii: ") + e.what());
        }
      }
      for (double r : parse_length_list(options->radii, "--radii")) radii_mm.push_back(r * mm);
    } else {
      if (options->samples < 2 || options->samples > 1000000)
        throw InvalidInput("--samples", std::to_string(options->samples), "2 to 1000000");
      const auto n = static_cast<std::size_t>(options->samples);
      const auto defaults =
          stack_file ? default_stack_radii_mm(stack_file->stack, n) : default_radii_mm(resolved.medium, *model, n);
      double lo = options->r_min.empty() ? defaults.front() : parse_length(options->r_min, "--r-min") * mm;
      double hi = options->r_max.empty() ? defaults.back() : parse_length(options->r_max, "--r-max") * mm;
      if (options->spacing == "linear" && options->r_min.empty()) lo = 0;
      if (options->spacing == "log" && !(lo > 0))
        throw InvalidInput("--r-min", format_number(lo / mm), "> 0 with log spacing");
      if (!(hi > lo))  // errors name only options the user gave
        throw InvalidInput(
            options->r_max.empty() ? "--r-min" : "--r-max", format_number((options->r_max.empty() ? lo : hi) / mm),
            options->r_max.empty()
                ? "< the default largest radius " + format_number(hi / mm)
                : "> " + std::string(options->r_min.empty() ? "the default smallest radius " : "--r-min = ") +
                      format_number(lo / mm));
      radii_mm = options->spacing == "log" ? log_spaced(lo, hi, n) : linear_spaced(lo, hi, n);
    }
    auto report = with_flag_names({{"radii", "--radii"}}, [&] {
      return stack_file ? compute_stack_report(stack_file->stack, radii_mm, resolved.unit)
                        : compute_profile_report(resolved.medium, *model, radii_mm, resolved.unit);
    });
    report.material = resolved.material;
    report.model_choice = auto_note;
    for (const auto& ch : report.channels) warn_validity(report.model, ch.name, ch.validity);
    if (colour) report = spectral::colour_profile(report, wavelengths, *colour);
    emit(
        options->output, [&] { return to_json(report); }, [&] { return to_csv(report); }, to_table(report));
  };
}

}  // namespace bssrdf::cli
