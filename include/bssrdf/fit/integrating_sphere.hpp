// What an integrating sphere reports for a sample, from the sample's totals: iad 4's single- and
// double-sphere equations option for option (Pickering et al. 1993, Appl. Opt. 32:399; Prahl et
// al. 1993, Appl. Opt. 32:559; Prahl's iad 4 manual and iad_calc.w, Calculate_Distance_With_Corrections).
//
// Port areas are fractions of the sphere's wall, a = d_port^2 / (4 D_sphere^2), the wall's
// a_w = 1 - a_s - a_t - a_d. The gain of a sphere with reflectance r_s on its sample port and
// r_3 on its third port (entrance or exit) is, with a baffle between sample and detector,
//     G = 1 / (1 - (r_w + (a_t/a_w) r_3) (a_w + (1 - a_t)(a_d r_d + a_s r_s))),
// without one G = 1 / (1 - a_w r_w - a_d r_d - a_s r_s - a_t r_3).
//  - no sphere:   M_R = UR1 - (1 - c) R_u,  M_T = UT1 - (1 - C) T_u;
//  - one sphere (substitution): the detector power P = G (P_ss + P_su) relative to the standard's;
//    with a baffle the scattered light reaches the detector after one wall bounce r_w (1 - a_t),
//    a fraction f of the beam hits the wall first, c R_u reaches the wall specularly; the
//    transmission sphere's third port holds the standard t_std when C > 0 (or a wall plug when
//    it has no third port);
//  - dual beam (comparison, one sphere): the sphere's gain cancels, M = the totals as with none;
//  - two spheres: both at once, light passing between them through the sample (UTU).
// R_u and T_u are the unscattered (specular) reflection and transmission of the sample with its
// slides; c and C say how much of them the sphere collects (the file's or iad's 1).
#pragma once

#include <cmath>
#include <utility>

#include "bssrdf/io/rxt.hpp"

namespace bssrdf {

// The sample's totals under collimated (1) and diffuse (U) illumination, per incident flux,
// specular reflection and unscattered transmission included; ru and tu: the unscattered parts.
struct SampleTotals {
  double ur1 = 0, ut1 = 0, uru = 0, utu = 0;
  double ru = 0, tu = 0;
};

// The instrument's options that an .rxt file does not carry, with iad 4's defaults.
struct SphereModel {
  bool baffle_r = true, baffle_t = true;  // iad -H 3
  double detector_reflectance = 0;        // r_d of both detectors (iad: 0)
  double wall_first = 0;                  // f: fraction of the beam hitting the R sphere's wall first (-f)
  bool dual_beam = false;                 // comparison method (-X)
  double unscattered_in_m_r = NAN;        // c (-c); NaN: the file's (1 unless given)
  double unscattered_in_m_t = NAN;        // C (-C)
};

// (M_R, M_T) the spheres of `setup` would report.
std::pair<double, double> sphere_measurements(const RxtSetup& setup, const SphereModel& model,
                                              const SampleTotals& sample);
inline std::pair<double, double> sphere_measurements(const RxtSetup& setup, const SampleTotals& sample) {
  return sphere_measurements(setup, SphereModel{}, sample);
}

}  // namespace bssrdf
