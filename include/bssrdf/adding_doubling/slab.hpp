// Adding-doubling: the exact total reflectance and transmittance of a plane-parallel slab (or a
// stack of scattering layers) of Henyey-Greenstein media with smooth Fresnel boundaries, optional
// glass slides and any ambient index; the semi-infinite medium is its thick limit. The method of
// van de Hulst (1980) with Prahl's boundary treatment (Prahl 1995, "The adding-doubling method",
// in Welch & van Gemert, Optical-Thermal Response of Laser-Irradiated Tissue, ch. 5):
//  - angles: the cosines inside the slab are split at the critical angle(s); Gauss-Legendre below,
//    Gauss-Radau (with mu = 1, the direction of a normally incident beam) above, so that Fresnel's
//    kinks fall on interval ends and the light that escapes is integrated exactly;
//  - phase function: delta-M (Wiscombe 1977) with 2N Legendre terms for N angles per hemisphere,
//    normalised so the discrete scattering conserves energy exactly;
//  - a thin starting layer (diamond initialisation, Wiscombe 1976) doubled to the thickness;
//  - layers, boundaries and slides combined with the adding equations;
//  - an oblique collimated beam (Options::incidence_cosine) enters along the quadrature angle made
//    equal to its refracted direction (the interval below it ends in a Radau node there), as
//    Prahl's ad does for oblique incidence.
// The number of angles is chosen from a tolerance (8, 16, 32, ... until R and T change by less)
// and reported with the last change as the error estimate.
//
//   adding_doubling::Slab slab;
//   slab.layers = {{0.1, 10.0, 0.9, 2.0}};                 // sigma_a, sigma_s (1/mm), g, thickness (mm)
//   slab.n = 1.4;
//   slab.above = slab.below = {{1.5, 1.0}};                 // 1 mm glass slides, n = 1.5
//   auto t = adding_doubling::solve(slab, adding_doubling::Incidence::collimated);
//   t.diffuse_reflectance, t.total_transmittance          // per unit incident flux
//
// Conventions (as MCML and Prahl's ad report them): every quantity is per unit INCIDENT flux.
// specular_reflectance is the light reflected by the top boundary (with slides, including their
// multiple reflections) without entering the scattering medium; diffuse_reflectance is everything
// else leaving the top; total_transmittance includes the unscattered beam, which is also given on
// its own (exact exponential attenuation with the multiple reflections between the faces).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/reduced.hpp"

namespace bssrdf::adding_doubling {

// A non-scattering layer, e.g. a glass slide: index, thickness (mm) and absorption (1/mm).
struct ClearLayer {
  double n = 1.5;
  double thickness = 1.0;
  double sigma_a = 0.0;
};

// One scattering layer for one channel (1/mm, mm); the last may be kSemiInfinite.
struct ScatteringLayer {
  double sigma_a = 0, sigma_s = 0, g = 0;
  double thickness = kSemiInfinite;
};

struct Slab {
  std::vector<ScatteringLayer> layers;  // top to bottom
  double n = 1.0;                       // absolute index of every scattering layer
  double ambient_above = 1.0, ambient_below = 1.0;
  std::vector<ClearLayer> above;  // between the ambient above and the slab, top to bottom
  std::vector<ClearLayer> below;  // between the slab and the ambient below, top to bottom

  // Throws InvalidInput naming the field (e.g. "layers[0].g = 1: accepted range is -1 < g < 1").
  void validate() const;
  bool semi_infinite() const { return !layers.empty() && layers.back().thickness == kSemiInfinite; }
};

enum class Incidence { collimated, diffuse };
std::string_view to_string(Incidence incidence);
Incidence parse_incidence(const std::string& text);  // "collimated" | "diffuse"

struct Options {
  double tolerance = 1e-4;  // on R and T (absolute): angles are doubled until they change by less
  int points = 0;           // angles per hemisphere; 0: chosen from the tolerance
  // Cosine of the collimated beam's angle to the normal in the ambient above, in (0, 1]: an
  // oblique beam (iad's -i) refracts into the slab at a cosine made one of the quadrature angles.
  double incidence_cosine = 1;
};

struct Totals {
  double specular_reflectance = 0;       // per incident flux
  double diffuse_reflectance = 0;        // per incident flux, specular excluded
  double total_transmittance = 0;        // per incident flux, unscattered included
  double unscattered_transmittance = 0;  // per incident flux
  // Specular reflection plus the unscattered light reflected back out by the bottom boundary
  // (iad's R_u), per incident flux.
  double unscattered_reflectance = 0;
  int points = 0;             // quadrature angles per hemisphere used
  double error_estimate = 0;  // largest change of R or T from points/2 (0 with fixed points)

  double absorbed() const { return 1 - specular_reflectance - diffuse_reflectance - total_transmittance; }
  // 1 / (1 - R_sp): multiply per-incident values by this for per-entered ones.
  double entered_scale() const { return 1 / (1 - specular_reflectance); }
};

Totals solve(const Slab& slab, Incidence incidence, const Options& options = {});
// Several incidences from one set of layer operators (e.g. collimated and diffuse for sphere
// corrections): the same results as separate calls, for little more than the cost of one.
std::vector<Totals> solve(const Slab& slab, const std::vector<Incidence>& incidences, const Options& options = {});

// One-layer slabs that differ only in the layer's thickness (a table against thickness): the results
// of solve() at each thickness, bitwise, with the angles, boundaries and phase function computed once
// per number of angles instead of once per thickness.
std::vector<Totals> solve_thicknesses(const Slab& slab, const std::vector<double>& thicknesses, Incidence incidence,
                                      const Options& options = {});

// Channel `c` of a layer stack: leading and trailing layers that do not scatter become clear
// layers (slides); the scattering layers between them must share one index and may not contain a
// non-scattering layer (InvalidInput otherwise).
Slab slab_of(const LayerStack& stack, std::size_t channel);

// A semi-infinite medium of relative index m.eta in air, one channel: the thick limit, per entered
// flux with Totals::entered_scale().
Slab half_space(const Reduced<double>& m);

}  // namespace bssrdf::adding_doubling
