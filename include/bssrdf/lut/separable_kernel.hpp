// The separable screen-space subsurface kernel of Jimenez et al. (2015, "Separable Subsurface
// Scattering"): N taps (11, 17, 25 in the paper; any odd N >= 3 here) over +-range, offsets warped
// quadratically toward 0 (o_i = range sign(t) t^2, t = -1 + 2 i / (N - 1)), weights = the
// trapezoid footprint of each tap times the profile, normalised per channel; the centre tap first,
// as the paper's shader expects. Default range: the half-width of the band |x| < range that holds
// `band` (95 %) of the widest channel's light; the paper's fixed 3 mm if N > 20 else 2 mm
// (jimenez_range) suits its skin profile but holds 71-81 % of the red channel for Jensen's skin and
// less for milks, whose profiles are centimetres wide. A channel that does not scatter (sigma_s = 0,
// total 0) gets the identity kernel (centre tap 1): the limit of a vanishing profile.
//
// The 1D profile of a separable pass is the line projection of R (ProjectedProfile::line, the
// exitance next to a lit line; a 2D Gaussian projects to the 1D Gaussian of the same variance),
// and each tap's weight is its integral over the tap's footprint [mid(o_{i-1}, o_i), mid(o_i,
// o_{i+1})] (the ends stop at +-range): Jimenez's "trapezoid area x profile" made exact where the
// profile is curved or singular (R ~ 1/r at 0 for Burley and single scattering). Before the
// normalisation the weights sum to the light of a point inside the band |x| < range: captured[c]
// of the channel's total reflectance; that fraction is recorded, with the total itself (the colour
// the normalised kernel leaves out).
//
//   auto k = build_separable_kernel(skin, *make_model("pbd"), {.taps = 25});
#pragma once

#include <string>
#include <vector>

#include <optional>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

struct SeparableKernelOptions {
  int taps = 17;
  double range = 0;       // mm, half-width; 0: the band holding `band` of the widest channel's light
  double band = 0.95;     // 0 < band < 1
  void validate() const;  // throws InvalidInput naming the option
};

// Jimenez et al.'s fixed half-width for their skin profile: 3 mm if taps > 20 else 2 mm.
double jimenez_range(int taps);

struct SeparableKernel {
  SeparableKernelOptions options;  // range resolved
  bool range_from_band = false;    // the range was chosen to hold options.band of the widest channel
  std::vector<std::string> channel_names;
  std::vector<double> offset;               // [i] in units of the range: -1 .. 1, centre first
  std::vector<std::vector<double>> weight;  // [channel][i], each channel sums to 1
  std::vector<std::vector<double>> strip;   // [channel][i], before normalisation: light per unit entered flux
  std::vector<double> total_reflectance;    // [channel]: int 2 pi r R dr
  std::vector<double> captured;             // [channel]: sum of strip / total_reflectance (1 without scattering)
  std::vector<double> projection_error;     // [channel]: ProjectedProfile::conservation_error()
};

SeparableKernel build_separable_kernel(const Medium& medium, const Model& model, const SeparableKernelOptions& options);
// The same from the channels' projections (project_channels), for callers that build many kernels.
SeparableKernel build_separable_kernel(const Medium& medium,
                                       const std::vector<std::optional<ProjectedProfile>>& profiles,
                                       const SeparableKernelOptions& options);

// Channels: the weights under the medium's channel names, "offset" (units of the range); the range
// in the unit, totals and captured fractions as attributes.
LookupTable to_lookup_table(const SeparableKernel& kernel, const TableContext& context);
// A few lines for people: taps and range, each channel's centre weight and captured light, and a note
// when the range holds less than 90 % of a channel's light.
std::string summary(const SeparableKernel& kernel, const TableContext& context);

enum class ShaderLanguage { glsl, hlsl };
// "float4 kernel[N] = ..." (HLSL) / "const vec4 kernel[N] = vec4[N](...)" (GLSL): xyz = RGB weight,
// w = offset in units of the kernel's half-width, whose physical size is a constant beside it and
// in the comment. Needs three channels.
std::string to_shader(const SeparableKernel& kernel, const TableContext& context, ShaderLanguage language);

}  // namespace bssrdf
