// Layer stacks under the multipole (Donner & Jensen 2005): every finite layer
// is a multipole slab whose faces take their A from the index ratio across each interface, a
// semi-infinite last layer is a dipole, and the layers combine by the adding equations on their
// 2D Fourier (zero-order Hankel) spectra, exact in closed form (multipole::spectra):
//
//   R_12 = R_1 + T_1 R_2 T_1' / (1 - R_2 R_1')      T_12 = T_1 T_2 / (1 - R_2 R_1')
//
// where ' marks layer 1 seen from below (faces swapped; the same as the brief's symmetric form
// when both faces of a layer have the same index ratio). Stacks fold from the bottom. R(r), T(r)
// are the inverse Hankel transforms of the combined spectra (hankel.hpp); totals are the spectra
// at k = 0. Per unit flux entered at the top, multiple scattering only, no ballistic part.
//
//   layered::Stack stack(layers, channel);
//   double R = stack.reflectance(0.3), T_total = stack.total_transmittance();
#pragma once

#include <cstddef>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf::layered {

struct StackSpectra {
  double reflectance, transmittance;
};

class Stack {
 public:
  // Throws InvalidInput for a clear layer (no scattering or absorption: not diffusive).
  Stack(const LayerStack& stack, std::size_t channel, multipole::BoundaryA boundary = multipole::BoundaryA::classical);

  StackSpectra spectra(double k) const;
  double total_reflectance() const { return spectra(0).reflectance; }
  double total_transmittance() const { return spectra(0).transmittance; }
  double reflectance(double r) const;    // 1/mm^2
  double transmittance(double r) const;  // 0 for a semi-infinite stack
  // The radius holding `fraction` of R_total (or of T_total), by bisection on the radial integral.
  double radius_for_fraction(double fraction, bool transmitted = false) const;

  // Per layer: thin_layer (d < 2 ell: invalid; < 4 ell: warning), negative totals; plus a note on
  // the adding approximation and the top layer's albedo notes.
  ValidityReport validity() const;

  std::size_t layers() const { return media_.size(); }
  const Reduced<double>& medium(std::size_t i) const { return media_[i]; }
  bool semi_infinite() const { return semi_infinite_; }

 private:
  std::vector<Reduced<double>> media_;
  std::vector<multipole::Slab<double>> slabs_;  // the last is unused when semi_infinite_
  std::vector<std::string> names_;
  bool semi_infinite_;
};

}  // namespace bssrdf::layered
