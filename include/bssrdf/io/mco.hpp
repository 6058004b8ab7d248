// MCML output files (.mco; Wang, Jacques & Zheng 1995, MCML 1.2.2 mcmlio.c WriteResult), so MCML's
// readers and its CONV convolution program read our Monte Carlo runs. ASCII, cm and 1/cm, per unit
// incident flux, in MCML's order: version "A1", InParm, RAT (R_sp, R_d, A, T_t), then A_l, A_z,
// Rd_r, Rd_a, Tt_r, Tt_a (one number a line) and A_rz, Rd_ra, Tt_ra (five a line), each array
// after its label line.
//
// What we tally and what we do not (stated in '#' lines before each label, which MCML's reader
// skips):
//   Rd_r, Tt_r  our radial bins (bin width dr = r_max / bins); light beyond the last bin is added
//               to it, as MCML does; Tt_r is empty (zeros) for a semi-infinite stack
//   A_z         absorbed fraction per unit depth; absorption below nz dz goes to the last bin, as
//               MCML does; zeros when depth bins were off
//   A_l         from A_z, each bin credited to the layer holding its centre (MCML's IzToLayer)
//   Rd_a, Tt_a, Rd_ra, Tt_ra  not tallied (no exit angles): exact when na = 1 (one bin holds the
//               whole hemisphere; MCML's solid-angle scaling applied), zeros otherwise
//   A_rz        not tallied (no radius of absorption): zeros
// One channel per file (an .mci run has one).
#pragma once

#include <string>

#include "bssrdf/montecarlo.hpp"

namespace bssrdf {

// `output_name` is written into InParm; `angle_bins` is the .mci's na.
std::string format_mco(const MonteCarloResult& result, const std::string& output_name, int angle_bins);

}  // namespace bssrdf
