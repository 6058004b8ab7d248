// Penner's shadow (penumbra) LUT for any profile: how much light scattering carries across a
// soft shadow edge. A shadow map's filtered value s in [0, 1] is read as the position inside a
// penumbra of width w across which the incident light rises linearly from 0 (umbra) to 1 (lit):
// the point sits at p = (s - 1/2) w from the penumbra's centre, and the exitance there is the
// light ramp convolved with the profile,
//
//   D(s, w) = (1 / total) int L(X) line(p - X) dX,   L(X) = clamp(X / w + 1/2, 0, 1)
//           = 1 - (A(p + w/2) - A(p - w/2)) / (w total),
//
// A(x) = int_0^x half_plane (ProjectedProfile; for x < 0, A(x) = I(|x|) - total |x|). D is per
// channel, in [0, 1], normalised per channel like the pre-integrated LUT (multiply by the diffuse
// colour); D = s where w is much wider than the profile, D(1/2, w) = 1/2 for every w (symmetry),
// and D > s on the shadowed side (the profile's red glow into the shadow). A channel that does not
// scatter (sigma_s = 0) has D = s. Penner sharpens the shadow value before the lookup, an artistic
// choice this table leaves to the shader.
//
// Layout: width columns over s, height rows over w, at texel centres: s_i = (i + 0.5) / width,
// w_j = width_max (j + 0.5) / height (mm).
//
//   auto t = build_penumbra_table(skin, *make_model("pbd"), {});
#pragma once

#include <vector>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

struct PenumbraOptions {
  std::size_t width = 256, height = 256;  // shadow-value columns x penumbra-width rows
  double width_max = 0;                   // mm; 0: 8 r_50 of the widest channel
  unsigned threads = 1;                   // 0: all; results never depend on it

  void validate() const;  // throws InvalidInput naming the option
};

struct PenumbraTable {
  PenumbraOptions options;  // width_max resolved
  std::vector<std::string> channel_names;
  std::vector<double> shadow;              // [i], width
  std::vector<double> penumbra_width;      // [j], height, mm
  std::vector<std::vector<double>> value;  // [channel][j * width + i]: D
  std::vector<bool> scatters;              // [channel]: false for sigma_s = 0, whose D is s
  bool width_from_widest = false;          // width_max was 0: 8 widest_r50
  double widest_r50 = 0;                   // mm
};

PenumbraTable build_penumbra_table(const Medium& medium, const Model& model, const PenumbraOptions& options);

// Channels: one per colour channel (D). Attributes record the axes, the ramp convention and width_max.
LookupTable to_lookup_table(const PenumbraTable& table, const TableContext& context);
// A few lines for people: the axes and each channel's D at a shadow value for the narrowest and widest penumbra.
std::string summary(const PenumbraTable& table, const TableContext& context);

}  // namespace bssrdf
