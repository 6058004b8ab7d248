// The table kinds of `bssrdf lut`: each parses its flags into the library's options
// (lut/table_kinds.hpp) and calls the library's entry point for the kind.
#include "lut_kinds.hpp"

#include <algorithm>
#include <array>
#include <tuple>

#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/spectral/colour_medium.hpp"

namespace bssrdf::cli {
namespace {

// The kinds that tabulate a profile model: the medium, --model (auto resolved here, saying so in the
// summary) and the context every such table records.
// With --colour (with --all: for the spectral materials), the table is of R, G, B integrated per radius from each
// wavelength's profile under the model (spectral/colour_medium.hpp), and records the integration.
template <class Tabulate>
BuiltTable with_model(const LutOptions& o, Tabulate&& tabulate) {
  const auto resolved = o.medium.resolve();
  const auto chosen = resolve_model(o.model, o.accuracy, resolved.medium);
  const auto settings = o.all && !resolved.medium.spectral() ? std::nullopt : o.colour.resolve(resolved.medium);
  const std::shared_ptr<const Model> model = make_model(chosen.name);
  warn_validity(*model, resolved.medium);
  if (!settings) {
    BuiltTable built =
        tabulate(resolved, TableContext{resolved.material, &resolved.medium, model.get(), resolved.unit, chosen.note});
    if (!chosen.note.empty()) built.summary = chosen.note + "\n" + built.summary;
    return built;
  }
  if (o.kind == "gaussians" && o.count == 0 && model_entry(chosen.name).own_gaussians)
    throw InvalidInput("--colour: --model " + chosen.name +
                       "'s own Gaussians are per wavelength; give --count N to fit N to the colour profile");
  const auto colour = spectral::colour_medium(resolved.medium, model, *settings);
  auto rgb = resolved;
  rgb.medium = colour.rgb;
  BuiltTable built = tabulate(rgb, TableContext{resolved.material, &colour.rgb, colour.model.get(), resolved.unit,
                                                chosen.note, TableColour{colour.note, colour.summary()}});
  built.summary =
      "colour: " + colour.summary() + "\n" + (chosen.note.empty() ? "" : chosen.note + "\n") + built.summary;
  return built;
}

// The kinds that take no profile refuse --colour rather than ignore it.
void refuse_colour(const LutOptions& o, const std::string& why) {
  if (!o.colour.colour.empty() || !o.colour.illuminant.empty())
    throw InvalidInput("--colour: not for --kind " + o.kind + " (" + why + ")");
}

// --kind radial --reference: the Monte Carlo reference tabulated, for a medium or a layer stack.
BuiltTable build_reference_radial(const LutOptions& o) {
  if (o.model_given || !o.accuracy.empty())
    throw InvalidInput(
        "--reference: the table is the Monte Carlo reference, not a model (give no --model or --accuracy)");
  ReferenceRadialOptions options;
  if (o.photons_given) options.photons = o.photons;
  options.seed = o.seed;
  options.threads = o.threads;
  if (!o.all) options.progress = progress_bar("lut --reference");  // a terminal only; --all shows materials
  // With --colour: each wavelength's run integrated per bin to R, G, B (with --all: for the spectral materials).
  if (o.layers.empty()) {
    const auto resolved = o.medium.resolve();
    options.colour = o.all && !resolved.medium.spectral() ? std::nullopt : o.colour.resolve(resolved.medium);
    return tabulate_reference_radial({resolved.material, &resolved.medium, nullptr, resolved.unit}, options);
  }
  if (!o.medium.material.empty() || !o.medium.sigma_a.empty())
    throw InvalidInput("--layers: give no --material or coefficients with it");
  const auto file = read_layers_json(o.layers);
  options.colour = o.colour.resolve(spectral::wavelengths_from_channel_names(file.stack.channel_names));
  const auto unit =
      o.medium.unit.empty() || o.medium.unit == "mm" ? file.unit : parse_length_unit(o.medium.unit, "--unit");
  return tabulate_reference_radial(file.stack, o.layers, {std::nullopt, nullptr, nullptr, unit}, options);
}

BuiltTable build_radial(const LutOptions& o) {
  if (o.reference) return build_reference_radial(o);  // --layers without it: refused by register_lut
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const TableContext& context) {
    RadialKindOptions options;
    // With --pixel, --tolerance is an image error (code values) and sizes the table through the
    // relative interpolation tolerance; without, it is that relative tolerance.
    options.image = image_check(o, resolved.unit);
    if (!o.tolerance.empty() && !options.image) options.table.tolerance = positive_fraction(o.tolerance, "--tolerance");
    if (!o.energy.empty()) options.table.energy = positive_fraction(o.energy, "--energy");
    if (!o.interpolation.empty()) options.table.interpolation = parse_interpolation(o.interpolation, "--interpolation");
    options.table.threads = o.threads;
    return tabulate_radial(context, options);
  });
}

// albedo-radius tables are dimensionless: only (g, eta) come from the medium (a material's first
// channel, or --g and --eta, default 0 and 1.3).
BuiltTable build_albedo_radius(const LutOptions& o) {
  // Colour does not apply: the rows span every albedo for one (g, eta), in no colour; a renderer finds each of its
  // channels' rows from that channel's own albedo, so one table serves a spectral medium at every wavelength.
  refuse_colour(o,
                "its rows are over every albedo for one (g, eta) in no colour: a renderer looks up each channel's "
                "row by its own albedo; give no --colour");
  AlbedoRadiusKindOptions options;
  std::string g_choice;
  if (!o.medium.material.empty() || !o.medium.sigma_a.empty()) {
    const auto resolved = o.medium.resolve();
    const auto& g = resolved.medium.g;
    options.g = g[0];
    options.eta = resolved.medium.eta;
    options.material = resolved.material;
    const auto [g_min, g_max] = std::minmax_element(g.begin(), g.end());
    if (*g_min != *g_max)  // one table serves one g: say which, not silently
      g_choice = "g differs between the channels (" + format_number(*g_min) + " to " + format_number(*g_max) +
                 "): the table is for the first channel's g = " + format_number(g[0]) +
                 " (--g G without a medium makes one for another g)";
  } else {
    if (!o.medium.g.empty()) options.g = parse_number(o.medium.g, "--g");
    if (!o.medium.eta.empty()) options.eta = parse_number(o.medium.eta, "--eta");
  }
  if (!o.accuracy.empty()) throw InvalidInput("--accuracy: not for --kind albedo-radius (its rows span every albedo)");
  std::string note;  // why the rows are not the exact model's, when they are not by default
  if (o.model.empty()) {
    const auto chosen = default_model_over_albedos({options.g}, options.eta, options.eta);
    if (chosen.name == "exact")
      options.table.shape = RowShape::exact;
    else
      note = "default: " + chosen.reason + "; albedo-radius rows take the exact model or the library's default";
  } else if (o.model == "exact") {
    options.table.shape = RowShape::exact;
  } else if (o.model != "pbd") {
    throw InvalidInput("--model", "'" + o.model + "'",
                       "pbd (photon beam diffusion, as pbrt) or exact for --kind albedo-radius");
  }
  if (!o.tolerance.empty()) options.table.tolerance = positive_fraction(o.tolerance, "--tolerance");
  options.table.threads = o.threads;
  if (o.layout == "pbrt") {
    options.layout = AlbedoRadiusLayoutRule::pbrt;
  } else if (o.layout == "family") {
    // Up to 2048 a side, as the adaptive layout: 4M cells of beam integrals is already minutes.
    options.layout = AlbedoRadiusLayoutRule::family;
    std::tie(options.albedos, options.radii) = parse_grid(o.size, 4, 2048, 4, 2048, "64x48 (ALBEDOSxRADII)");
  } else if (o.layout == "adaptive") {
    options.layout = AlbedoRadiusLayoutRule::adaptive;
    if (!o.table_tolerance.empty()) options.table_tolerance = positive_fraction(o.table_tolerance, "--table-tolerance");
    options.table.progress = progress_bar("adaptive albedo-radius layout");  // on a terminal: minutes at 1e-3
  } else {
    throw InvalidInput("--layout", "'" + o.layout + "'",
                       "pbrt, family (with --size AxR) or adaptive (with --table-tolerance)");
  }
  BuiltTable built = tabulate_albedo_radius(options);
  if (!note.empty()) built.summary = note + "\n" + built.summary;
  if (!g_choice.empty()) {
    built.summary = g_choice + "\n" + built.summary;
    built.table.set("bssrdf:g_choice", g_choice);
  }
  return built;
}

BuiltTable build_transmission(const LutOptions& o) {
  if (!o.accuracy.empty())
    throw InvalidInput("--accuracy: only with --model auto (transmission tables use adding-doubling or the multipole)");
  const auto resolved = o.medium.resolve();
  // With --colour (with --all: for the spectral materials), each wavelength's slab integrated per thickness to R, G, B.
  const auto colour = o.all && !resolved.medium.spectral() ? std::nullopt : o.colour.resolve(resolved.medium);
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
  return tabulate_transmission({resolved.material, &resolved.medium, nullptr, resolved.unit}, thickness, options,
                               colour);
}

BuiltTable build_preintegrated(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const TableContext& context) {
    PreintegratedKindOptions options;
    parse_size(o.size, options.table.width, options.table.height);
    if (!o.curvature_max.empty()) {
      const double c = parse_number(o.curvature_max, "--curvature-max");
      if (!(c > 0))
        throw InvalidInput("--curvature-max", format_number(c), "> 0 (1/" + std::string(symbol(resolved.unit)) + ")");
      options.table.curvature_max = c / millimetres_per(resolved.unit);
    }
    options.table.threads = o.threads;
    options.image = image_check(o, resolved.unit);
    options.size_given = o.size_given;  // --size and --curvature-max override --tolerance
    options.curvature_given = !o.curvature_max.empty();
    return tabulate_preintegrated(context, options);
  });
}

BuiltTable build_penumbra(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const TableContext& context) {
    PenumbraOptions options;
    parse_size(o.size, options.width, options.height);
    if (!o.width_max.empty()) options.width_max = positive_length_mm(o.width_max, "--width-max", resolved.unit);
    options.threads = o.threads;
    return tabulate_penumbra(context, options);
  });
}

BuiltTable build_separable(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const TableContext& context) {
    SeparableKindOptions options;
    auto& kernel = options.kernel;
    if (o.taps != 0) kernel.taps = o.taps;
    if (o.range == "jimenez") {
      kernel.range = jimenez_range(kernel.taps);
    } else if (!o.range.empty()) {
      kernel.range = positive_length_mm(o.range, "--range", resolved.unit);
    }
    if (!o.band.empty()) kernel.band = positive_fraction(o.band, "--band");
    if (kernel.taps < 3 || kernel.taps % 2 == 0 || kernel.taps > 255)
      throw InvalidInput("--taps", std::to_string(kernel.taps), "an odd number from 3 to 255 (Jimenez: 11, 17, 25)");
    options.image = image_check(o, resolved.unit);
    options.kernel_given = o.taps_given || o.range_given;  // --taps or --range override --tolerance
    return tabulate_separable(context, options);
  });
}

BuiltTable build_gaussians(const LutOptions& o) {
  return with_model(o, [&](const MediumOptions::Resolved& resolved, const TableContext& context) {
    GaussiansKindOptions options;
    options.count = o.count;  // 0 unless --count (1 to 32) overrides --tolerance
    options.image = image_check(o, resolved.unit);
    return tabulate_gaussians(context, options);
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
