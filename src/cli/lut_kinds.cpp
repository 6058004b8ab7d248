// The table kinds of `bssrdf lut`: options in, the library's table and summary out.
#include "lut_kinds.hpp"

#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "bssrdf/advise/realtime_tables.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/lut/albedo_radius_table.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/lut/material_preview.hpp"
#include "bssrdf/lut/penumbra_table.hpp"
#include "bssrdf/lut/preintegrated_table.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/lut/reference_radial_table.hpp"
#include "bssrdf/lut/separable_kernel.hpp"
#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"
#include "bssrdf/profile.hpp"

namespace bssrdf::cli {
namespace {

// The kinds that tabulate a profile model: the medium, --model (auto resolved here, saying so in the
// summary) and the context every such table records.
template <class Tabulate>
Built with_model(const LutOptions& o, Tabulate&& tabulate) {
  const auto resolved = o.medium.resolve();
  const auto chosen = resolve_model(o.model, o.accuracy, resolved.medium);
  const auto model = make_model(chosen.name);
  const TableContext context{resolved.material, &resolved.medium, model.get(), resolved.unit};
  Built built = tabulate(resolved, *model, context);
  if (!chosen.note.empty()) built.summary = chosen.note + "\n" + built.summary;
  return built;
}

// --kind radial --reference: the Monte Carlo reference tabulated, for a medium or a layer stack.
Built build_reference_radial(const LutOptions& o) {
  if (o.model_given || !o.accuracy.empty())
    throw InvalidInput(
        "--reference: the table is the Monte Carlo reference, not a model (give no --model or --accuracy)");
  ReferenceRadialOptions options;
  if (o.photons_given) options.photons = o.photons;
  options.seed = o.seed;
  options.threads = o.threads;
  if (!o.all) options.progress = progress_bar("lut --reference");  // a terminal only; --all shows materials
  if (o.layers.empty()) {
    const auto resolved = o.medium.resolve();
    const TableContext context{resolved.material, &resolved.medium, nullptr, resolved.unit};
    const auto t = build_reference_radial_table(LayerStack::half_space(resolved.medium), options);
    return {to_lookup_table(t, context), summary(t, context), {}};
  }
  if (!o.medium.material.empty() || !o.medium.sigma_a.empty())
    throw InvalidInput("--layers: give no --material or coefficients with it");
  const auto file = read_layers_json(o.layers);
  const auto unit =
      o.medium.unit.empty() || o.medium.unit == "mm" ? file.unit : parse_length_unit(o.medium.unit, "--unit");
  const TableContext context{std::nullopt, nullptr, nullptr, unit};
  const auto t = build_reference_radial_table(file.stack, options);
  auto table = to_lookup_table(t, context);
  table.set("bssrdf:layers", o.layers + " (" + std::to_string(file.stack.layers.size()) + " layers)");
  return {std::move(table), summary(t, context), {}};
}

Built build_radial(const LutOptions& o) {
  if (!o.layers.empty() && !o.reference)
    throw InvalidInput("--layers: only with --kind radial --reference (Monte Carlo)");
  if (o.reference) return build_reference_radial(o);
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
    RadialTableOptions options;
    // With --pixel, --tolerance is an image error (code values) and sizes the table through the
    // relative interpolation tolerance; without, it is that relative tolerance.
    const auto judge = pixel_judge(o, resolved, model);
    if (!o.tolerance.empty() && !judge) options.tolerance = positive_fraction(o.tolerance, "--tolerance");
    if (!o.energy.empty()) options.energy = positive_fraction(o.energy, "--energy");
    if (!o.interpolation.empty()) options.interpolation = parse_interpolation(o.interpolation, "--interpolation");
    options.threads = o.threads;
    std::string sized;
    if (judge && judge->tolerance) {
      const auto choice = choose_radial_tolerance(resolved.medium, model, judge->judge, *judge->tolerance, options);
      options.tolerance = choice.relative_tolerance;
      sized = sized_note(judge->tolerance, choice.meets_tolerance,
                         "relative interpolation tolerance " + format_number(choice.relative_tolerance));
    }
    const auto t = build_radial_table(resolved.medium, model, options);
    Built b{to_lookup_table(t, context), summary(t, context), {}};
    if (judge) record_image_error(b, *judge, image_error_of(judge->judge, t), model, sized);
    return b;
  });
}

// albedo-radius tables are dimensionless: only (g, eta) come from the medium (a material's first
// channel, or --g and --eta, default 0 and 1.3).
Built build_albedo_radius(const LutOptions& o) {
  double g = 0, eta = 1.3;
  std::optional<Material> material;
  if (!o.medium.material.empty() || !o.medium.sigma_a.empty()) {
    const auto resolved = o.medium.resolve();
    g = resolved.medium.g[0];
    eta = resolved.medium.eta;
    material = resolved.material;
  } else {
    if (!o.medium.g.empty()) g = parse_number(o.medium.g, "--g");
    if (!o.medium.eta.empty()) eta = parse_number(o.medium.eta, "--eta");
  }
  if (o.model != "pbd")
    throw InvalidInput("--model", "'" + o.model + "'", "pbd for --kind albedo-radius (photon beam diffusion, as pbrt)");
  AlbedoRadiusOptions options;
  if (!o.tolerance.empty()) options.tolerance = positive_fraction(o.tolerance, "--tolerance");
  options.threads = o.threads;
  AlbedoRadiusLayout layout;
  std::string adaptive_note;
  if (o.layout == "pbrt") {
    layout = AlbedoRadiusLayout::pbrt();
  } else if (o.layout == "family") {
    // Up to 2048 a side, as the adaptive layout: 4M cells of beam integrals is already minutes.
    const auto [a, r] = parse_grid(o.size, 4, 2048, 4, 2048, "64x48 (ALBEDOSxRADII)");
    layout = AlbedoRadiusLayout::family(a, r);
  } else if (o.layout == "adaptive") {
    const double table_tolerance =
        o.table_tolerance.empty() ? kAdaptiveTableTolerance : positive_fraction(o.table_tolerance, "--table-tolerance");
    AlbedoRadiusOptions search = options;
    search.progress = progress_bar("adaptive albedo-radius layout");  // on a terminal: minutes at 1e-3
    const auto adaptive = adaptive_albedo_radius_layout(g, eta, table_tolerance, search);
    layout = adaptive.layout;
    adaptive_note = summary(adaptive, table_tolerance);
  } else {
    throw InvalidInput("--layout", "'" + o.layout + "'",
                       "pbrt, family (with --size AxR) or adaptive (with --table-tolerance)");
  }
  const auto t = build_albedo_radius_table(layout, g, eta, options);
  const auto model = make_model("pbd");
  auto table = to_lookup_table(t, {material, nullptr, model.get(), LengthUnit::millimetre}, o.layout);
  auto lines = summary(t, o.layout);
  if (!adaptive_note.empty()) {
    lines += "  " + adaptive_note + "\n";
    table.set("bssrdf:adaptive", adaptive_note);
  }
  return {std::move(table), lines, {}};
}

Built build_transmission(const LutOptions& o) {
  if (!o.accuracy.empty())
    throw InvalidInput("--accuracy: only with --model auto (transmission tables use adding-doubling or the multipole)");
  const auto resolved = o.medium.resolve();
  if (o.model_given && o.model != "multipole" && o.model != "adding-doubling")
    throw InvalidInput(
        "--model", "'" + o.model + "'",
        "adding-doubling (default) or multipole for --kind transmission (or --reference for Monte Carlo)");
  TransmissionTableOptions options;
  options.model = o.model_given ? o.model : "adding-doubling";
  if (options.model == "adding-doubling" && o.reference && !o.reference_everywhere)
    throw InvalidInput(
        "--reference", "given",
        "--model multipole (adding-doubling is exact at every thickness; --reference-everywhere runs Monte Carlo)");
  options.reference = o.reference;
  options.reference_everywhere = o.reference_everywhere;
  if (o.photons_given) options.photons = o.photons;
  options.seed = o.seed;
  options.threads = o.threads;
  auto thickness = slab_thicknesses(o.thickness, o.d_min, o.d_max, o.samples, resolved.unit,
                                    default_thickness_range(resolved.medium, options));
  for (double& d : thickness) d *= millimetres_per(resolved.unit);
  const auto t = build_transmission_table(resolved.medium, thickness, options);
  const multipole::Model model(1.0);
  const TableContext context{resolved.material, &resolved.medium, &model, resolved.unit};
  auto table = to_lookup_table(t, context);  // throws when nothing is left
  table.set("bssrdf:model_description",
            options.model == "adding-doubling" && !o.reference_everywhere
                ? std::string("total transmittance of slabs: adding-doubling (exact)")
                : std::string("total transmittance of slabs: multipole (Donner & Jensen 2005) where valid") +
                      (o.reference || o.reference_everywhere ? ", Monte Carlo reference elsewhere" : ""));
  return {std::move(table), summary(t, context), {}};
}

Built build_preintegrated(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
    PreintegratedOptions options;
    parse_size(o.size, options.width, options.height);
    if (!o.curvature_max.empty()) {
      const double c = parse_number(o.curvature_max, "--curvature-max");
      if (!(c > 0))
        throw InvalidInput("--curvature-max", format_number(c), "> 0 (1/" + std::string(symbol(resolved.unit)) + ")");
      options.curvature_max = c / millimetres_per(resolved.unit);
    }
    options.threads = o.threads;
    const auto judge = pixel_judge(o, resolved, model);
    const auto projections = project_channels(resolved.medium, model);
    std::string sized;
    if (judge && judge->tolerance && !o.size_given) {  // --size overrides
      const auto choice =
          choose_preintegrated_table(resolved.medium, projections, judge->judge, *judge->tolerance, false);
      options.width = options.height = choice.size;
      if (o.curvature_max.empty()) options.curvature_max = choice.curvature_max;
      sized = sized_note(judge->tolerance, choice.meets_tolerance,
                         "size " + std::to_string(choice.size) + "x" + std::to_string(choice.size));
    }
    const auto t = build_preintegrated_table(resolved.medium, projections, options);
    Built b{to_lookup_table(t, context), summary(t, context), {}};
    if (judge)
      record_image_error(b, *judge, image_error_of(judge->judge, t, resolved.medium, projections), model, sized);
    return b;
  });
}

Built build_penumbra(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
    PenumbraOptions options;
    parse_size(o.size, options.width, options.height);
    if (!o.width_max.empty()) options.width_max = positive_length_mm(o.width_max, "--width-max", resolved.unit);
    options.threads = o.threads;
    const auto t = build_penumbra_table(resolved.medium, model, options);
    return Built{to_lookup_table(t, context), summary(t, context), {}};
  });
}

Built build_separable(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
    SeparableKernelOptions options;
    if (o.taps != 0) options.taps = o.taps;
    if (o.range == "jimenez") {
      options.range = jimenez_range(options.taps);
    } else if (!o.range.empty()) {
      options.range = positive_length_mm(o.range, "--range", resolved.unit);
    }
    if (!o.band.empty()) options.band = positive_fraction(o.band, "--band");
    if (options.taps < 3 || options.taps % 2 == 0 || options.taps > 255)
      throw InvalidInput("--taps", std::to_string(options.taps), "an odd number from 3 to 255 (Jimenez: 11, 17, 25)");
    const auto judge = pixel_judge(o, resolved, model);
    const auto projections = project_channels(resolved.medium, model);
    std::string sized;
    if (judge && judge->tolerance && !o.taps_given && !o.range_given) {  // --taps or --range override
      const auto choice = choose_separable_kernel(resolved.medium, projections, judge->judge, *judge->tolerance);
      options = choice.options;
      sized = sized_note(judge->tolerance, choice.meets_tolerance,
                         std::to_string(options.taps) + " taps and the range holding " +
                             short_number(100 * options.band) + " % of the light");
    }
    const auto k = build_separable_kernel(resolved.medium, projections, options);
    Built b{to_lookup_table(k, context), summary(k, context), {}};
    if (judge) record_image_error(b, *judge, image_error_of(judge->judge, k), model, sized);
    for (const auto language : {ShaderLanguage::glsl, ShaderLanguage::hlsl}) {
      const std::string name = language == ShaderLanguage::glsl ? "glsl" : "hlsl";
      try {
        b.other_formats[name] = [text = to_shader(k, context, language)] { return text; };
      } catch (const InvalidInput& e) {  // e.g. not three channels: an error only when that format is asked for
        b.other_formats[name] = [e]() -> std::string { throw InvalidInput("--format", e.value(), e.accepted()); };
      }
    }
    return b;
  });
}

Built build_gaussians(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
    GaussianMixtureTable t;
    const auto judge = pixel_judge(o, resolved, model);
    std::string sized;
    if (judge && judge->tolerance && !o.count_given) {  // --count overrides
      const auto choice = choose_gaussian_count(resolved.medium, model, judge->judge, *judge->tolerance);
      t = fitted_mixture_table(resolved.medium, model, static_cast<int>(choice.count),
                               kGaussianFitSamples);  // as judged
      sized = sized_note(judge->tolerance, choice.meets_tolerance, std::to_string(choice.count) + " Gaussians");
    } else if (o.count == 0 && model_entry(model.name()).own_gaussians) {
      t = own_mixture_table(resolved.medium, model);
    } else {
      const int count = o.count == 0 ? 6 : o.count;
      if (count < 1 || count > 32) throw InvalidInput("--count", std::to_string(count), "1 to 32");
      t = fitted_mixture_table(resolved.medium, model, count);
    }
    Built b{to_lookup_table(t, context), summary(t, context), {}};
    if (judge) record_image_error(b, *judge, image_error_of(judge->judge, t), model, sized);
    return b;
  });
}

}  // namespace

std::span<const TableKind> table_kinds() {
  static const std::array<TableKind, 7> kinds{{
      {"radial", build_radial, "R(r) with its sampling CDF and inverse, or the Monte Carlo reference (--reference)"},
      {"albedo-radius", build_albedo_radius, "pbrt's photon-beam-diffusion table over (albedo, radius in mfp)"},
      {"transmission", build_transmission, "total diffuse transmittance of slabs against their thickness"},
      {"preintegrated", build_preintegrated, "pre-integrated skin: diffuse light over (N.L, curvature)"},
      {"penumbra", build_penumbra, "shadow-edge scattering over (shadow value, penumbra width)"},
      {"separable", build_separable, "a screen-space separable kernel (taps, weights; also GLSL or HLSL)"},
      {"gaussians", build_gaussians, "a sum of Gaussians (weights and variances per channel)"},
  }};
  return kinds;
}

const TableKind& table_kind(const std::string& name) {
  std::string known;
  for (const auto& kind : table_kinds()) {
    if (kind.name == name) return kind;
    known += (known.empty() ? "" : ", ") + std::string(kind.name);
  }
  throw InvalidInput("--kind", "'" + name + "'", "one of " + known);
}

}  // namespace bssrdf::cli
