// A boundary of the slab: the interfaces and clear layers (glass slides) between a scattering
// layer and an ambient medium. Nothing in it scatters, so it keeps every angle and acts on each
// quadrature angle on its own: diagonal reflection and transmission, with the multiple
// reflections inside the slides summed exactly (unpolarised Fresnel, Snell's law, Beer's law).
#pragma once

#include <vector>

#include "angles.hpp"
#include "bssrdf/adding_doubling/slab.hpp"

namespace bssrdf::adding_doubling {

struct Boundary {
  std::vector<double> r_top;     // reflectance for light arriving from above, per angle
  std::vector<double> r_bottom;  // from below
  std::vector<double> t;         // transmittance (the same both ways)
};

// `indices`/`clear`: the media from top to bottom, the first and last being the half-spaces on
// either side (their thickness is ignored). Angles are cosines in the scattering medium of index n.
Boundary make_boundary(const Angles& angles, double n, const std::vector<ClearLayer>& media);

}  // namespace bssrdf::adding_doubling
