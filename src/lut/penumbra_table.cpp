#include "bssrdf/lut/penumbra_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/parallel.hpp"

namespace bssrdf {

void PenumbraOptions::validate() const {
  if (width < 2 || width > 8192) throw InvalidInput("size", std::to_string(width) + " shadow values", "2 to 8192");
  if (height < 1 || height > 8192) throw InvalidInput("size", std::to_string(height) + " penumbra widths", "1 to 8192");
  if (!(width_max >= 0) || !std::isfinite(width_max))
    throw InvalidInput("width_max", format_number(width_max), "> 0 (0: default)");
  if (threads > 4096) throw InvalidInput("threads", std::to_string(threads), "0 (all cores) to 4096");
}

PenumbraTable build_penumbra_table(const Medium& medium, const Model& model, const PenumbraOptions& options) {
  medium.validate();
  options.validate();
  PenumbraTable t;
  t.options = options;
  t.channel_names = medium.channel_names;
  const std::size_t channels = medium.channels(), W = options.width, H = options.height;
  const auto profiles = project_channels(medium, model);
  for (const auto& p : profiles) {
    t.scatters.push_back(p.has_value());
    if (p) t.widest_r50 = std::max(t.widest_r50, p->radius_for_fraction(0.5));
  }
  t.width_from_widest = t.options.width_max == 0;
  if (t.width_from_widest) t.options.width_max = 8 * t.widest_r50;
  for (std::size_t i = 0; i < W; ++i) t.shadow.push_back((static_cast<double>(i) + 0.5) / static_cast<double>(W));
  for (std::size_t j = 0; j < H; ++j)
    t.penumbra_width.push_back(t.options.width_max * (static_cast<double>(j) + 0.5) / static_cast<double>(H));
  t.value.assign(channels, std::vector<double>(W * H));
  // D = 1 - [A(s w) - A(-(1 - s) w)] / (w total), A(x) = int_0^x half_plane (odd part: A(-y) =
  // half_plane_integral(y) - total y). The columns s_i and 1 - s_i = s_{W-1-i} share their
  // integrals, so a row needs W of them, at ln(s_i w) = ln s_i + ln w (no logarithm per texel).
  std::vector<double> ln_shadow(W);
  for (std::size_t i = 0; i < W; ++i) ln_shadow[i] = std::log(t.shadow[i]);
  parallel_for(H, options.threads, [&](std::size_t j) {
    const double w = t.penumbra_width[j], ln_w = std::log(w);
    std::vector<double> integral(W), x(W), ln_x(W);  // the columns' s_i w and their logarithms, shared by the channels
    for (std::size_t i = 0; i < W; ++i) {
      x[i] = t.shadow[i] * w;
      ln_x[i] = ln_shadow[i] + ln_w;
    }
    for (std::size_t c = 0; c < channels; ++c) {
      const auto& p = profiles[c];
      if (!p) {
        for (std::size_t i = 0; i < W; ++i) t.value[c][j * W + i] = t.shadow[i];
        continue;
      }
      p->half_plane_integrals(x.data(), ln_x.data(), integral.data(), W);
      const double total = p->total();
      for (std::size_t i = 0; i < W; ++i) {
        const std::size_t m = W - 1 - i;
        const double lit = integral[i] - integral[m] + total * t.shadow[m] * w;
        t.value[c][j * W + i] = std::clamp(1 - lit / (w * total), 0.0, 1.0);
      }
    }
  });
  return t;
}

LookupTable to_lookup_table(const PenumbraTable& t, const TableContext& context) {
  auto out = described_table("penumbra", t.options.width, t.options.height, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  out.set(
      "bssrdf:formula",
      std::string("D(s, w) = int L(X) R_line(p - X) dX / int R_line, L(X) = clamp(X / w + 1/2, 0, 1), p = (s - 1/2) w: "
                  "a light ramp across a penumbra of width w convolved with the profile's line projection "
                  "(Penner 2011's shadow LUT, without his artistic sharpening)"));
  out.set("bssrdf:normalization",
          std::string("per channel, int R_line = 1: D is in [0, 1]; multiply by the diffuse colour"));
  out.set("bssrdf:x_axis", "shadow value s in [0, 1] (0: umbra, 1: lit): column i holds s_i = (i + 0.5) / width");
  out.set("bssrdf:y_axis", "penumbra width w in " + u +
                               ": row j holds w_j = width_max (j + 0.5) / height (texture coordinate w / width_max)");
  out.x_axis = {"shadow", t.shadow};
  out.y_axis = {"penumbra_width (" + u + ")", {}};
  for (double w : t.penumbra_width) out.y_axis.values.push_back(w / mm);
  out.set("bssrdf:width_max", t.options.width_max / mm);
  out.set("bssrdf:widest_r50", t.widest_r50 / mm);
  out.set("bssrdf:size", std::to_string(t.options.width) + "x" + std::to_string(t.options.height));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    if (!t.scatters[c])
      out.set("bssrdf:note." + t.channel_names[c], std::string("the channel does not scatter (sigma_s = 0): D = s"));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    out.add_channel(t.channel_names[c], "diffused light across a penumbra D(s, w), dimensionless", t.value[c]);
  return out;
}

std::string summary(const PenumbraTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  const std::size_t W = t.options.width, H = t.options.height;
  std::ostringstream s;
  s << "penumbra table: " << W << " shadow values x " << H << " penumbra widths from 0 to "
    << short_number(t.options.width_max / mm) << ' ' << u
    << (t.width_from_widest ? " (8 r_50 of the widest channel)" : "") << ", texel centres\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    if (!t.scatters[c]) {
      s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): D = s\n";
      continue;
    }
    s << "  " << t.channel_names[c] << ": D at s = " << short_number(t.shadow[W / 8]) << ": "
      << short_number(t.value[c][W / 8]) << " (narrowest penumbra) to " << short_number(t.value[c][(H - 1) * W + W / 8])
      << " (widest)\n";
  }
  return s.str();
}

}  // namespace bssrdf
