// iad 4 (Prahl, iad_find.w U_Find_AB) searches the albedo a in [0, 1] and the optical thickness b
// with a bounded Nelder-Mead simplex started from a grid; it flags a row 'x' (IAD_SEARCH_STALLED,
// iad_main.w) when the simplex collapses before its distance to M_R, M_T falls below its
// tolerance. On iad's 62 test files (8 angles, -M 0) it does so on 195 rows that ours solves:
// 192 lie within 0.31 % of the edge a = 1, where iad stops at a = 1 (it reports mu_a = 0), and
// 3 on the edge a = 0 (no scattering). Whether iad stalls depends on its simplex's path, which we
// do not reproduce; every converged row within kIadEdgeAlbedo (1 %, three times the largest
// distance seen) of either edge is marked instead, so a superset of iad's stalled rows is.
// Ours searches ln mu_a and ln mu_s', which have no edge where iad's do (a -> 1 is ln mu_a -> -inf),
// so it reaches solutions just inside an edge; the status says so with the chi^2 that shows it.
#include "iad_search_edge.hpp"

#include <cmath>
#include <cstdio>

#include "bssrdf/error.hpp"

namespace bssrdf {

namespace {

std::string digits(double v, int significant) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

std::string reproduced(double chi2) {
  return "reproduces M_R, M_T to chi^2 = " + digits(chi2, 2) + " (within their errors: <= 4)";
}

}  // namespace

std::string converged_status(double mu_a, double mu_s_prime, double g, double chi2) {
  const double mu_s = mu_s_prime / (1 - g);
  const double a = mu_s / (mu_a + mu_s);
  const std::string iad =
      "iad's search (a bounded simplex in the albedo a in [0, 1]) may stop on that edge and flag "
      "the row 'x'";
  // Ours reaching its own bound (ln mu_a or ln mu_s' at -25) counts as the edge.
  if (mu_a <= 1e-9 * mu_s)
    return "converged at the edge mu_a = 0 (a = 1): only no absorption " + reproduced(chi2) + "; " + iad;
  if (mu_s <= 1e-9 * mu_a)
    return "converged at the edge mu_s' = 0 (a = 0): only no scattering " + reproduced(chi2) +
           " (M_R at or below a clear sample's within its error); " + iad;
  const std::string near =
      "converged; albedo a = " + digits(a, 6) + ", within " + digits(kIadEdgeAlbedo * 100, 3) + " % of ";
  if (1 - a < kIadEdgeAlbedo)
    return near + "1: " + iad + " (at a = 1, mu_a = 0); ours searches ln mu_a, which has no edge there, and " +
           reproduced(chi2);
  if (a < kIadEdgeAlbedo)
    return near + "0: " + iad + " (at a = 0, mu_s = 0); ours searches ln mu_s', which has no edge there, and " +
           reproduced(chi2);
  return "converged";
}

}  // namespace bssrdf
