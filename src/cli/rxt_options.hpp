// The options of 'bssrdf fit slab --rxt' that describe iad's instrument beyond the file (iad's
// -H, -f, -X, -c, -C, -q and the detector reflectance), each with iad 4's default, and iad's
// constraints -a, -b, -A, -F (a number or the power law 'P lambda0 mu_s0 gamma') and -j.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "bssrdf/fit/rxt_fit.hpp"

namespace bssrdf::cli {

struct RxtSphereOptions {
  std::string baffles = "both", wall_first, detector_reflectance, unscattered_in_m_r, unscattered_in_m_t;
  bool dual_beam = false;
  int quadrature = 0;
  std::string albedo, optical_thickness, mu_a, mu_s, mu_s_prime;  // the constraints (empty: not given)
  std::string incidence;                                          // iad's -i (degrees)
};

void add_rxt_sphere_options(CLI::App& command, RxtSphereOptions& o);
// Whether any was given (they need --rxt).
bool any_rxt_sphere_option(const RxtSphereOptions& o);
void apply_rxt_sphere_options(const RxtSphereOptions& o, RxtFitOptions& options);

}  // namespace bssrdf::cli
