// bssrdf lut: lookup tables for renderers (radial, albedo-radius, transmission, pre-integrated,
// separable kernel, Gaussian mixture) as OpenEXR, JSON, CSV or shader arrays; --all for the whole
// materials database, one file per material.
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <map>
#include <optional>
#include <sstream>

#include "bssrdf/advise/realtime_tables.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/exr_table.hpp"
#include "bssrdf/lut/albedo_radius_table.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/lut/material_preview.hpp"
#include "bssrdf/lut/penumbra_table.hpp"
#include "bssrdf/lut/preintegrated_table.hpp"
#include "bssrdf/lut/reference_radial_table.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/lut/separable_kernel.hpp"
#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/profile.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bssrdf::cli {
namespace {

struct LutOptions {
  MediumOptions medium;
  std::string kind = "radial", model = "pbd", accuracy, tolerance, energy = "0.999", interpolation = "catmull-rom";
  std::string output, format, output_dir, layout = "pbrt", size, table_tolerance;
  bool half = false, all = false, quiet = false;
  unsigned threads = 1;
  bool model_given = false;    // --model appeared on the command line
  bool photons_given = false;  // --photons appeared on the command line
  // transmission
  std::string thickness, d_min, d_max;
  int samples = 32;
  bool reference = false, reference_everywhere = false;
  std::string layers;  // radial --reference: a layer stack file instead of a medium
  std::uint64_t photons = 100'000, seed = 1;
  // preintegrated, penumbra
  std::string curvature_max, width_max;
  // separable
  int taps = 17;
  std::string range, band = "0.95";
  // gaussians
  int count = 0;  // 0: quantized diffusion's own mixture with --model quantized, else 6
  std::string preview;  // PNG file
  // --pixel: how wrong the table looks at that pixel size (with --tolerance: sized by it)
  std::string pixel;
  bool taps_given = false, range_given = false, size_given = false, count_given = false;
};

// --pixel [--tolerance]: the image-space judge of the tabulated model (advise/realtime_tables.hpp),
// the tolerance in code values (nullopt: none given), and what a table records about its error.
struct PixelJudge {
  RealtimeJudge judge;
  double pixel = 0;  // mm
  std::optional<double> tolerance;
};

std::optional<PixelJudge> pixel_judge(const LutOptions& o, const MediumOptions::Resolved& resolved, const Model& model) {
  if (o.pixel.empty()) {
    if (!o.tolerance.empty() && (o.kind == "separable" || o.kind == "preintegrated" || o.kind == "gaussians"))
      throw InvalidInput("--tolerance", o.tolerance, "a value only with --pixel for --kind " + o.kind + " (an image error, 8-bit sRGB code values)");
    return std::nullopt;
  }
  const double pixel = parse_length(o.pixel, "--pixel") * millimetres_per(resolved.unit);
  if (!(pixel > 0) || !std::isfinite(pixel)) throw InvalidInput("--pixel", o.pixel, "a pixel size > 0 in --unit");
  std::optional<double> tolerance;
  if (!o.tolerance.empty()) {
    tolerance = parse_number(o.tolerance, "--tolerance");
    if (!(*tolerance > 0) || !std::isfinite(*tolerance)) throw InvalidInput("--tolerance", o.tolerance, "> 0 (8-bit sRGB code values, with --pixel)");
  }
  return PixelJudge{judge_against(resolved.medium, ModelReference(make_model(model.name())), pixel), pixel, tolerance};
}

// Records the table's image error (metadata and a summary line).
void record_image_error(LookupTable& table, std::string& summary, const PixelJudge& j, const ImageError& e, const Model& model,
                        const std::string& sized) {
  table.set("bssrdf:image_error", e.error);
  table.set("bssrdf:image_error_pixel_mm", j.pixel);
  table.set("bssrdf:image_error_definition",
            "largest 8-bit sRGB code-value difference between this table and the model " + model.name() +
                " it tabulates at a shadow edge, a one-pixel light line and a flat lit region, pixels of " + format_number(j.pixel) +
                " mm (bssrdf advise; the model's own error against the truth is not included)");
  if (!sized.empty()) table.set("bssrdf:sized_by", sized);
  summary += "  image error at " + format_number(j.pixel) + " mm pixels: " + format_number(std::round(e.error * 1000) / 1000) +
             " code values against " + model.name() + " (worst at the " + e.pattern + ")" + (sized.empty() ? "" : "; " + sized) + "\n";
}

std::string sized_note(const std::optional<double>& tolerance, bool meets, const std::string& what) {
  return what + (meets ? " chosen for" : " (the most accurate tried: none meets") + " --tolerance " + format_number(*tolerance) +
         " code values" + (meets ? "" : ")");
}

const std::vector<std::string>& kinds() {
  static const std::vector<std::string> k = {"radial", "albedo-radius", "transmission", "preintegrated", "penumbra", "separable", "gaussians"};
  return k;
}

// "WxH" with each side a count in its range (parsed as signed: "-1x10" is refused, not wrapped).
std::pair<std::size_t, std::size_t> parse_grid(const std::string& text, std::int64_t min_w, std::int64_t max_w,
                                               std::int64_t min_h, std::int64_t max_h, const std::string& example) {
  const auto x = text.find('x');
  const std::string accepted = "WIDTHxHEIGHT, width " + count_range(min_w, max_w) + ", height " + count_range(min_h, max_h) +
                               ", e.g. " + example;
  if (x == std::string::npos) throw InvalidInput("--size", "'" + text + "'", accepted);
  try {
    return {static_cast<std::size_t>(parse_count(text.substr(0, x), "--size", min_w, max_w)),
            static_cast<std::size_t>(parse_count(text.substr(x + 1), "--size", min_h, max_h))};
  } catch (const InvalidInput&) {
    throw InvalidInput("--size", "'" + text + "'", accepted);
  }
}

double positive_fraction(const std::string& text, const std::string& field) {
  const double v = parse_number(text, field);
  if (!(v > 0 && v < 1)) throw InvalidInput(field, format_number(v), "0 < value < 1");
  return v;
}

// Four significant digits, for the lines people read (the files keep full precision).
std::string short_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

// The table and a few lines for people about it.
struct Built {
  LookupTable table;
  std::string summary;
  std::map<std::string, std::string> other_formats;  // e.g. "glsl", "hlsl" for kernels
};

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
  if (o.model != "pbd") throw InvalidInput("--model", "'" + o.model + "'", "pbd for --kind albedo-radius (photon beam diffusion, as pbrt)");
  AlbedoRadiusOptions options;
  // 1e-2: 8-point quadrature, worst cell error ~1e-2 against the converged model (pbrt's scheme: ~0.2).
  options.tolerance = o.tolerance.empty() ? 1e-2 : positive_fraction(o.tolerance, "--tolerance");
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
    const double table_tolerance = o.table_tolerance.empty() ? 1e-3 : positive_fraction(o.table_tolerance, "--table-tolerance");
    AlbedoRadiusOptions search = options;
    search.progress = progress_bar("adaptive albedo-radius layout");  // on a terminal: minutes at 1e-3
    const auto adaptive = adaptive_albedo_radius_layout(g, eta, table_tolerance, search);
    layout = adaptive.layout;
    adaptive_note = "adaptive layout for interpolation tolerance " + format_number(table_tolerance) + ": worst midpoint error " +
                    format_number(std::round(adaptive.albedo_error * 1e6) / 1e6) + " (albedo), " +
                    format_number(std::round(adaptive.radius_error * 1e6) / 1e6) + " (radius), relative to each row's peak";
  } else {
    throw InvalidInput("--layout", "'" + o.layout + "'", "pbrt, family (with --size AxR) or adaptive (with --table-tolerance)");
  }
  const auto start = std::chrono::steady_clock::now();
  const auto t = build_albedo_radius_table(layout, g, eta, options);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  auto model = make_model("pbd");
  TableContext context{material, nullptr, model.get(), LengthUnit::millimetre};
  std::ostringstream s;
  s << "albedo-radius table (" << o.layout << " layout): " << t.rows() << " albedos x " << t.columns()
    << " radii, g = " << format_number(g) << ", eta = " << format_number(eta) << ", photon beam diffusion with "
    << t.quadrature_order << "-point Gauss-Legendre (tolerance " << format_number(options.tolerance) << "); table in "
    << format_number(std::round(ms * 100) / 100) << " ms\n  effective albedo: " << format_number(t.effective_albedo.front())
    << " (rho = 0) to " << format_number(t.effective_albedo.back()) << " (rho = 1)\n";
  auto table = to_lookup_table(t, context, o.layout);
  if (!adaptive_note.empty()) {
    s << "  " << adaptive_note << "\n";
    table.set("bssrdf:adaptive", adaptive_note);
  }
  return {std::move(table), s.str(), {}};
}

// Thicknesses in mm: --thickness, or --samples log-spaced from --d-min to --d-max (defaults: half
// the smallest transport mfp to 40 of the largest, so thin slabs are covered too).
std::vector<double> thicknesses_mm(const LutOptions& o, const MediumOptions::Resolved& resolved) {
  const double mm = millimetres_per(resolved.unit);
  std::vector<double> out;
  if (!o.thickness.empty()) {
    if (!o.d_min.empty() || !o.d_max.empty()) throw InvalidInput("--thickness: give either --thickness or --d-min/--d-max");
    for (double d : parse_length_list(o.thickness, "--thickness")) {
      if (!(d > 0)) throw InvalidInput("--thickness", format_number(d), "> 0");
      out.push_back(d * mm);
    }
    return out;
  }
  double ell_min = 1e300, ell_max = 0;
  for (std::size_t c = 0; c < resolved.medium.channels(); ++c) {
    ell_min = std::min(ell_min, resolved.medium.reduced(c).ell);
    ell_max = std::max(ell_max, resolved.medium.reduced(c).ell);
  }
  const double a = o.d_min.empty() ? 0.5 * ell_min : parse_length(o.d_min, "--d-min") * mm;
  const double b = o.d_max.empty() ? 40 * ell_max : parse_length(o.d_max, "--d-max") * mm;
  if (!(a > 0)) throw InvalidInput("--d-min", format_number(a / mm), "> 0");
  if (!(b > a)) throw InvalidInput("--d-max", format_number(b / mm), "> --d-min = " + format_number(a / mm));
  if (o.samples < 2 || o.samples > 4096) throw InvalidInput("--samples", std::to_string(o.samples), "2 to 4096");
  return log_spaced(a, b, static_cast<std::size_t>(o.samples));
}

Built build_transmission(const LutOptions& o, const MediumOptions::Resolved& resolved) {
  if (o.model_given && o.model != "multipole" && o.model != "adding-doubling")
    throw InvalidInput("--model", "'" + o.model + "'", "adding-doubling (default) or multipole for --kind transmission (or --reference for Monte Carlo)");
  TransmissionTableOptions options;
  options.model = o.model_given ? o.model : "adding-doubling";
  if (options.model == "adding-doubling" && o.reference && !o.reference_everywhere)
    throw InvalidInput("--reference", "given", "--model multipole (adding-doubling is exact at every thickness; --reference-everywhere runs Monte Carlo)");
  options.reference = o.reference;
  options.reference_everywhere = o.reference_everywhere;
  options.photons = o.photons;
  options.seed = o.seed;
  options.threads = o.threads;
  const auto t = build_transmission_table(resolved.medium, thicknesses_mm(o, resolved), options);
  const multipole::Model model(1.0);
  TableContext context{resolved.material, &resolved.medium, &model, resolved.unit};
  auto table = to_lookup_table(t, context);  // throws when nothing is left
  table.set("bssrdf:model_description",
            options.model == "adding-doubling" && !o.reference_everywhere
                ? std::string("total transmittance of slabs: adding-doubling (exact)")
                : std::string("total transmittance of slabs: multipole (Donner & Jensen 2005) where valid") +
                      (o.reference || o.reference_everywhere ? ", Monte Carlo reference elsewhere" : ""));
  const double mm = millimetres_per(resolved.unit);
  const std::string u(symbol(resolved.unit));
  std::ostringstream s;
  std::size_t mc = 0;
  for (auto x : t.source) mc += x == TransmissionSource::monte_carlo;
  s << "transmission table: " << t.size() << " thicknesses from " << short_number(t.thickness.front() / mm) << " to "
    << short_number(t.thickness.back() / mm) << ' ' << u << " (" << t.size() - mc << (options.model == "adding-doubling" ? " adding-doubling, " : " multipole, ") << mc
    << " Monte Carlo with " << o.photons << " photons per channel";
  if (mc) s << ", " << format_number(std::round(t.monte_carlo_seconds * 100) / 100) << " s";
  s << "); diffuse T per entered flux, ballistic excluded\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    s << "  " << t.channel_names[c] << ": T = " << short_number(t.transmittance[c].front()) << " at "
      << short_number(t.thickness.front() / mm) << ' ' << u << ", " << short_number(t.transmittance[c].back()) << " at "
      << short_number(t.thickness.back() / mm) << ' ' << u << '\n';
  if (!t.omitted_thickness.empty()) {
    s << "  omitted " << t.omitted_thickness.size() << " thicknesses where the multipole is invalid (recorded in bssrdf:omitted; --reference fills them):";
    for (std::size_t i = 0; i < t.omitted_thickness.size(); ++i) s << ' ' << short_number(t.omitted_thickness[i] / mm);
    s << ' ' << u << '\n';
  }
  return {std::move(table), s.str(), {}};
}

// "WxH", each >= 1 (width >= 2).
std::pair<std::size_t, std::size_t> parse_size(const std::string& text, std::size_t width, std::size_t height) {
  if (text.empty()) return {width, height};
  return parse_grid(text, 2, 8192, 1, 8192, "256x256");
}

Built build_preintegrated(const LutOptions& o, const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
  PreintegratedOptions options;
  std::tie(options.width, options.height) = parse_size(o.size, 256, 256);
  const double mm = millimetres_per(resolved.unit);
  if (!o.curvature_max.empty()) {
    const double c = parse_number(o.curvature_max, "--curvature-max");
    if (!(c > 0)) throw InvalidInput("--curvature-max", format_number(c), "> 0 (1/" + std::string(symbol(resolved.unit)) + ")");
    options.curvature_max = c / mm;
  }
  options.threads = o.threads;
  const auto judge = pixel_judge(o, resolved, model);
  const auto projections = project_channels(resolved.medium, model);
  std::string sized;
  if (judge && judge->tolerance && !o.size_given) {  // --size overrides
    const auto choice = choose_preintegrated_table(resolved.medium, projections, judge->judge, *judge->tolerance, false);
    options.width = options.height = choice.size;
    if (o.curvature_max.empty()) options.curvature_max = choice.curvature_max;
    sized = sized_note(judge->tolerance, choice.meets_tolerance, "size " + std::to_string(choice.size) + "x" + std::to_string(choice.size));
  }
  const auto t = build_preintegrated_table(resolved.medium, projections, options);
  const std::string u(symbol(resolved.unit));
  std::ostringstream s;
  s << "pre-integrated table: " << options.width << " N.L x " << options.height << " curvatures from 0 to "
    << short_number(t.options.curvature_max * mm) << " 1/" << u << " (sphere radius down to " << short_number(1 / (t.options.curvature_max * mm))
    << ' ' << u << ", the widest channel's r_50), texel centres\n";
  const std::size_t W = options.width, H = options.height;
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    s << "  " << t.channel_names[c] << ": D at N.L = " << short_number(t.n_dot_l[W / 2]) << ": "
      << short_number(t.value[c][W / 2]) << " (flattest row) to " << short_number(t.value[c][(H - 1) * W + W / 2])
      << " (most curved); at N.L = " << short_number(t.n_dot_l[0]) << ": " << short_number(t.value[c][0]) << " to "
      << short_number(t.value[c][(H - 1) * W]) << '\n';
  Built b{to_lookup_table(t, context), s.str(), {}};
  if (judge) record_image_error(b.table, b.summary, *judge, image_error_of(judge->judge, t, resolved.medium, projections), model, sized);
  return b;
}

Built build_penumbra(const LutOptions& o, const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
  PenumbraOptions options;
  std::tie(options.width, options.height) = parse_size(o.size, 256, 256);
  const double mm = millimetres_per(resolved.unit);
  const std::string u(symbol(resolved.unit));
  if (!o.width_max.empty()) {
    const double w = parse_length(o.width_max, "--width-max");
    if (!(w > 0)) throw InvalidInput("--width-max", format_number(w), "> 0 (" + u + ")");
    options.width_max = w * mm;
  }
  options.threads = o.threads;
  const auto t = build_penumbra_table(resolved.medium, model, options);
  std::ostringstream s;
  s << "penumbra table: " << options.width << " shadow values x " << options.height << " penumbra widths from 0 to "
    << short_number(t.options.width_max / mm) << ' ' << u << (o.width_max.empty() ? " (8 r_50 of the widest channel)" : "")
    << ", texel centres\n";
  const std::size_t W = options.width, H = options.height;
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    if (!t.scatters[c]) {
      s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): D = s\n";
      continue;
    }
    s << "  " << t.channel_names[c] << ": D at s = " << short_number(t.shadow[W / 8]) << ": " << short_number(t.value[c][W / 8])
      << " (narrowest penumbra) to " << short_number(t.value[c][(H - 1) * W + W / 8]) << " (widest)\n";
  }
  return {to_lookup_table(t, context), s.str(), {}};
}

Built build_separable(const LutOptions& o, const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
  SeparableKernelOptions options;
  options.taps = o.taps;
  const double mm = millimetres_per(resolved.unit);
  const std::string u(symbol(resolved.unit));
  if (o.range == "jimenez") {
    options.range = jimenez_range(o.taps);
  } else if (!o.range.empty()) {
    const double r = parse_length(o.range, "--range");
    if (!(r > 0)) throw InvalidInput("--range", format_number(r), "> 0 (" + u + ") or jimenez");
    options.range = r * mm;
  }
  options.band = positive_fraction(o.band, "--band");
  if (options.taps < 3 || options.taps % 2 == 0 || options.taps > 255)
    throw InvalidInput("--taps", std::to_string(options.taps), "an odd number from 3 to 255 (Jimenez: 11, 17, 25)");
  const auto judge = pixel_judge(o, resolved, model);
  const auto projections = project_channels(resolved.medium, model);
  std::string sized;
  if (judge && judge->tolerance && !o.taps_given && !o.range_given) {  // --taps or --range override
    const auto choice = choose_separable_kernel(resolved.medium, projections, judge->judge, *judge->tolerance);
    options = choice.options;
    sized = sized_note(judge->tolerance, choice.meets_tolerance, std::to_string(options.taps) + " taps and the range holding " +
                                                                     short_number(100 * options.band) + " % of the light");
  }
  const auto k = build_separable_kernel(resolved.medium, projections, options);
  std::ostringstream s;
  s << "separable kernel: " << options.taps << " taps over +-" << short_number(k.options.range / mm) << ' ' << u
    << (k.range_from_band ? " (the band holding " + short_number(100 * options.band) + " % of the widest channel's light)"
                          : o.range == "jimenez" ? std::string(" (Jimenez's range)") : std::string())
    << ", offsets warped quadratically, centre tap first\n";
  double worst = 1;
  for (std::size_t c = 0; c < k.channel_names.size(); ++c) {
    if (k.total_reflectance[c] == 0) {
      s << "  " << k.channel_names[c] << ": does not scatter (total reflectance 0): identity kernel, centre weight 1\n";
      continue;
    }
    s << "  " << k.channel_names[c] << ": centre weight " << short_number(k.weight[c][0]) << ", the band |x| < range holds "
      << short_number(100 * k.captured[c]) << " % of the total reflectance " << short_number(k.total_reflectance[c]) << '\n';
    worst = std::min(worst, k.captured[c]);
  }
  if (worst < 0.9)
    s << "  note: the range holds less than 90 % of a channel's light; a wider --range (e.g. "
      << short_number(1.5 * k.options.range / mm) << " " << u << ") keeps more of it\n";
  Built b{to_lookup_table(k, context), s.str(), {}};
  if (judge) record_image_error(b.table, b.summary, *judge, image_error_of(judge->judge, k), model, sized);
  b.other_formats["glsl"] = to_shader(k, context, ShaderLanguage::glsl);
  b.other_formats["hlsl"] = to_shader(k, context, ShaderLanguage::hlsl);
  return b;
}

Built build_gaussians(const LutOptions& o, const MediumOptions::Resolved& resolved, const Model& model, const TableContext& context) {
  GaussianMixtureTable t;
  const auto judge = pixel_judge(o, resolved, model);
  std::string sized;
  if (judge && judge->tolerance && !o.count_given) {  // --count overrides
    const auto choice = choose_gaussian_count(resolved.medium, model, judge->judge, *judge->tolerance);
    t = fitted_mixture_table(resolved.medium, model, static_cast<int>(choice.count), kGaussianFitSamples);  // as judged
    sized = sized_note(judge->tolerance, choice.meets_tolerance, std::to_string(choice.count) + " Gaussians");
  } else if (o.count == 0 && model.name() == "quantized") {
    t = quantized_mixture_table(resolved.medium, dynamic_cast<const quantized_diffusion::Model&>(model));
  } else {
    const int count = o.count == 0 ? 6 : o.count;
    if (count < 1 || count > 32) throw InvalidInput("--count", std::to_string(count), "1 to 32");
    t = fitted_mixture_table(resolved.medium, model, count);
  }
  const double mm = millimetres_per(resolved.unit);
  const std::string u(symbol(resolved.unit));
  std::ostringstream s;
  s << "Gaussian mixture: " << t.count() << " Gaussians (" << (t.shared_variance ? "shared" : "per-channel")
    << " variances) in " << short_number(t.seconds * 1000) << " ms; " << t.method << '\n';
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    if (t.total_reflectance[c] == 0) {
      s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): every weight 0\n";
      continue;
    }
    s << "  " << t.channel_names[c] << ": " << t.weight[c].size() << " Gaussians, variances "
      << short_number(t.variance[c].front() / (mm * mm)) << " to " << short_number(t.variance[c].back() / (mm * mm)) << ' ' << u
      << "^2; sum of weights / total reflectance - 1 = " << short_number(t.conservation_error[c]);
    if (t.shared_variance) s << "; relative L2 error " << short_number(t.relative_l2_error[c]);
    s << '\n';
  }
  Built b{to_lookup_table(t, context), s.str(), {}};
  if (judge) record_image_error(b.table, b.summary, *judge, image_error_of(judge->judge, t), model, sized);
  return b;
}

// The PNG preview (any kind; the model is --model where given, else pbd) and a line about it.
struct RenderedPreview {
  std::string png, description;
};
RenderedPreview render_preview(const LutOptions& o, const MediumOptions::Resolved& resolved) {
  if (std::filesystem::path(o.preview).extension() != ".png")
    throw InvalidInput("--preview", "'" + o.preview + "'", "a file ending in .png");
  const bool own_model = o.kind == "transmission" || o.kind == "albedo-radius" || !o.model_given;
  const auto model = make_model(own_model ? "pbd" : resolve_model(o.model, o.accuracy, resolved.medium).name);
  PreviewOptions options;
  options.unit = resolved.unit;
  options.label = (resolved.material ? resolved.material->name : std::string("custom medium")) + ", " + model->name();
  const auto preview = render_material_preview(resolved.medium, *model, options);
  const std::string u(symbol(resolved.unit));
  return {encode_png(preview.image), std::to_string(preview.image.width) + " x " + std::to_string(preview.image.height) +
                                         " px; shadow edge at the centre, +-" + short_number(from_mm(preview.half_width, resolved.unit)) +
                                         ' ' + u + ", ticks every " + short_number(from_mm(preview.tick, resolved.unit)) + ' ' + u +
                                         "; " + model->name()};
}

Built build_with(const LutOptions& o, const MediumOptions::Resolved& resolved, std::unique_ptr<Model> model) {
  const TableContext table_context{resolved.material, &resolved.medium, model.get(), resolved.unit};
  if (o.kind == "preintegrated") return build_preintegrated(o, resolved, *model, table_context);
  if (o.kind == "penumbra") return build_penumbra(o, resolved, *model, table_context);
  if (o.kind == "separable") return build_separable(o, resolved, *model, table_context);
  if (o.kind == "gaussians") return build_gaussians(o, resolved, *model, table_context);
  TableContext context{resolved.material, &resolved.medium, model.get(), resolved.unit};
  std::ostringstream s;
  const std::string u(symbol(resolved.unit));
  const double mm = millimetres_per(resolved.unit);
  if (o.kind == "radial") {
    RadialTableOptions options;
    // With --pixel, --tolerance is an image error (code values) and sizes the table through the
    // relative interpolation tolerance; without, it is that relative tolerance.
    const auto judge = pixel_judge(o, resolved, *model);
    options.tolerance = o.tolerance.empty() || judge ? 1e-3 : positive_fraction(o.tolerance, "--tolerance");
    options.energy = positive_fraction(o.energy, "--energy");
    options.interpolation = parse_interpolation(o.interpolation, "--interpolation");
    options.threads = o.threads;
    std::string sized;
    if (judge && judge->tolerance) {
      const auto choice = choose_radial_tolerance(resolved.medium, *model, judge->judge, *judge->tolerance, options);
      options.tolerance = choice.relative_tolerance;
      sized = sized_note(judge->tolerance, choice.meets_tolerance, "relative interpolation tolerance " + format_number(choice.relative_tolerance));
    }
    const auto t = build_radial_table(resolved.medium, *model, options);
    s << "radial table: " << t.size() << " radii from " << short_number(t.radius.front() / mm) << " to "
      << short_number(t.radius.back() / mm) << ' ' << u << ", uniform in ln r + r/" << short_number(t.decay_length / mm)
      << " (" << to_string(options.interpolation) << "; worst error " << short_number(t.max_error) << " <= tolerance " << short_number(options.tolerance)
      << " over the range holding " << short_number(options.energy) << " of each channel's total; " << t.evaluations << " model evaluations)\n";
    for (std::size_t c = 0; c < t.channel_names.size(); ++c)
      if (t.range_max[c] == 0)
        s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): R = 0, all of its CDF at r = 0\n";
      else
        s << "  " << t.channel_names[c] << ": total reflectance " << short_number(t.total_reflectance[c])
          << ", range " << short_number(t.range_min[c] / mm) << " to " << short_number(t.range_max[c] / mm) << ' ' << u << '\n';
    Built b{to_lookup_table(t, context), s.str(), {}};
    if (judge) record_image_error(b.table, b.summary, *judge, image_error_of(judge->judge, t), *model, sized);
    return b;
  }
  std::string known;
  for (const auto& k : kinds()) known += (known.empty() ? "" : ", ") + k;
  throw InvalidInput("--kind", "'" + o.kind + "'", "one of " + known);
}

std::string encode(const Built& built, const std::string& format, bool half) {
  const auto other = built.other_formats.find(format);
  if (other != built.other_formats.end()) return other->second;
  if (format == "exr") return encode_exr(built.table, half ? ExrPixelType::half : ExrPixelType::float32);
  if (format == "json") return to_json(built.table);
  if (format == "csv") return to_csv(built.table);
  if (format == "glsl" || format == "hlsl") throw InvalidInput("--format", "'" + format + "'", "exr, json or csv for --kind " + built.table.kind + " (glsl and hlsl: --kind separable)");
  throw InvalidInput("--format", "'" + format + "'", "exr, json, csv, or glsl/hlsl for --kind separable");
}

std::string format_for(const LutOptions& o, const std::string& path) {
  if (!o.format.empty()) return o.format;
  const auto ext = std::filesystem::path(path).extension().string();
  if (ext == ".exr") return "exr";
  if (ext == ".json") return "json";
  if (ext == ".csv") return "csv";
  if (ext == ".glsl") return "glsl";
  if (ext == ".hlsl") return "hlsl";
  throw InvalidInput("-o", "'" + path + "'", "a file ending in .exr, .json, .csv, .glsl or .hlsl (or give --format)");
}

// --kind radial --reference: the Monte Carlo reference tabulated, for a medium or a layer stack.
Built build_reference_radial(const LutOptions& o, const LayerStack& stack, const TableContext& context) {
  if (o.model_given || !o.accuracy.empty())
    throw InvalidInput("--reference: the table is the Monte Carlo reference, not a model (give no --model or --accuracy)");
  ReferenceRadialOptions options;
  options.photons = o.photons_given ? o.photons : 1'000'000;
  options.seed = o.seed;
  options.threads = o.threads;
  if (!o.all) options.progress = progress_bar("lut --reference");  // a terminal only; --all shows materials
  const auto t = build_reference_radial_table(stack, options);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  s << "radial table from the Monte Carlo reference: " << t.size() << " bins from " << short_number(t.r_outer.front() / mm) << " to "
    << short_number(t.r_outer.back() / mm) << ' ' << u << " (logarithmic), " << options.photons << " photons per channel, seed " << options.seed
    << "; values are bin averages with standard errors (stderr.<c>)\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    s << "  " << t.channel_names[c] << ": total reflectance " << short_number(t.total_reflectance[c]) << " +- "
      << short_number(t.total_stderr[c]) << ", " << short_number(100 * (t.total_reflectance[c] > 0 ? t.table_reflectance[c] / t.total_reflectance[c] : 1))
      << " % of it inside the table\n";
  auto table = to_lookup_table(t, context);
  if (!o.layers.empty()) table.set("bssrdf:layers", o.layers + " (" + std::to_string(stack.layers.size()) + " layers)");
  return {std::move(table), s.str(), {}};
}

// The table of --kind for the medium; --model auto is resolved here and says so in the summary.
Built build(const LutOptions& o, const MediumOptions::Resolved& resolved) {
  if (o.kind == "transmission") {
    if (!o.accuracy.empty()) throw InvalidInput("--accuracy: only with --model auto (transmission tables use adding-doubling or the multipole)");
    return build_transmission(o, resolved);
  }
  if (o.kind == "radial" && o.reference)
    return build_reference_radial(o, LayerStack::half_space(resolved.medium), {resolved.material, &resolved.medium, nullptr, resolved.unit});
  const auto chosen = resolve_model(o.model, o.accuracy, resolved.medium);
  auto built = build_with(o, resolved, make_model(chosen.name));
  if (!chosen.note.empty()) built.summary = chosen.note + "\n" + built.summary;
  return built;
}

// A material's name as a file-name stem: lower case, anything but letters and digits as '-'.
std::string file_stem(const std::string& material) {
  std::string name;
  for (char ch : material) name += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::tolower(ch)) : '-';
  return name;
}

std::string file_name(const std::string& material, const std::string& kind, const std::string& format) {
  return file_stem(material) + "-" + kind + "." + format;
}

}  // namespace

Action register_lut(CLI::App& app) {
  auto o = std::make_shared<LutOptions>();
  auto* sub = app.add_subcommand("lut", "Lookup tables for renderers: OpenEXR, JSON or CSV with their conventions recorded");
  o->medium.add_to(*sub);
  sub->add_option("--kind,-k", o->kind, "Table: radial, albedo-radius, transmission, preintegrated, penumbra, separable, gaussians [radial]");
  sub->add_option("--layout", o->layout,
                  "albedo-radius: pbrt (100 x 64, pbrt's spacing), family (--size) or adaptive (--table-tolerance) [pbrt]");
  sub->add_option("--table-tolerance", o->table_tolerance,
                  "albedo-radius --layout adaptive: interpolation error allowed, relative to each row's peak [1e-3]; "
                  "cost grows as 1/tolerance (each axis refined up to 2048 points; minutes at 1e-3, progress shown on a terminal)");
  sub->add_option("--size", o->size, "albedo-radius with --layout family: ALBEDOSxRADII, e.g. 64x48; preintegrated: N.LxCURVATURES; penumbra: SHADOWSxWIDTHS [256x256]");
  auto* model_option = sub->add_option("--model", o->model,
                                       "Profile model (see 'bssrdf models'), or auto: the cheapest measured within --accuracy of Monte Carlo here [pbd]");
  sub->add_option("--accuracy", o->accuracy, "With --model auto: relative error allowed in the total and in R(r) (L2) [0.1]");
  sub->add_option("--tolerance", o->tolerance,
                  "radial: relative interpolation error bound [1e-3]; albedo-radius: beam-integral quadrature tolerance [1e-2]; "
                  "with --pixel (radial, separable, preintegrated, gaussians): the largest image error, 8-bit sRGB code values, "
                  "that sizes the table (--taps/--range, --size, --count override)");
  sub->add_option("--pixel", o->pixel,
                  "radial, separable, preintegrated, gaussians: pixel size in --unit; the table records how wrong it looks there "
                  "(bssrdf:image_error, code values against the model it tabulates)");
  sub->add_option("--energy", o->energy, "Fraction of each channel's total inside the checked radius range [0.999]");
  sub->add_option("--interpolation", o->interpolation, "How the consumer interpolates: catmull-rom or linear [catmull-rom]");
  sub->add_option("-o,--output", o->output, "Output file: .exr, .json or .csv")->check(file_name("-o"));
  sub->add_option("--format,-f", o->format, "exr, json, csv; glsl or hlsl for separable [from the file's extension]");
  sub->add_flag("--half", o->half, "OpenEXR: half-float channels instead of float32");
  sub->add_flag("--all", o->all, "Every material of the database, one file per material in --output-dir");
  sub->add_option("--output-dir", o->output_dir, "Directory for --all [.]")->check(file_name("--output-dir"));
  add_count_option(*sub, "--threads", o->threads, 0, kMaxThreads, "Threads (0: all) [1]; results never depend on it");
  sub->add_flag("-q,--quiet", o->quiet, "Print nothing on stdout");
  sub->add_option("--thickness", o->thickness, "transmission: slab thicknesses in --unit, comma-separated");
  sub->add_option("--d-min", o->d_min, "transmission: smallest thickness [half the smallest transport mfp]");
  sub->add_option("--d-max", o->d_max, "transmission: largest thickness [40 of the largest transport mfp]");
  add_count_option(*sub, "--samples", o->samples, 2, 4096, "transmission: thicknesses, log-spaced from --d-min to --d-max [32]");
  sub->add_flag("--reference", o->reference,
                "radial: tabulate the Monte Carlo reference instead of a model (bins with standard errors; --photons, default 1e6); "
                "transmission: Monte Carlo where the multipole is invalid (else omitted)");
  sub->add_option("--layers", o->layers, "radial --reference: a layer stack file (bssrdf-layers JSON, as for 'bssrdf reference --layers')");
  sub->add_flag("--reference-everywhere", o->reference_everywhere, "transmission: Monte Carlo reference at every thickness");
  auto* photons_option = add_count_option(*sub, "--photons", o->photons, 1, kMaxPhotons,
                                         "Monte Carlo photons per channel: per thickness for transmission [100000], for radial --reference [1000000]");
  add_count_option(*sub, "--seed", o->seed, 0, kMaxSeed, "Monte Carlo seed (transmission --reference, radial --reference) [1]");
  sub->add_option("--preview", o->preview, "Also (or, without -o, only) write a PNG preview of the material: shadow-edge swatch + colour falloff")
      ->check(file_name("--preview"));
  add_count_option(*sub, "--taps", o->taps, 3, 255, "separable: number of taps, odd, >= 3 (Jimenez: 11, 17, 25) [17]");
  sub->add_option("--range", o->range,
                  "separable: kernel half-width in --unit, or jimenez (3 mm if taps > 20 else 2 mm) [the band holding --band of the widest channel's light]");
  sub->add_option("--band", o->band, "separable: fraction of the widest channel's light inside +-range when --range is not given [0.95]");
  add_count_option(*sub, "--count,-n", o->count, 1, 32, "gaussians: number of shared-variance Gaussians fitted [6; with --model quantized and no --count: its own mixture]");
  sub->add_option("--curvature-max", o->curvature_max, "preintegrated: largest curvature 1/r, in 1/--unit [1/r_50 of the widest channel]");
  sub->add_option("--width-max", o->width_max, "penumbra: widest penumbra, in --unit [8 r_50 of the widest channel]");

  return [o, model_option, photons_option, sub] {
    o->model_given = model_option->count() > 0;
    o->photons_given = photons_option->count() > 0;
    o->taps_given = sub->count("--taps") > 0;
    o->range_given = sub->count("--range") > 0;
    o->size_given = sub->count("--size") > 0;
    o->count_given = sub->count("--count") > 0;
    if (o->all) {
      if (!o->medium.material.empty() || !o->medium.sigma_a.empty())
        throw InvalidInput("--all: give no --material or coefficients with --all");
      const std::string format = o->format.empty() ? "exr" : o->format;
      const std::filesystem::path dir = o->output_dir.empty() ? "." : o->output_dir;
      if (!std::filesystem::is_directory(dir)) throw InvalidInput("--output-dir", "'" + dir.string() + "'", "an existing directory");
      const auto database = MaterialDatabase::load(o->medium.db.empty() ? default_materials_dir() : std::filesystem::path(o->medium.db));
      const auto progress = progress_bar("lut --all");
      const auto start = std::chrono::steady_clock::now();
      // Materials are built in parallel (--threads workers, each table single-threaded), then
      // written in database order, so files and messages do not depend on the thread count. A
      // material this kind cannot tabulate (e.g. a channel that does not scatter) is skipped with
      // its reason, one line each on stderr; the others are still written.
      const auto& materials = database.all();
      // With --preview NAME.png each material also gets <material>-NAME.png beside its table.
      if (!o->preview.empty() && std::filesystem::path(o->preview).extension() != ".png")
        throw InvalidInput("--preview", "'" + o->preview + "'", "a file name ending in .png (with --all: <material>-NAME.png each)");
      std::vector<std::string> encoded(materials.size()), failure(materials.size()), previews(materials.size());
      std::atomic<std::size_t> next{0}, done{0};
      std::mutex progress_mutex;
      const auto work = [&] {
        for (std::size_t i; (i = next++) < materials.size();) {
          LutOptions one = *o;
          one.medium.material = materials[i].name;
          one.threads = 1;
          try {
            const auto resolved = one.medium.resolve();
            const auto built = o->kind == "albedo-radius" ? build_albedo_radius(one) : build(one, resolved);
            encoded[i] = encode(built, format, o->half);
            if (!o->preview.empty()) previews[i] = render_preview(one, resolved).png;
          } catch (const InvalidInput& e) {
            failure[i] = e.what();
          }
          const std::size_t finished = ++done;
          if (progress) {
            std::lock_guard lock(progress_mutex);
            progress(finished, materials.size());
          }
        }
      };
      const unsigned workers = std::max(1u, std::min<unsigned>(o->threads == 0 ? std::thread::hardware_concurrency() : o->threads,
                                                               static_cast<unsigned>(materials.size())));
      std::vector<std::thread> pool;
      for (unsigned t = 1; t < workers; ++t) pool.emplace_back(work);
      work();
      for (auto& t : pool) t.join();
      std::size_t written = 0;
      std::vector<std::string> skipped;
      for (std::size_t i = 0; i < materials.size(); ++i) {
        if (!failure[i].empty()) {
          skipped.push_back(materials[i].name + ": " + failure[i]);
          continue;
        }
        const auto path = dir / file_name(materials[i].name, o->kind, format);
        write_file_atomically(path, encoded[i]);  // an unwritable directory stops the batch
        ++written;
        if (!o->quiet && !progress) std::cout << "written: " << path.string() << '\n';
        if (previews[i].empty()) continue;
        const auto png = dir / (file_stem(materials[i].name) + "-" + std::filesystem::path(o->preview).filename().string());
        write_file_atomically(png, previews[i]);
        if (!o->quiet && !progress) std::cout << "written: " << png.string() << '\n';
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      for (const auto& line : skipped) std::cerr << "bssrdf: skipped " << line << '\n';
      if (!o->quiet)
        std::cout << written << " " << o->kind << " tables in " << format_number(std::round(seconds * 1000) / 1000) << " s"
                  << (skipped.empty() ? "" : ", " + std::to_string(skipped.size()) + " materials skipped (see stderr)") << "\n";
      return;
    }
    if (!o->preview.empty()) {
      const auto resolved = o->medium.resolve();
      const auto preview = render_preview(*o, resolved);
      if (!o->output.empty()) format_for(*o, o->output);  // bad -o fails before anything is written
      write_file_atomically(o->preview, preview.png);
      if (!o->quiet) std::cout << "preview: " << o->preview << " (" << preview.description << ")\n";
      if (o->output.empty()) return;
    }
    if (o->output.empty()) throw InvalidInput("-o: give an output file (.exr, .json, .csv), or --preview FILE.png");
    const std::string format = format_for(*o, o->output);
    const auto start = std::chrono::steady_clock::now();
    Built built;
    if (!o->layers.empty()) {
      if (o->kind != "radial" || !o->reference) throw InvalidInput("--layers: only with --kind radial --reference (Monte Carlo)");
      if (!o->medium.material.empty() || !o->medium.sigma_a.empty()) throw InvalidInput("--layers: give no --material or coefficients with it");
      const auto file = read_layers_json(o->layers);
      const auto unit = o->medium.unit.empty() || o->medium.unit == "mm" ? file.unit : parse_length_unit(o->medium.unit, "--unit");
      built = build_reference_radial(*o, file.stack, {std::nullopt, nullptr, nullptr, unit});
    } else {
      built = o->kind == "albedo-radius" ? build_albedo_radius(*o) : build(*o, o->medium.resolve());
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    write_file_atomically(o->output, encode(built, format, o->half));
    if (!o->quiet)
      std::cout << built.summary << "built in " << format_number(std::round(ms * 100) / 100) << " ms\nwritten: " << o->output << '\n';
  };
}

}  // namespace bssrdf::cli
