// A stack of planar, homogeneous layers lit from above: the geometry of the Monte Carlo reference
// (and of layered diffusion models). Each layer has per-channel absorption sigma_a, scattering
// sigma_s (1/mm) and Henyey-Greenstein g, one absolute refractive index n and a thickness in mm;
// the last layer may be semi-infinite. Ambient media above and below have their own indices.
//
//   LayerStack stack = LayerStack::half_space(medium);          // semi-infinite, ambient n = 1
//   LayerStack slab  = LayerStack::slab(medium, 2.0);            // 2 mm slab
//   stack.validate();                                            // throws InvalidInput
//
// z grows downward from the top surface z = 0. Indices are absolute (n), not relative: a Medium's
// eta = n_medium / n_outside becomes a layer with n = eta between ambients of index 1.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "bssrdf/medium.hpp"

namespace bssrdf {

inline constexpr double kSemiInfinite = std::numeric_limits<double>::infinity();

struct Layer {
  std::string name;
  double thickness = kSemiInfinite;  // mm; kSemiInfinite only for the last layer
  double n = 1.0;                    // absolute refractive index
  std::vector<double> sigma_a;       // 1/mm, one per channel
  std::vector<double> sigma_s;       // 1/mm
  std::vector<double> g;             // HG mean cosine, -1 < g < 1

  double sigma_t(std::size_t c) const { return sigma_a[c] + sigma_s[c]; }
  // A layer without absorption or scattering in channel c (e.g. a glass slide): light crosses it
  // in a straight line.
  bool clear(std::size_t c) const { return sigma_t(c) == 0.0; }

  // A layer with `medium`'s coefficients and n = medium.eta (not validated: LayerStack::validate does).
  static Layer of(const Medium& medium, double thickness_mm, std::string name = "medium");
};

struct LayerStack {
  std::vector<std::string> channel_names;
  double ambient_above = 1.0;  // index of the medium the light comes from
  double ambient_below = 1.0;  // index below the last layer (irrelevant when it is semi-infinite)
  std::vector<Layer> layers;

  std::size_t channels() const { return channel_names.size(); }
  bool semi_infinite() const { return !layers.empty() && layers.back().thickness == kSemiInfinite; }
  // Depth of the bottom surface (mm); infinite for a semi-infinite stack.
  double depth() const;

  // Throws InvalidInput naming the first offending field, e.g. "layers[1].sigma_a[G] = -1:
  // accepted range is >= 0 and finite". Checks: >= 1 layer and >= 1 channel with unique, non-empty
  // names; per-layer vectors of one value per channel; sigma_a, sigma_s >= 0 and finite;
  // -1 < g < 1; n, ambients > 0 and finite; thickness > 0 and finite except the last layer, which
  // may be semi-infinite, but then must attenuate (sigma_t > 0) in every channel.
  void validate() const;

  // One homogeneous layer of `medium` (n = medium.eta, ambient 1 on both sides).
  static LayerStack slab(const Medium& medium, double thickness_mm);
  static LayerStack half_space(const Medium& medium) { return slab(medium, kSemiInfinite); }
};

// transport_mfp_range over the layers and channels that attenuate (a clear layer has no ell); both
// 0 when none does.
TransportMfpRange transport_mfp_range(const LayerStack& stack);

}  // namespace bssrdf
