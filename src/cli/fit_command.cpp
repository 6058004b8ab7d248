// bssrdf fit profile|albedo|slab|gaussians|burley: from measurements (or a model's profile) to
// parameters, with a Ceres-style report.
#include <iostream>
#include <memory>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/fit/profile_fit.hpp"
#include "bssrdf/fit/rxt_fit.hpp"
#include "bssrdf/io/profile_csv.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/profile_report.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "rxt_options.hpp"
#include "rxt_output.hpp"
#include "skin_command.hpp"

namespace bssrdf::cli {
namespace {

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    out.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::vector<double> per_channel(const std::string& text, const std::string& field, std::size_t n, double fallback) {
  if (text.empty()) return std::vector<double>(n, fallback);
  auto v = parse_number_list(text, field);
  if (v.size() == 1) v.assign(n, v[0]);
  if (v.size() != n)
    throw InvalidInput(field + ": " + std::to_string(v.size()) + " values for " + std::to_string(n) + " channels");
  return v;
}

void emit_report(const OutputOptions& output, const FitReport& report) {
  const bool json = output.file_format() == Format::json && (!output.output.empty() || output.format == "json");
  emit(output, json ? report.to_json() : report.full_report(), report.full_report());
}

// A profile to fit for gaussians/burley: a CSV file, or a model's R(r) for a medium.
struct ProfileSource {
  MediumOptions medium;
  std::string data, model;
  int samples = 128;

  void add_to(CLI::App& app) {
    auto* d = app.add_option("--data", data,
                             "Profile CSV (radius, one column per channel), e.g. from 'bssrdf profile -f csv'");
    medium.add_to(app);
    app.add_option(
        "--model", model,
        "Model whose profile is fitted when no --data is given [the registry's default: exact inside its domain]");
    add_count_option(app, "--samples", samples, 8, 100000, "Radii sampled from the model [128]");
    d->excludes(app.get_option("--material"))->excludes(app.get_option("--sigma-a"));
  }

  std::pair<std::vector<NamedProfile>, std::string> resolve(LengthUnit& unit) const {
    std::vector<NamedProfile> out;
    if (!data.empty()) {
      const auto measured = read_profile_csv(data);
      unit = measured.unit;
      return {named_profiles_in_own_unit(measured), data};
    }
    const auto resolved = medium.resolve();
    unit = resolved.unit;
    const auto chosen = resolve_model(model, "", resolved.medium);
    const auto m = make_model(chosen.name);
    if (samples < 8 || samples > 100000) throw InvalidInput("--samples", std::to_string(samples), "8 to 100000");
    const auto report =
        compute_profile_report(resolved.medium, *m, default_radii_mm(resolved.medium, *m, samples), unit);
    for (const auto& ch : report.channels) out.push_back({ch.name, ch.profile});
    return {out, chosen.name + " profile of " +
                     (resolved.material ? resolved.material->name : std::string("the given medium")) +
                     (chosen.note.empty() ? "" : " (" + chosen.note + ")")};
  }
};

}  // namespace

Action register_fit(CLI::App& app) {
  auto* fit = app.add_subcommand("fit", "Fit material parameters to measurements, or real-time forms to a profile");
  fit->require_subcommand(1);

  // fit profile
  struct ProfileOptions {
    std::string file, model, eta = "1.3", g, loss = "none", unit;
    bool fit_eta = false, fit_scale = false;
    double loss_scale = 1;
    OutputOptions output;
  };
  auto po = std::make_shared<ProfileOptions>();
  auto* profile = fit->add_subcommand("profile", "Measured radial reflectance (CSV) -> sigma_a, sigma_s' per channel");
  profile
      ->add_option("file", po->file, "Profile CSV: radius, one column per channel, optional <channel>_stderr columns")
      ->required();
  profile->add_option(
      "--model", po->model,
      "Forward model (any of 'bssrdf models', NAME+ss too) [the registry's default: exact inside its domain]");
  profile->add_option("--eta", po->eta, "Relative index; the start value with --fit-eta [1.3]");
  profile->add_flag("--fit-eta", po->fit_eta, "Fit one eta shared by all channels (within [1, 2])");
  profile->add_flag("--fit-scale", po->fit_scale, "Fit an unknown overall scale (uncalibrated camera)");
  profile->add_option("--g", po->g, "Henyey-Greenstein g per channel, held fixed [0]");
  profile->add_option("--loss", po->loss, "Robust loss: none, huber, cauchy [none]")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  profile->add_option("--loss-scale", po->loss_scale, "Scale of the robust loss, in weighted-residual units [1]");
  profile->add_option("--unit", po->unit, "Unit of the radius column when its header does not say [mm]");
  po->output.add_to(*profile);

  // fit albedo
  struct AlbedoOptions {
    std::string albedo, distance, convention = "mfp", unit = "mm", model, eta = "1.3", g, channels;
    OutputOptions output;
  };
  auto ao = std::make_shared<AlbedoOptions>();
  auto* albedo =
      fit->add_subcommand("albedo", "Surface albedo + a distance per channel -> sigma_a, sigma_s' (exact inversion)");
  albedo->add_option("--albedo", ao->albedo, "Total diffuse reflectance per channel, e.g. 0.8,0.5,0.3")->required();
  albedo->add_option("--distance", ao->distance, "Distance per channel in --unit, in the --convention")->required();
  albedo
      ->add_option("--convention", ao->convention,
                   "mfp (1/sigma_t), transport-mfp (1/sigma_t') or dmfp (1/sigma_tr) [mfp]")
      ->check(CLI::IsMember({"mfp", "transport-mfp", "dmfp"}));
  albedo->add_option("--unit", ao->unit, "Length unit: um, mm, cm, m [mm]");
  albedo->add_option("--model", ao->model,
                     "Model whose total is inverted [the registry's default: exact inside its domain]");
  albedo->add_option("--eta", ao->eta, "Relative index [1.3]");
  albedo->add_option("--g", ao->g, "Anisotropy per channel [0]");
  albedo->add_option("--channels", ao->channels, "Channel names [R,G,B for three]");
  ao->output.add_to(*albedo);

  // fit slab
  struct SlabOptions {
    std::string reflectance, transmittance, r_stderr = "0.002", t_stderr = "0.002", thickness, unit = "mm", eta = "1.4",
                                            g, channels;
    std::string unscattered, u_stderr = "0.002", slides, model = "adding-doubling", rxt;
    bool lost_light = false;
    std::uint64_t lost_light_photons = 100000;
    RxtSphereOptions sphere;
    OutputOptions output;
  };
  auto so = std::make_shared<SlabOptions>();
  auto* slab = fit->add_subcommand(
      "slab",
      "Integrating-sphere R and T (and unscattered U) of a slab -> sigma_a, sigma_s' (and g) by adding-doubling");
  slab->add_option("--reflectance", so->reflectance,
                   "Diffuse reflectance per channel, per incident flux, specular excluded");
  slab->add_option("--transmittance", so->transmittance, "Total transmittance per channel (ballistic included)");
  slab->add_flag("--lost-light", so->lost_light,
                 "--rxt: correct for light leaving beyond the sphere's sample port with the Monte Carlo reference (off "
                 "by default)");
  slab->add_option("--lost-light-photons", so->lost_light_photons,
                   "--lost-light: photons per Monte Carlo run [100000]");
  slab->add_option(
      "--rxt", so->rxt,
      "Integrating-sphere file of Prahl's iad (.rxt): fit every row (g held at --g or 0 unless M_U is given)");
  add_rxt_sphere_options(*slab, so->sphere);
  slab->add_option("--reflectance-stderr", so->r_stderr, "Standard error of the reflectance [0.002]");
  slab->add_option("--transmittance-stderr", so->t_stderr, "Standard error of the transmittance [0.002]");
  slab->add_option("--thickness", so->thickness, "Slab thickness in --unit (not with --rxt)");
  slab->add_option("--unit", so->unit, "Length unit [mm]");
  slab->add_option("--eta", so->eta, "Relative index of the slab [1.4]");
  slab->add_option("--g", so->g, "Anisotropy per channel [0]");
  slab->add_option("--channels", so->channels, "Channel names");
  slab->add_option("--unscattered", so->unscattered,
                   "Unscattered (collimated) transmittance per channel: g is then fitted too");
  slab->add_option("--unscattered-stderr", so->u_stderr, "Standard error of the unscattered transmittance [0.002]");
  slab->add_option("--slides", so->slides, "Glass slides on both faces: index,thickness (in --unit), e.g. 1.5,1");
  slab->add_option("--model", so->model, "adding-doubling (exact) or multipole (for comparison) [adding-doubling]")
      ->check(CLI::IsMember({"adding-doubling", "multipole"}));
  so->output.add_to(*slab);

  // fit gaussians / burley
  auto go = std::make_shared<std::pair<ProfileSource, OutputOptions>>();
  auto gcount = std::make_shared<int>(6);
  auto* gaussians = fit->add_subcommand(
      "gaussians", "Sum of N Gaussians (shared variances, per-channel weights) fitted to a profile");
  go->first.add_to(*gaussians);
  add_count_option(*gaussians, "-n,--count", *gcount, 1, 32, "Number of Gaussians [6]");
  go->second.add_to(*gaussians);
  auto bo = std::make_shared<std::pair<ProfileSource, OutputOptions>>();
  auto* burley = fit->add_subcommand("burley", "Burley's d per channel fitted to a profile");
  bo->first.add_to(*burley);
  bo->second.add_to(*burley);

  const FitSkinCommand skin = register_fit_skin(*fit);

  return [=] {
    if (skin.app->parsed()) {
      skin.run();
    } else if (profile->parsed()) {
      ProfileFitOptions options;
      options.model = po->model;
      options.eta = parse_number(po->eta, "--eta");
      options.fit_eta = po->fit_eta;
      options.fit_scale = po->fit_scale;
      if (!po->g.empty()) options.g = parse_number_list(po->g, "--g");
      options.loss = po->loss;
      options.loss_scale = po->loss_scale;
      std::optional<LengthUnit> unit;
      if (!po->unit.empty()) unit = parse_length_unit(po->unit, "--unit");
      const auto data = read_profile_csv(po->file, unit);
      emit_report(po->output, fit_profile(data, options));
    } else if (albedo->parsed()) {
      const auto A = parse_number_list(ao->albedo, "--albedo");
      const auto n = A.size();
      const auto distance = per_channel(ao->distance, "--distance", n, 0);
      const auto g = per_channel(ao->g, "--g", n, 0);
      const auto names = ao->channels.empty() ? default_channel_names(n) : split_names(ao->channels);
      if (names.size() != n)
        throw InvalidInput("--channels: " + std::to_string(names.size()) + " names for " + std::to_string(n) +
                           " channels");
      std::vector<ChannelInput> inputs;
      for (std::size_t c = 0; c < n; ++c) {
        if (!(A[c] >= 0 && A[c] <= 1)) throw InvalidInput("--albedo[" + names[c] + "]", format_number(A[c]), "[0, 1]");
        if (!(g[c] > -1 && g[c] < 1)) throw InvalidInput("--g[" + names[c] + "]", format_number(g[c]), "-1 < g < 1");
        inputs.push_back({names[c], A[c], distance[c], g[c]});
      }
      emit_report(ao->output,
                  fit_albedo(inputs, parse_distance_convention(ao->convention), parse_length_unit(ao->unit, "--unit"),
                             ao->model, parse_number(ao->eta, "--eta")));
    } else if (slab->parsed() && !so->rxt.empty()) {
      if (!so->reflectance.empty() || !so->transmittance.empty() || !so->thickness.empty() ||
          !so->unscattered.empty() || !so->slides.empty())
        throw InvalidInput(
            "--rxt: the file gives the measurements, thickness and slides; do not combine it with --reflectance, "
            "--transmittance, --unscattered, --thickness or --slides");
      if (so->model != "adding-doubling") throw InvalidInput("--model", so->model, "adding-doubling with --rxt");
      RxtFitOptions options;
      if (!so->g.empty()) options.g = parse_number(so->g, "--g");
      options.reflectance_stderr = parse_number(so->r_stderr, "--reflectance-stderr");
      options.transmittance_stderr = parse_number(so->t_stderr, "--transmittance-stderr");
      options.unscattered_stderr = parse_number(so->u_stderr, "--unscattered-stderr");
      options.lost_light = so->lost_light;
      options.lost_light_photons = so->lost_light_photons;
      apply_rxt_sphere_options(so->sphere, options);
      const auto file = read_rxt(so->rxt);
      const auto fit = fit_rxt(file, options);
      const auto table = rxt_fit_table(fit);
      emit(
          so->output, [&] { return rxt_fit_json(fit); }, [&] { return rxt_fit_csv(fit); }, table);
    } else if (slab->parsed()) {
      if (so->lost_light || any_rxt_sphere_option(so->sphere))
        throw InvalidInput("--lost-light, --quadrature and the sphere options: only with --rxt");
      if (so->reflectance.empty()) throw InvalidInput("--reflectance is required (or --rxt FILE)");
      if (so->transmittance.empty()) throw InvalidInput("--transmittance is required (or --rxt FILE)");
      if (so->thickness.empty()) throw InvalidInput("--thickness is required (or --rxt FILE)");
      const auto R = parse_number_list(so->reflectance, "--reflectance");
      const auto n = R.size();
      const auto T = per_channel(so->transmittance, "--transmittance", n, 0);
      const auto rs = per_channel(so->r_stderr, "--reflectance-stderr", n, 0.002);
      const auto ts = per_channel(so->t_stderr, "--transmittance-stderr", n, 0.002);
      const auto g = per_channel(so->g, "--g", n, 0);
      const auto names = so->channels.empty() ? default_channel_names(n) : split_names(so->channels);
      if (names.size() != n)
        throw InvalidInput("--channels: " + std::to_string(names.size()) + " names for " + std::to_string(n) +
                           " channels");
      const auto U = per_channel(so->unscattered, "--unscattered", n, -1);
      const auto us = per_channel(so->u_stderr, "--unscattered-stderr", n, 0.002);
      for (std::size_t c = 0; c < n; ++c)
        if (!so->unscattered.empty() && !(U[c] >= 0 && U[c] <= 1))
          throw InvalidInput("--unscattered[" + names[c] + "]", format_number(U[c]), "[0, 1]");
      std::vector<SlabMeasurement> data;
      for (std::size_t c = 0; c < n; ++c) data.push_back({names[c], R[c], T[c], rs[c], ts[c], g[c], U[c], us[c]});
      SlabFitOptions options;
      options.model = so->model;
      if (!so->slides.empty()) {
        const auto v = parse_number_list(so->slides, "--slides");
        if (v.size() != 2) throw InvalidInput("--slides", so->slides, "two numbers: index,thickness (e.g. 1.5,1)");
        options.slide_n = v[0];
        options.slide_thickness = v[1];
      }
      emit_report(so->output, fit_slab(data, parse_number(so->thickness, "--thickness"),
                                       parse_length_unit(so->unit, "--unit"), parse_number(so->eta, "--eta"), options));
    } else if (gaussians->parsed()) {
      LengthUnit unit = LengthUnit::millimetre;
      const auto [profiles, source] = go->first.resolve(unit);
      emit_report(go->second, fit_gaussians(profiles, *gcount, unit, source));
    } else if (burley->parsed()) {
      LengthUnit unit = LengthUnit::millimetre;
      const auto [profiles, source] = bo->first.resolve(unit);
      emit_report(bo->second, fit_burley(profiles, unit, source));
    }
  };
}

}  // namespace bssrdf::cli
