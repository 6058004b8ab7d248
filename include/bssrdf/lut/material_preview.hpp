// A picture to judge a material by: on top, a shadow-edge swatch (light falls on the left half of
// a flat surface; the profile carries it across the edge: exitance = ProjectedProfile::half_plane
// of the signed distance, the exact 2D convolution of the half-plane with R), shown as the
// diffuse colour it produces (linear per channel, sRGB-encoded, channels 0, 1, 2 as R, G, B, or the display weights'
// sums, clipped to [0, 1]);
// below, a strip of the profile's colour falloff: at distance r from a point of light, R_c(r)
// divided by its largest channel (the hue a point light's halo takes at that distance, mirrored
// about the centre). Both share
// one horizontal scale: tick marks every `tick` length at the bottom, the shadow edge at the
// swatch's centre (its distance 0) and the strip starting at r = 0 at that centre. A caption band
// below names the material and model and states the tick spacing in text.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "bssrdf/io/png_image.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

struct PreviewOptions {
  int width = 512, swatch_height = 192, strip_height = 64;
  double half_width = 0;  // mm shown each side of the edge; 0: the widest channel's 99 % band half-width
  bool caption = true;    // a dark band below with `label` on the left and the tick spacing on the right
  std::string label;      // e.g. "Skin1, pbd"
  LengthUnit unit = LengthUnit::millimetre;  // of the ticks and their caption
  // Display R, G, B (linear sRGB) as sums over the medium's channels: display_weights[i][k] is channel i's weight in
  // display channel k (a spectral medium's colour weights, spectral/colour.hpp, make the preview its colour: the
  // swatch and strip are linear in R). Empty: one channel shown grey, or three as R, G, B.
  std::vector<std::array<double, 3>> display_weights{};
};

struct Preview {
  RgbImage image;
  double half_width = 0;  // mm
  double tick = 0;        // mm between tick marks
  // Columns whose swatch or strip colour lies outside [0, 1] in some display channel (a colour outside linear sRGB,
  // e.g. the deep red left far from a spectral medium's edge), clipped there for display, and which channels.
  int clipped_columns = 0;
  std::array<bool, 3> clipped_channel{};
};

// Needs one channel (shown grey) or three, or display_weights for each channel (InvalidInput otherwise). A channel
// that does not scatter (sigma_s = 0) contributes nothing: no light crosses the edge in it.
Preview render_material_preview(const Medium& medium, const Model& model, const PreviewOptions& options = {});

}  // namespace bssrdf
