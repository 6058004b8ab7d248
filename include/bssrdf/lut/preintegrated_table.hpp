// Penner's pre-integrated skin LUT (Penner & Borshukov 2011), for any profile: the diffuse
// shading of a curved surface of radius r = 1/curvature lit at angle theta (u = N.L = cos theta),
// with light scattered around the ring:
//
//   D(theta, r) = int_{-pi}^{pi} max(0, cos(theta + x)) R_ring(2 r sin(x/2)) dx / int_{-pi}^{pi} R_ring(2 r sin(x/2))
//   dx
//
// (Penner & Borshukov 2011, GPU Pro 2) where R_ring is the profile's cross-section through the ring,
// the line projection of R (ProjectedProfile::line: for a sum of Gaussians, the 1D-normalised
// Gaussians exp(-x^2/2v)/sqrt(2 pi v) of d'Eon & Luebke 2007), evaluated at the chord length. D is per channel, in [0,
// 1], and tends to max(0, N.L) as the curvature goes to 0; the diffuse colour is applied separately.
//
// Layout: width columns over u = N.L, height rows over curvature, sampled at texel centres:
// u_i = -1 + 2 (i + 0.5) / width, curvature_j = curvature_max (j + 0.5) / height (1/mm). The ring
// integral uses nodes geometric in x near 0 (the profile's scale over r) and uniform beyond 0.1,
// trapezoid weights (density in the options).
//
//   auto t = build_preintegrated_table(skin, *make_model("pbd"), {});
#pragma once

#include <optional>
#include <vector>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

struct PreintegratedOptions {
  std::size_t width = 256, height = 256;  // N.L columns x curvature rows
  double curvature_max = 0;               // 1/mm; 0: 1 / r_50 of the widest channel
  unsigned threads = 1;                   // 0: all; results never depend on it
  // The ring integral's nodes in x: geometric below 0.1 (this many per decade), uniform above (this
  // step). The defaults are within 3.2e-5 of D from a 4x finer quadrature (Skin1, Ketchup).
  double ring_nodes_per_decade = 32, ring_step = 0.01;

  void validate() const;  // throws InvalidInput naming the option
};

struct PreintegratedTable {
  PreintegratedOptions options;  // curvature_max resolved
  std::vector<std::string> channel_names;
  std::vector<double> n_dot_l;             // [i], width
  std::vector<double> curvature;           // [j], height, 1/mm
  std::vector<std::vector<double>> value;  // [channel][j * width + i]: D
  double widest_r50 = 0;                   // mm: the default curvature_max is its inverse
  std::vector<bool> scatters;              // [channel]: false for sigma_s = 0, whose D is max(0, N.L)
};

PreintegratedTable build_preintegrated_table(const Medium& medium, const Model& model,
                                             const PreintegratedOptions& options);
// The same from the channels' projections (project_channels), for callers that build several sizes.
PreintegratedTable build_preintegrated_table(const Medium& medium,
                                             const std::vector<std::optional<ProjectedProfile>>& profiles,
                                             const PreintegratedOptions& options);

// Channels: one per colour channel (D). Attributes record the axes, sampling and curvature range.
LookupTable to_lookup_table(const PreintegratedTable& table, const TableContext& context);
// A few lines for people: the axes and each channel's D on the flattest and most curved rows.
std::string summary(const PreintegratedTable& table, const TableContext& context);

}  // namespace bssrdf
