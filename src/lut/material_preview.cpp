#include "bssrdf/lut/material_preview.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/projected_profile.hpp"

namespace bssrdf {

Preview render_material_preview(const Medium& medium, const Model& model, const PreviewOptions& o) {
  medium.validate();
  if (medium.channels() != 3) throw InvalidInput("preview", std::to_string(medium.channels()) + " channels", "3 (R, G, B)");
  if (o.width < 16 || o.width > 8192 || o.swatch_height < 1 || o.strip_height < 1 || o.swatch_height + o.strip_height > 8192)
    throw InvalidInput("preview size", std::to_string(o.width) + "x" + std::to_string(o.swatch_height + o.strip_height), "16 to 8192 pixels");
  std::vector<ProjectedProfile> p;
  double half = o.half_width;
  for (std::size_t c = 0; c < 3; ++c) p.emplace_back(model, medium.reduced(c));
  if (half <= 0)
    for (const auto& q : p) half = std::max(half, q.line_width_for_fraction(0.99));
  Preview out{RgbImage(o.width, o.swatch_height + o.strip_height), half, 0};
  // Ticks: 1, 2 or 5 x 10^k, about 8 per half-width.
  const double raw = half / 8, decade = std::pow(10.0, std::floor(std::log10(raw)));
  out.tick = raw / decade < 2 ? decade : raw / decade < 5 ? 2 * decade : 5 * decade;
  const double pixel = 2 * half / o.width;
  for (int x = 0; x < o.width; ++x) {
    const double d = -half + (x + 0.5) * pixel;  // signed distance from the edge; lit for d < 0
    std::array<double, 3> swatch{}, hue{};
    for (std::size_t c = 0; c < 3; ++c) swatch[c] = p[c].half_plane(d);
    const double r = std::abs(d);
    double top = 0;
    for (std::size_t c = 0; c < 3; ++c) top = std::max(top, hue[c] = p[c].reflectance(std::max(r, 1e-9)));
    for (std::size_t c = 0; c < 3; ++c) hue[c] = top > 0 ? hue[c] / top : 0;
    for (int y = 0; y < o.swatch_height; ++y)
      for (std::size_t c = 0; c < 3; ++c) out.image.at(x, y)[c] = to_srgb8(swatch[c]);
    for (int y = o.swatch_height; y < o.swatch_height + o.strip_height; ++y)
      for (std::size_t c = 0; c < 3; ++c) out.image.at(x, y)[c] = to_srgb8(hue[c]);
  }
  // Tick marks (grey) at multiples of `tick` from the edge, along the bottom of both parts.
  for (int k = -static_cast<int>(half / out.tick); k <= static_cast<int>(half / out.tick); ++k) {
    const int x = static_cast<int>(std::floor((k * out.tick + half) / pixel));
    if (x < 0 || x >= o.width) continue;
    const int length = k == 0 ? 12 : 6;
    for (int base : {o.swatch_height, o.swatch_height + o.strip_height})
      for (int y = base - length; y < base; ++y)
        for (int c = 0; c < 3; ++c) out.image.at(x, y)[c] = 128;
  }
  return out;
}

}  // namespace bssrdf
