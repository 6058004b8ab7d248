#include "bssrdf/layers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "bssrdf/error.hpp"

namespace bssrdf {

double LayerStack::depth() const {
  double z = 0;
  for (const auto& layer : layers) z += layer.thickness;
  return z;
}

void LayerStack::validate() const {
  if (channel_names.empty()) throw InvalidInput("channels: at least one channel is needed");
  std::set<std::string> seen;
  for (std::size_t c = 0; c < channel_names.size(); ++c) {
    if (channel_names[c].empty()) throw InvalidInput("channels[" + std::to_string(c) + "]", "''", "a non-empty name");
    if (!seen.insert(channel_names[c]).second)
      throw InvalidInput("channels[" + std::to_string(c) + "]", "'" + channel_names[c] + "'", "a unique name");
  }
  const auto check_index = [](double n, const std::string& field) {
    if (!(n >= kMinRefractiveIndex && n <= kMaxRefractiveIndex))
      throw InvalidInput(field, format_number(n),
                         format_number(kMinRefractiveIndex) + " to " + format_number(kMaxRefractiveIndex));
  };
  check_index(ambient_above, "ambient_above");
  check_index(ambient_below, "ambient_below");
  if (layers.empty()) throw InvalidInput("layers: at least one layer is needed");
  const std::size_t nc = channel_names.size();
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const Layer& layer = layers[i];
    const std::string prefix = "layers[" + std::to_string(i) + "]";
    check_index(layer.n, prefix + ".n");
    const bool last = i + 1 == layers.size();
    if (layer.thickness == kSemiInfinite) {
      if (!last)
        throw InvalidInput(prefix + ".thickness", "semi-infinite",
                           "> 0 and finite (only the last layer may be semi-infinite)");
    } else if (!(layer.thickness > 0 && layer.thickness <= 1e6)) {  // 1e6 mm = 1 km: use semi-infinite beyond
      throw InvalidInput(prefix + ".thickness", format_number(layer.thickness),
                         "> 0 and at most 1e6 mm, or semi-infinite for the last layer");
    }
    const auto check_size = [&](const std::vector<double>& v, const char* name) {
      if (v.size() != nc)
        throw InvalidInput(prefix + "." + name + ": " + std::to_string(v.size()) + " values given, but there are " +
                           std::to_string(nc) + " channels");
    };
    check_size(layer.sigma_a, "sigma_a");
    check_size(layer.sigma_s, "sigma_s");
    check_size(layer.g, "g");
    for (std::size_t c = 0; c < nc; ++c) {
      const std::string at = "[" + channel_names[c] + "]";
      const std::string coefficient_range =
          ">= 0 and finite, at most " + format_number(kMaxCoefficient) + " (a 1 nm mean free path in mm)";
      if (!(layer.sigma_a[c] >= 0 && layer.sigma_a[c] <= kMaxCoefficient))
        throw InvalidInput(prefix + ".sigma_a" + at, format_number(layer.sigma_a[c]), coefficient_range);
      if (!(layer.sigma_s[c] >= 0 && layer.sigma_s[c] <= kMaxCoefficient))
        throw InvalidInput(prefix + ".sigma_s" + at, format_number(layer.sigma_s[c]), coefficient_range);
      if (!(layer.g[c] > -1 && layer.g[c] < 1))
        throw InvalidInput(prefix + ".g" + at, format_number(layer.g[c]), "-1 < g < 1");
      if (layer.thickness == kSemiInfinite && layer.clear(c))
        throw InvalidInput(prefix + ".sigma_a + sigma_s" + at, "0",
                           "> 0 in a semi-infinite layer (light would travel forever)");
    }
  }
}

Layer Layer::of(const Medium& medium, double thickness_mm, std::string name) {
  Layer layer;
  layer.name = std::move(name);
  layer.thickness = thickness_mm;
  layer.n = medium.eta;
  layer.sigma_a = medium.sigma_a;
  layer.sigma_s = medium.sigma_s;
  layer.g = medium.g;
  return layer;
}

LayerStack LayerStack::slab(const Medium& medium, double thickness_mm) {
  medium.validate();
  LayerStack stack;
  stack.channel_names = medium.channel_names;
  stack.layers.push_back(Layer::of(medium, thickness_mm));
  stack.validate();
  return stack;
}

TransportMfpRange transport_mfp_range(const LayerStack& stack) {
  TransportMfpRange range{std::numeric_limits<double>::infinity(), 0};
  for (const Layer& layer : stack.layers)
    for (std::size_t c = 0; c < stack.channels(); ++c) {
      if (layer.clear(c)) continue;
      const double ell = reduce(layer.sigma_a[c], layer.sigma_s[c], layer.g[c], layer.n).ell;
      range.min = std::min(range.min, ell);
      range.max = std::max(range.max, ell);
    }
  if (range.max == 0) range.min = 0;
  return range;
}

}  // namespace bssrdf
