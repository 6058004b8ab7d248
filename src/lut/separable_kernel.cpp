#include "bssrdf/lut/separable_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/projected_profile.hpp"

namespace bssrdf {

void SeparableKernelOptions::validate() const {
  if (taps < 3 || taps > 255 || taps % 2 == 0)
    throw InvalidInput("taps", std::to_string(taps), "an odd number from 3 to 255");
  if (!(range >= 0) || !std::isfinite(range)) throw InvalidInput("range", format_number(range), "> 0 (0: default)");
  if (!(band > 0 && band < 1)) throw InvalidInput("band", format_number(band), "0 < band < 1");
}

double jimenez_range(int taps) { return taps > 20 ? 3.0 : 2.0; }

SeparableKernel build_separable_kernel(const Medium& medium, const Model& model,
                                       const SeparableKernelOptions& options) {
  medium.validate();
  options.validate();
  return build_separable_kernel(medium, project_channels(medium, model), options);
}

SeparableKernel build_separable_kernel(const Medium& medium,
                                       const std::vector<std::optional<ProjectedProfile>>& profiles,
                                       const SeparableKernelOptions& options) {
  options.validate();
  SeparableKernel k;
  k.options = options;
  k.range_from_band = options.range == 0;
  k.channel_names = medium.channel_names;
  for (const auto& p : profiles)
    if (options.range == 0 && p) k.options.range = std::max(k.options.range, p->line_width_for_fraction(options.band));
  const int N = options.taps;
  const double range = k.options.range;
  // Offsets in [-range, range], sorted; then the footprints' edges.
  std::vector<double> o(N), edge(N + 1);
  for (int i = 0; i < N; ++i) {
    const double t = -1 + 2.0 * i / (N - 1);
    o[i] = range * (t < 0 ? -1 : 1) * t * t;
  }
  o[N / 2] = 0;
  edge[0] = -range;
  edge[N] = range;
  for (int i = 1; i < N; ++i) edge[i] = 0.5 * (o[i - 1] + o[i]);
  // Centre first (Jimenez's order), then the others in increasing offset.
  std::vector<int> order = {N / 2};
  for (int i = 0; i < N; ++i)
    if (i != N / 2) order.push_back(i);
  for (int i : order) k.offset.push_back(o[i] / range);
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    if (!profiles[c]) {  // no scattering: the identity kernel
      k.strip.emplace_back(N, 0.0);
      k.weight.emplace_back(N, 0.0);
      k.weight.back()[0] = 1;
      k.total_reflectance.push_back(0);
      k.captured.push_back(1);
      k.projection_error.push_back(0);
      continue;
    }
    const ProjectedProfile& p = *profiles[c];
    std::vector<double> strip, weight;
    double sum = 0;
    for (int i : order) {
      strip.push_back(p.strip(edge[i], edge[i + 1]));
      sum += strip.back();
    }
    for (double s : strip) weight.push_back(s / sum);
    k.strip.push_back(std::move(strip));
    k.weight.push_back(std::move(weight));
    k.total_reflectance.push_back(p.total());
    k.captured.push_back(sum / p.total());
    k.projection_error.push_back(p.conservation_error());
  }
  return k;
}

LookupTable to_lookup_table(const SeparableKernel& k, const TableContext& context) {
  auto out = described_table("separable", k.offset.size(), 1, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  out.set("bssrdf:taps", static_cast<int>(k.offset.size()));
  out.set("bssrdf:range", k.options.range / mm);
  out.set("bssrdf:range_unit", u);
  out.set("bssrdf:range_rule", k.range_from_band
                                   ? "half-width of the band |x| < range holding " + format_number(k.options.band) +
                                         " of the widest channel's light (line projection of R)"
                                   : std::string("given"));
  out.set("bssrdf:offset",
          "offset in units of the kernel half-width bssrdf:range (" + format_number(k.options.range / mm) + " " + u +
              "): physical offset = offset x range; o_i = sign(t) t^2, t = -1 + 2 i / (N - 1); centre tap first");
  out.set("bssrdf:weights",
          std::string(
              "per channel: the line-projected profile integrated over each tap's footprint, normalised to sum to 1 "
              "(multiply by the diffuse colour, bssrdf:total_reflectance.<c>)"));
  out.set("bssrdf:layout",
          std::string(
              "Jimenez et al. 2015 separable SSS: float4(weight.rgb, offset), applied horizontally then vertically"));
  for (std::size_t c = 0; c < k.channel_names.size(); ++c) {
    out.set("bssrdf:total_reflectance." + k.channel_names[c], k.total_reflectance[c]);
    out.set("bssrdf:captured." + k.channel_names[c], k.captured[c]);
    if (k.total_reflectance[c] == 0)
      out.set("bssrdf:note." + k.channel_names[c],
              std::string(
                  "the channel does not scatter (sigma_s = 0, total reflectance 0): identity kernel, centre tap 1"));
  }
  for (std::size_t c = 0; c < k.channel_names.size(); ++c)
    out.add_channel(k.channel_names[c], "tap weight, normalised per channel", k.weight[c]);
  out.add_channel("offset", "tap offset in units of the kernel half-width (bssrdf:range)", k.offset);
  return out;
}

namespace {

// A float literal every shading language accepts: always with a decimal point or exponent.
std::string float_literal(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", v);
  std::string s = buffer;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace

std::string to_shader(const SeparableKernel& k, const TableContext& context, ShaderLanguage language) {
  if (k.channel_names.size() != 3)
    throw InvalidInput("format", language == ShaderLanguage::glsl ? "glsl" : "hlsl",
                       "a medium with three channels (it has " + std::to_string(k.channel_names.size()) + ")");
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  const std::size_t N = k.offset.size();
  const bool glsl = language == ShaderLanguage::glsl;
  std::ostringstream s;
  s << "// bssrdf " << BSSRDF_VERSION << ": separable subsurface-scattering kernel (Jimenez et al. 2015), " << N
    << " taps\n";
  if (context.material) s << "// material: " << context.material->name << " (" << context.material->source << ")\n";
  if (context.model) s << "// model: " << context.model->name() << "\n";
  s << "// xyz: weight per channel (" << k.channel_names[0] << ", " << k.channel_names[1] << ", " << k.channel_names[2]
    << "), each channel sums to 1; multiply the result by the diffuse colour\n"
    << "//      (total reflectance " << format_number(k.total_reflectance[0]) << ", "
    << format_number(k.total_reflectance[1]) << ", " << format_number(k.total_reflectance[2]) << " per entered flux)\n"
    << "// w:   offset in units of the kernel half-width kernelRange = " << format_number(k.options.range / mm) << ' '
    << u << " (physical offset = w * kernelRange); centre tap first\n";
  s << (glsl ? "const float kernelRange = " : "static const float kernelRange = ")
    << float_literal(k.options.range / mm) << ";  // " << u << "\n";
  if (glsl)
    s << "const vec4 kernel[" << N << "] = vec4[" << N << "](\n";
  else
    s << "static const float4 kernel[" << N << "] = {\n";
  for (std::size_t i = 0; i < N; ++i)
    s << "    " << (glsl ? "vec4(" : "float4(") << float_literal(k.weight[0][i]) << ", "
      << float_literal(k.weight[1][i]) << ", " << float_literal(k.weight[2][i]) << ", " << float_literal(k.offset[i])
      << ")" << (i + 1 < N ? "," : "") << "\n";
  s << (glsl ? ");\n" : "};\n");
  return s.str();
}

std::string summary(const SeparableKernel& k, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  s << "separable kernel: " << k.options.taps << " taps over +-" << short_number(k.options.range / mm) << ' ' << u
    << (k.range_from_band
            ? " (the band holding " + short_number(100 * k.options.band) + " % of the widest channel's light)"
        : k.options.range == jimenez_range(k.options.taps) ? std::string(" (Jimenez's range)")
                                                           : std::string())
    << ", offsets warped quadratically, centre tap first\n";
  double worst = 1;
  for (std::size_t c = 0; c < k.channel_names.size(); ++c) {
    if (k.total_reflectance[c] == 0) {
      s << "  " << k.channel_names[c] << ": does not scatter (total reflectance 0): identity kernel, centre weight 1\n";
      continue;
    }
    s << "  " << k.channel_names[c] << ": centre weight " << short_number(k.weight[c][0])
      << ", the band |x| < range holds " << short_number(100 * k.captured[c]) << " % of the total reflectance "
      << short_number(k.total_reflectance[c]) << '\n';
    worst = std::min(worst, k.captured[c]);
  }
  if (worst < 0.9)
    s << "  note: the range holds less than 90 % of a channel's light; a wider --range (e.g. "
      << short_number(1.5 * k.options.range / mm) << " " << u << ") keeps more of it\n";
  return s.str();
}

}  // namespace bssrdf
