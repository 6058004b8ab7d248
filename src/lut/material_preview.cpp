#include "bssrdf/lut/material_preview.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/io/bitmap_text.hpp"
#include "bssrdf/lut/projected_profile.hpp"

namespace bssrdf {
namespace {

constexpr int kTextScale = 2;
constexpr int kCaptionHeight = 7 * kTextScale + 10;

}  // namespace

Preview render_material_preview(const Medium& medium, const Model& model, const PreviewOptions& o) {
  medium.validate();
  const std::size_t n = medium.channels();
  // Display channel k = sum_i weight[i][k] x medium channel i.
  auto weight = o.display_weights;
  if (weight.empty() && n != 1 && n != 3)
    throw InvalidInput("preview", std::to_string(n) + " channels",
                       "1 (grey) or 3 (R, G, B), or display weights per channel (a spectral medium's colour)");
  if (weight.empty())
    for (std::size_t i = 0; i < n; ++i)
      weight.push_back(n == 1 ? std::array<double, 3>{1, 1, 1}
                              : std::array<double, 3>{1.0 * (i == 0), 1.0 * (i == 1), 1.0 * (i == 2)});
  if (weight.size() != n)
    throw InvalidInput("preview display weights", std::to_string(weight.size()),
                       "one per channel (" + std::to_string(n) + ")");
  if (o.width < 16 || o.width > 8192 || o.swatch_height < 1 || o.strip_height < 1 ||
      o.swatch_height + o.strip_height > 8192)
    throw InvalidInput("preview size", std::to_string(o.width) + "x" + std::to_string(o.swatch_height + o.strip_height),
                       "16 to 8192 pixels");
  // A channel that does not scatter (sigma_s = 0) sends no light across the edge: it stays black.
  const auto p = project_channels(medium, model);
  double half = o.half_width;
  for (const auto& q : p)
    if (q && o.half_width <= 0) half = std::max(half, q->line_width_for_fraction(0.99));
  const int caption = o.caption ? kCaptionHeight : 0;
  const int height = o.swatch_height + o.strip_height + caption;
  Preview out{RgbImage(o.width, height), half, 0};
  // Ticks: 1, 2 or 5 x 10^k in the caption's unit, about 8 per half-width.
  const double unit = millimetres_per(o.unit);
  const double raw = half / unit / 8, decade = std::pow(10.0, std::floor(std::log10(raw)));
  out.tick = unit * (raw / decade < 2 ? decade : raw / decade < 5 ? 2 * decade : 5 * decade);
  const double pixel = 2 * half / o.width;
  for (int x = 0; x < o.width; ++x) {
    const double d = -half + (x + 0.5) * pixel;  // signed distance from the edge; lit for d < 0
    const double r = std::max(std::abs(d), 1e-9);
    std::array<double, 3> swatch{}, hue{};
    for (std::size_t i = 0; i < n; ++i) {
      if (!p[i]) continue;
      const double exitance = p[i]->half_plane(d), R = p[i]->reflectance(r);
      for (std::size_t k = 0; k < 3; ++k) {
        swatch[k] += weight[i][k] * exitance;
        hue[k] += weight[i][k] * R;
      }
    }
    const double top = std::max({hue[0], hue[1], hue[2]});
    for (std::size_t k = 0; k < 3; ++k) hue[k] = top > 0 ? hue[k] / top : 0;
    // Outside [0, 1]: a colour linear sRGB cannot show; clipped (to_srgb8) and counted.
    bool clipped = false;
    for (std::size_t k = 0; k < 3; ++k)
      if (swatch[k] < 0 || swatch[k] > 1 || hue[k] < 0) clipped = out.clipped_channel[k] = true;
    out.clipped_columns += clipped;
    for (int y = 0; y < o.swatch_height; ++y)
      for (std::size_t k = 0; k < 3; ++k) out.image.at(x, y)[k] = to_srgb8(swatch[k]);
    for (int y = o.swatch_height; y < o.swatch_height + o.strip_height; ++y)
      for (std::size_t k = 0; k < 3; ++k) out.image.at(x, y)[k] = to_srgb8(hue[k]);
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
  if (caption) {
    // Dark band with the caption on the left and the tick spacing on the right.
    const int top = o.swatch_height + o.strip_height;
    for (int y = top; y < height; ++y)
      for (int x = 0; x < o.width; ++x)
        for (int c = 0; c < 3; ++c) out.image.at(x, y)[c] = 32;
    const std::array<std::uint8_t, 3> white{230, 230, 230};
    const std::string scale = "ticks " + short_number(out.tick / unit) + " " + std::string(symbol(o.unit));
    const int y = top + (kCaptionHeight - text_height(kTextScale)) / 2;
    draw_text(out.image, o.width - 6 - text_width(scale, kTextScale), y, scale, white, kTextScale);
    const int room = (o.width - 18 - text_width(scale, kTextScale)) / (6 * kTextScale);
    std::string label = o.label;
    if (room < 1)
      label.clear();
    else if (static_cast<int>(label.size()) > room)
      label = label.substr(0, static_cast<std::size_t>(std::max(0, room - 2))) + "..";
    draw_text(out.image, 6, y, label, white, kTextScale);
  }
  return out;
}

}  // namespace bssrdf
