// iad's constrained inversions (Prahl's iad 4: iad_pub.w determine_search, iad_find.w U_Find_*):
// one of the albedo a, the optical thickness b, mu_a or mu_s is held and the row's remaining
// unknowns are solved from what it measured.
//  - M_R and M_T, g not given: the other coefficient and g, matching both (iad's FIND_BG, FIND_AG,
//    FIND_BsG, FIND_BaG); with a = 0 only b, from M_T (FIND_B: without scattering M_R says nothing).
//  - M_R and M_T, g given: the other coefficient alone, from M_T alone (iad's one-parameter
//    searches match M_T and ignore M_R; the fitted M_R is reported).
//  - M_T alone: the other coefficient from M_T.
//  - M_R alone: with b held, a for that slab (FIND_A); with mu_a or mu_s held, a of a semi-infinite
//    sample (iad's U_Find_Bs and U_Find_Ba with M_T = 0) and the other coefficient from a; with
//    a held (0 < a < 1), g of a semi-infinite sample (FIND_G), mu_s = 1/mm by iad's convention.
// One unknown: a bracketing root search on the grid of its range then TOMS 748; two: the best
// point of a grid, then Levenberg-Marquardt (Ceres). Errors: linear propagation of the matched
// measurements' standard errors through the Jacobian, as invert_slab.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "bssrdf/fit/rxt_fit.hpp"
#include "slab_inversion.hpp"

namespace bssrdf {

// The quantity a row holds fixed, resolved from the options and the row's columns.
struct RowConstraint {
  enum class Kind { albedo, optical_thickness, mu_a, mu_s } kind = Kind::albedo;
  double value = 0;   // a, b, or 1/mm
  std::string label;  // "a = 0.9 (iad -a)"
};

// The row's constraint: an option where given, else the row's column; none when neither. Two at
// once (e.g. a and b) are refused with a one-line InvalidInput naming them, as is the power law
// on a row without a wavelength and a value out of range (a in [0, 1], b, mu_a, mu_s >= 0).
std::optional<RowConstraint> row_constraint(const RxtRow& row, const RxtConstraintOptions& options, double g_option);

// (M_R, M_T) of the instrument for a sample (sigma_a, sigma_s in 1/mm, g, thickness in mm or kSemiInfinite).
using SampleReadings = std::function<std::pair<double, double>(double sigma_a, double sigma_s, double g, double d)>;

struct ConstrainedSolution {
  SlabInversion inversion;  // parameters = (mu_a, mu_s', g) as iad reports them
  std::string search;       // what was held and what solved, e.g. "a = 0.9 (iad -a) held; b, g from M_R, M_T"
};

// g_held: the row's g when given (option --g or column g), NaN when not.
ConstrainedSolution solve_constrained(const RowConstraint& constraint, double m_r, double m_t, double r_stderr,
                                      double t_stderr, double g_held, double thickness, const SampleReadings& readings);

}  // namespace bssrdf
