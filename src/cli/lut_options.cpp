// Option parsing shared by the kinds of `bssrdf lut` (--size, fractions, lengths, --pixel and
// --tolerance) and the --preview image; declared in lut_kinds.hpp.
#include <cmath>

#include <filesystem>
#include <tuple>

#include "bssrdf/error.hpp"
#include "bssrdf/io/png_image.hpp"
#include "bssrdf/lut/material_preview.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "lut_kinds.hpp"

namespace bssrdf::cli {

// "WxH" with each side a count in its range (parsed as signed: "-1x10" is refused, not wrapped).
std::pair<std::size_t, std::size_t> parse_grid(const std::string& text, std::int64_t min_w, std::int64_t max_w,
                                               std::int64_t min_h, std::int64_t max_h, const std::string& example) {
  const auto x = text.find('x');
  const std::string accepted = "WIDTHxHEIGHT, width " + count_range(min_w, max_w) + ", height " +
                               count_range(min_h, max_h) + ", e.g. " + example;
  if (x == std::string::npos) throw InvalidInput("--size", "'" + text + "'", accepted);
  try {
    return {static_cast<std::size_t>(parse_count(text.substr(0, x), "--size", min_w, max_w)),
            static_cast<std::size_t>(parse_count(text.substr(x + 1), "--size", min_h, max_h))};
  } catch (const InvalidInput&) {
    throw InvalidInput("--size", "'" + text + "'", accepted);
  }
}

void parse_size(const std::string& text, std::size_t& width, std::size_t& height) {
  if (!text.empty()) std::tie(width, height) = parse_grid(text, 2, 8192, 1, 8192, "256x256");
}

double positive_fraction(const std::string& text, const std::string& field) {
  const double v = parse_number(text, field);
  if (!(v > 0 && v < 1)) throw InvalidInput(field, format_number(v), "0 < value < 1");
  return v;
}

// A length option in --unit, > 0, as mm.
double positive_length_mm(const std::string& text, const std::string& field, LengthUnit unit) {
  const double v = parse_length(text, field);
  if (!(v > 0)) throw InvalidInput(field, format_number(v), "> 0 (" + std::string(symbol(unit)) + ")");
  return v * millimetres_per(unit);
}

std::optional<ImageErrorCheck> image_check(const LutOptions& o, LengthUnit unit) {
  if (o.pixel.empty()) {
    if (!o.tolerance.empty() && (o.kind == "separable" || o.kind == "preintegrated" || o.kind == "gaussians"))
      throw InvalidInput(
          "--tolerance", o.tolerance,
          "a value only with --pixel for --kind " + o.kind + " (an image error, 8-bit sRGB code values)");
    return std::nullopt;
  }
  ImageErrorCheck check;
  check.pixel = parse_length(o.pixel, "--pixel") * millimetres_per(unit);
  if (!(check.pixel > 0) || !std::isfinite(check.pixel))
    throw InvalidInput("--pixel", o.pixel, "a pixel size > 0 in --unit");
  if (!o.tolerance.empty()) {
    check.tolerance = parse_number(o.tolerance, "--tolerance");
    if (!(*check.tolerance > 0) || !std::isfinite(*check.tolerance))
      throw InvalidInput("--tolerance", o.tolerance, "> 0 (8-bit sRGB code values, with --pixel)");
  }
  return check;
}

RenderedPreview render_preview(const LutOptions& o, const MediumOptions::Resolved& resolved) {
  if (std::filesystem::path(o.preview).extension() != ".png")
    throw InvalidInput("--preview", "'" + o.preview + "'", "a file ending in .png");
  // Transmission tables name no profile model: the preview then shows the registry's default.
  const bool own_model = o.kind == "transmission" || !o.model_given;
  const auto model =
      make_model(resolve_model(own_model ? "" : o.model, own_model ? "" : o.accuracy, resolved.medium).name);
  PreviewOptions options;
  options.unit = resolved.unit;
  options.label = (resolved.material ? resolved.material->name : std::string("custom medium")) + ", " + model->name();
  // A preview is an sRGB image: a spectral medium shows its colour in linear sRGB under --illuminant (D65 unless
  // given), whatever --colour the table is in; each wavelength's exact profile, summed with the colour weights.
  std::string colour;
  if (resolved.medium.spectral()) {
    const auto settings = o.colour.resolve(resolved.medium).value_or(spectral::ColourSettings{});
    const spectral::ColourIntegrator integrator(resolved.medium.wavelength_nm,
                                                {settings.illuminant, spectral::ColourSpace::srgb});
    options.display_weights = integrator.rgb_weights();
    colour = "; colour: " + spectral::describe(spectral::colour_note(integrator.wavelengths(), integrator.settings()));
  }
  const auto preview = render_material_preview(resolved.medium, *model, options);
  const std::string u(symbol(resolved.unit));
  RenderedPreview out;
  out.description = std::to_string(preview.image.width) + " x " + std::to_string(preview.image.height) +
                    " px; shadow edge at the centre, +-" + short_number(from_mm(preview.half_width, resolved.unit)) +
                    ' ' + u + ", ticks every " + short_number(from_mm(preview.tick, resolved.unit)) + ' ' + u + "; " +
                    model->name() + colour;
  if (preview.clipped_columns > 0) {
    std::string channels;
    for (int k = 0; k < 3; ++k)
      if (preview.clipped_channel[k]) channels += std::string(channels.empty() ? "" : ", ") + "RGB"[k];
    out.warning = "preview: " + channels + " outside linear sRGB's gamut in " +
                  std::to_string(preview.clipped_columns) + " of " + std::to_string(preview.image.width) +
                  " columns (a colour sRGB cannot show), clipped to [0, 1] in the image only; tables keep the values";
  }
  std::vector<std::pair<std::string, std::string>> text{{"Software", std::string("bssrdf ") + BSSRDF_VERSION},
                                                        {"Description", out.description}};
  if (!out.warning.empty()) text.emplace_back("Warning", out.warning);
  out.png = encode_png(preview.image, text);
  return out;
}

}  // namespace bssrdf::cli
