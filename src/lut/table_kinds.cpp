// The table kinds of `bssrdf lut`: options in, the library's table and summary out (table_kinds.hpp).
// In the fitting library: the Gaussian kind fits, and the image checks weigh fitted representations.
#include "bssrdf/lut/table_kinds.hpp"

#include <array>
#include <cmath>
#include <memory>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/image/realtime_tables.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "bssrdf/spectral/colour_transmission.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {
namespace {

// An ImageErrorCheck in force: the judge (the tabulated model's images, rendered once) and what it
// found, recorded in the table's metadata and summary.
struct ImageJudge {
  RealtimeJudge judge;
  ImageErrorCheck check;
};

std::optional<ImageJudge> judge_for(const TableContext& context, const std::optional<ImageErrorCheck>& check) {
  if (!check) return std::nullopt;
  // A colour table is judged against its colour model (each wavelength's profile integrated), held by the caller for
  // the table's lifetime: borrowed, not owned.
  const auto reference =
      context.colour
          ? ModelReference(std::shared_ptr<const Model>(std::shared_ptr<const Model>(), context.model), false)
          : ModelReference(make_model(context.model->name()));
  return ImageJudge{judge_against(*context.medium, reference, check->pixel), *check};
}

bool sized_by_image(const std::optional<ImageJudge>& j) { return j && j->check.tolerance; }

// What sized a table by the image tolerance, for its metadata and summary.
std::string sized_note(const ImageJudge& j, bool meets, const std::string& what) {
  return what + (meets ? " chosen for" : " (the most accurate tried: none meets") + " --tolerance " +
         format_number(*j.check.tolerance) + " code values" + (meets ? "" : ")");
}

// Records the table's image error (metadata and a summary line).
void record_image_error(BuiltTable& b, const ImageJudge& j, const ImageError& e, const Model& model,
                        const std::string& sized) {
  const double pixel = j.check.pixel;
  b.table.set("bssrdf:image_error", e.error);
  b.table.set("bssrdf:image_error_pixel_mm", pixel);
  b.table.set("bssrdf:image_error_definition",
              "largest 8-bit sRGB code-value difference between this table and the model " + model.name() +
                  " it tabulates at a shadow edge, a one-pixel light line and a flat lit region, pixels of " +
                  format_number(pixel) +
                  " mm (bssrdf advise; the model's own error against the truth is not included)");
  if (!sized.empty()) b.table.set("bssrdf:sized_by", sized);
  b.summary += "  image error at " + format_number(pixel) +
               " mm pixels: " + format_number(std::round(e.error * 1000) / 1000) + " code values against " +
               model.name() + " (worst at the " + e.pattern + ")" + (sized.empty() ? "" : "; " + sized) + "\n";
}

// The context of a profile kind: a medium and a model.
void check_profile_context(const TableContext& context) {
  BSSRDF_CHECK(context.medium != nullptr);
  BSSRDF_CHECK(context.model != nullptr);
}

}  // namespace

BuiltTable tabulate_radial(const TableContext& context, const RadialKindOptions& o) {
  check_profile_context(context);
  const auto& medium = *context.medium;
  const auto& model = *context.model;
  RadialTableOptions options = o.table;
  const auto judge = judge_for(context, o.image);
  std::string sized;
  if (sized_by_image(judge)) {
    const auto choice = choose_radial_tolerance(medium, model, judge->judge, *o.image->tolerance, options);
    options.tolerance = choice.relative_tolerance;
    sized = sized_note(*judge, choice.meets_tolerance,
                       "relative interpolation tolerance " + format_number(choice.relative_tolerance));
  }
  const auto t = build_radial_table(medium, model, options);
  BuiltTable b{to_lookup_table(t, context), summary(t, context), {}};
  if (judge) record_image_error(b, *judge, image_error_of(judge->judge, t), model, sized);
  return b;
}

BuiltTable tabulate_reference_radial(const TableContext& context, const ReferenceRadialOptions& options) {
  BSSRDF_CHECK(context.medium != nullptr);
  return tabulate_reference_radial(LayerStack::half_space(*context.medium), "", context, options);
}

BuiltTable tabulate_reference_radial(const LayerStack& stack, const std::string& source, const TableContext& context,
                                     const ReferenceRadialOptions& options) {
  const auto t = build_reference_radial_table(stack, options);
  TableContext described = context;
  if (options.colour)
    described.colour = reference_table_colour(t, spectral::wavelengths_from_channel_names(stack.channel_names));
  auto table = to_lookup_table(t, described);
  if (!source.empty()) table.set("bssrdf:layers", source + " (" + std::to_string(stack.layers.size()) + " layers)");
  return {
      std::move(table), (options.colour ? "colour: " + described.colour->line + "\n" : "") + summary(t, described), {}};
}

std::string to_string(AlbedoRadiusLayoutRule layout) {
  static constexpr std::array<const char*, 3> kNames = {"pbrt", "family", "adaptive"};  // in the enum's order
  return kNames.at(static_cast<std::size_t>(layout));
}

BuiltTable tabulate_albedo_radius(const AlbedoRadiusKindOptions& o) {
  AlbedoRadiusLayout layout;
  std::string adaptive_note;
  switch (o.layout) {
    case AlbedoRadiusLayoutRule::pbrt:
      layout = AlbedoRadiusLayout::pbrt();
      break;
    case AlbedoRadiusLayoutRule::family:
      layout = AlbedoRadiusLayout::family(o.albedos, o.radii);
      break;
    case AlbedoRadiusLayoutRule::adaptive: {
      const auto adaptive = adaptive_albedo_radius_layout(o.g, o.eta, o.table_tolerance, o.table);
      layout = adaptive.layout;
      adaptive_note = summary(adaptive, o.table_tolerance);
      break;
    }
  }
  AlbedoRadiusOptions options = o.table;
  options.progress = nullptr;  // the search's, not the table's
  const auto t = build_albedo_radius_table(layout, o.g, o.eta, options);
  const auto model = make_model(o.table.shape == RowShape::exact ? "exact" : "pbd");
  const std::string layout_name = to_string(o.layout);
  auto table = to_lookup_table(t, {o.material, nullptr, model.get(), LengthUnit::millimetre}, layout_name);
  auto lines = summary(t, layout_name);
  if (!adaptive_note.empty()) {
    lines += "  " + adaptive_note + "\n";
    table.set("bssrdf:adaptive", adaptive_note);
  }
  return {std::move(table), lines, {}};
}

BuiltTable tabulate_transmission(const TableContext& context, std::vector<double> thickness_mm,
                                 const TransmissionTableOptions& options,
                                 const std::optional<spectral::ColourSettings>& colour) {
  BSSRDF_CHECK(context.medium != nullptr);
  auto t = build_transmission_table(*context.medium, std::move(thickness_mm), options);
  const multipole::Model model(1.0);
  TableContext described = context;
  described.model = &model;
  if (colour) {
    if (!context.medium->spectral())
      throw InvalidInput("colour: needs a spectral medium (--wavelengths, or a material with wavelengths)");
    const spectral::ColourIntegrator integrator(context.medium->wavelength_nm, *colour);
    t = spectral::colour_transmission(t, integrator);
    described.colour = TableColour{spectral::colour_note(integrator.wavelengths(), *colour),
                                   spectral::colour_transmission_line(t, integrator)};
  }
  auto table = to_lookup_table(t, described);  // throws when nothing is left
  const bool exact = options.model == "adding-doubling" && !options.reference_everywhere;
  // The model that produced the rows (the multipole above only describes the table's medium).
  table.set("bssrdf:model", options.reference_everywhere ? std::string("monte carlo") : options.model);
  if (exact) table.set("bssrdf:includes_single_scattering", std::string("yes"));
  table.set("bssrdf:model_description",
            exact ? std::string("total transmittance of slabs: adding-doubling (exact)")
                  : std::string("total transmittance of slabs: multipole (Donner & Jensen 2005) where valid") +
                        (options.reference || options.reference_everywhere ? ", Monte Carlo reference elsewhere" : ""));
  return {std::move(table), (colour ? "colour: " + described.colour->line + "\n" : "") + summary(t, described), {}};
}

BuiltTable tabulate_preintegrated(const TableContext& context, const PreintegratedKindOptions& o) {
  check_profile_context(context);
  const auto& medium = *context.medium;
  PreintegratedOptions options = o.table;
  const auto judge = judge_for(context, o.image);
  const auto projections = project_channels(medium, *context.model);
  std::string sized;
  if (sized_by_image(judge) && !o.size_given) {
    const auto choice = choose_preintegrated_table(medium, projections, judge->judge, *o.image->tolerance, false);
    options.width = options.height = choice.size;
    if (!o.curvature_given) options.curvature_max = choice.curvature_max;
    sized = sized_note(*judge, choice.meets_tolerance,
                       "size " + std::to_string(choice.size) + "x" + std::to_string(choice.size));
  }
  const auto t = build_preintegrated_table(medium, projections, options);
  BuiltTable b{to_lookup_table(t, context), summary(t, context), {}};
  if (judge) record_image_error(b, *judge, image_error_of(judge->judge, t, medium, projections), *context.model, sized);
  return b;
}

BuiltTable tabulate_penumbra(const TableContext& context, const PenumbraOptions& options) {
  check_profile_context(context);
  const auto t = build_penumbra_table(*context.medium, *context.model, options);
  return {to_lookup_table(t, context), summary(t, context), {}};
}

BuiltTable tabulate_separable(const TableContext& context, const SeparableKindOptions& o) {
  check_profile_context(context);
  const auto& medium = *context.medium;
  SeparableKernelOptions options = o.kernel;
  const auto judge = judge_for(context, o.image);
  const auto projections = project_channels(medium, *context.model);
  std::string sized;
  if (sized_by_image(judge) && !o.kernel_given) {
    const auto choice = choose_separable_kernel(medium, projections, judge->judge, *o.image->tolerance);
    options = choice.options;
    sized = sized_note(*judge, choice.meets_tolerance,
                       std::to_string(options.taps) + " taps and the range holding " +
                           short_number(100 * options.band) + " % of the light");
  }
  const auto k = build_separable_kernel(medium, projections, options);
  BuiltTable b{to_lookup_table(k, context), summary(k, context), {}};
  if (judge) record_image_error(b, *judge, image_error_of(judge->judge, k), *context.model, sized);
  for (const auto language : {ShaderLanguage::glsl, ShaderLanguage::hlsl}) {
    const std::string name = language == ShaderLanguage::glsl ? "glsl" : "hlsl";
    try {
      b.other_formats[name] = [text = to_shader(k, context, language)] { return text; };
    } catch (const InvalidInput& e) {  // e.g. not three channels: an error only when that format is asked for
      b.other_formats[name] = [e]() -> std::string { throw InvalidInput("format", e.value(), e.accepted()); };
    }
  }
  return b;
}

BuiltTable tabulate_gaussians(const TableContext& context, const GaussiansKindOptions& o) {
  check_profile_context(context);
  const auto& medium = *context.medium;
  const auto& model = *context.model;
  if (o.count < 0 || o.count > 32)
    throw InvalidInput("count", std::to_string(o.count), "1 to 32 (0: chosen, the model's own or 6)");
  GaussianMixtureTable t;
  const auto judge = judge_for(context, o.image);
  std::string sized;
  if (sized_by_image(judge) && o.count == 0) {
    const auto choice = choose_gaussian_count(medium, model, judge->judge, *o.image->tolerance);
    t = fitted_mixture_table(medium, model, static_cast<int>(choice.count), kGaussianFitSamples);  // as judged
    sized = sized_note(*judge, choice.meets_tolerance, std::to_string(choice.count) + " Gaussians");
  } else if (o.count == 0 && model_entry(model.name()).own_gaussians) {
    t = own_mixture_table(medium, model);
  } else {
    t = fitted_mixture_table(medium, model, o.count == 0 ? 6 : o.count);
  }
  BuiltTable b{to_lookup_table(t, context), summary(t, context), {}};
  if (judge) record_image_error(b, *judge, image_error_of(judge->judge, t), model, sized);
  return b;
}

}  // namespace bssrdf
