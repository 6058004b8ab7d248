// What an integrating sphere reports for a sample, from the sample's totals: the single- and
// double-sphere equations of inverse adding-doubling (Pickering et al. 1993, Appl. Opt. 32:399;
// Prahl et al. 1993, Appl. Opt. 32:559; Prahl's iad manual), for a baffled sphere, light hitting
// the sample first (f = 0), a black detector port and no light lost at the sample's edges.
//
// Port areas are fractions of the sphere's wall, a = d_port^2 / (4 D_sphere^2) (flat ports), the
// wall's a_w = 1 - a_s - a_e - a_d. The gain of a sphere with the sample's diffuse reflectance
// r_s on its sample port is G(r_s) = 1 / (1 - r_w [a_w + (1 - a_e) a_s r_s]).
//  - no sphere:  M_R = UR1, M_T = UT1 (the totals, specular and unscattered light included);
//  - one sphere (reflection and transmission measured in turn):
//      M_R = UR1 G(URU) / G(r_std),  M_T = UT1 G'(URU) / G'(0);
//  - two spheres (both at once, light passing between them through the sample): the same with
//    the gains coupled through the sample's diffuse transmittance UTU.
#pragma once

#include <utility>

#include "bssrdf/io/rxt.hpp"

namespace bssrdf {

// The sample's totals under collimated (1) and diffuse (U) illumination, per incident flux,
// specular reflection and unscattered transmission included.
struct SampleTotals {
  double ur1 = 0, ut1 = 0, uru = 0, utu = 0;
};

// (M_R, M_T) the spheres of `setup` would report.
std::pair<double, double> sphere_measurements(const RxtFile& setup, const SampleTotals& sample);

}  // namespace bssrdf
