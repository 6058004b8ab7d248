// A picture to judge a material by: on top, a shadow-edge swatch (light falls on the left half of
// a flat surface; the profile carries it across the edge: exitance = ProjectedProfile::half_plane
// of the signed distance, the exact 2D convolution of the half-plane with R), shown as the
// diffuse colour it produces (linear per channel, sRGB-encoded, channels 0, 1, 2 as R, G, B);
// below, a strip of the profile's colour falloff: at distance r from a point of light, R_c(r)
// divided by its largest channel (the hue a point light's halo takes at that distance, mirrored
// about the centre). Both share
// one horizontal scale: tick marks every `tick` length at the bottom, the shadow edge at the
// swatch's centre (its distance 0) and the strip starting at r = 0 at that centre. A caption band
// below names the material and model and states the tick spacing in text.
#pragma once

#include <string>

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
};

struct Preview {
  RgbImage image;
  double half_width = 0;  // mm
  double tick = 0;        // mm between tick marks
};

// Needs one channel (shown grey) or three (InvalidInput otherwise). A channel that does not
// scatter (sigma_s = 0) stays black: no light crosses the edge in it.
Preview render_material_preview(const Medium& medium, const Model& model, const PreviewOptions& options = {});

}  // namespace bssrdf
