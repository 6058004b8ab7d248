// What Blender's Cycles simulates for a Principled BSDF's subsurface inputs, and the inputs that
// make it simulate a given medium. Transcribed from Cycles' kernel (Blender 3.4 ships it in the
// Cycles add-on's source/kernel/; Blender 4.x's is in intern/cycles/kernel/):
//
//   closure radius   R = Subsurface Radius x Subsurface (3.x) or x Subsurface Scale (4.x), per channel
//   albedo colour    C = Subsurface Color w + Base Color (1 - w) (3.x, w = Subsurface) or Base Color (4.x)
//   bssrdf_setup_radius (closure/bssrdf.h):
//     fixed radius   R_eff = R / (4 pi)                        3.x RANDOM_WALK_FIXED_RADIUS, 4.x RANDOM_WALK
//     radius remap   R_eff = R sqrt(3 (1 - alpha'(C, eta)))     3.x RANDOM_WALK, 4.x RANDOM_WALK_SKIN
//                    alpha' inverts the classical dipole total  (Jensen et al. 2001, eq. for R_d with
//                    A from F_dr(eta), Egan-Hilgeman fit) by a 12-step bisection
//   subsurface_random_walk_remap (integrator/subsurface_random_walk.h):
//     sigma_t = 1 / (R_eff (1 - g)), g clamped to [0, 0.9]
//     alpha   = a fit in (C, g) (Chiang, Kutz, Burley 2016, with Pixar's anisotropic extension),
//               clamped to [0, 0.999999]; below 0.2 Cycles raises it to 0.2 and scales the
//               throughput by alpha / 0.2 instead (a different medium: the file says so)
//   Christensen-Burley (bssrdf_burley_setup): R(r) = C (e^{-r/d} + e^{-r/3d}) / (8 pi d r),
//     d = R / (4 pi) / s(C), s(A) = 1.9 - A + 3.5 (A - 0.8)^2 (Christensen & Burley 2015, eq. 6)
//
// The functions evaluate in float, as the kernel does, so the inversion hits Cycles' own numbers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/medium.hpp"

namespace bssrdf {

// How the closure radius becomes the medium (the Cycles method, named by what it does).
enum class CyclesMapping { fixed_radius, radius_remap, burley };
// "fixed-radius", "radius-remap", "burley"; InvalidInput naming `field` otherwise.
CyclesMapping parse_cycles_mapping(std::string_view text, std::string_view field = "blender_method");
std::string_view to_string(CyclesMapping mapping);
// Blender's enum identifier for the method in that major version (3 or 4).
std::string_view blender_method_identifier(CyclesMapping mapping, int blender_major);

// Cycles' kernel functions.
float cycles_random_walk_alpha(float albedo_color, float g);  // subsurface_random_walk_remap
float cycles_dipole_alpha_prime(float total, float eta);      // bssrdf_dipole_compute_alpha_prime
float cycles_burley_scaling(float A);                         // bssrdf_burley_fitting
// R_eff / R for one channel (bssrdf_setup_radius); eta is clamped to [1.01, 3.8] first.
float cycles_radius_factor(CyclesMapping mapping, float albedo_color, float eta);

// The medium Cycles simulates from closure values (radius R and colour C per channel, in the scene
// unit). Random walks: sigma_t (1/unit) and alpha; Burley: d (unit) and A = C.
struct CyclesSimulated {
  std::vector<double> sigma_t, alpha, throughput_scale;  // random walks
  std::vector<double> burley_d, burley_A;                // Christensen-Burley
  double g = 0;
};
CyclesSimulated cycles_simulated(CyclesMapping mapping, const std::vector<double>& albedo_color,
                                 const std::vector<double>& radius, double eta, double anisotropy);

// The inputs that make Cycles simulate `medium` (needs three channels; lengths in `unit`).
struct CyclesInputs {
  CyclesMapping mapping = CyclesMapping::fixed_radius;
  std::vector<double> albedo_color;  // Base Color (and 3.x Subsurface Color)
  std::vector<double> radius;        // closure radius R per channel, scene unit
  double eta = 1.3;                  // Subsurface IOR (clamped to [1.01, 3.8])
  double g = 0;                      // Subsurface Anisotropy (in [0, 0.9])
  // What Cycles will simulate with these inputs (cycles_simulated), and what we asked for.
  CyclesSimulated simulated;
  std::vector<double> target_sigma_t, target_alpha;  // after g was moved into [0, 0.9] (1/unit)
  std::vector<std::string> notes;                    // where Cycles cannot represent the medium, one line each
};
CyclesInputs cycles_inputs(const Medium& medium, const DerivedQuantities& derived, CyclesMapping mapping,
                           double millimetres_per_unit);

}  // namespace bssrdf
