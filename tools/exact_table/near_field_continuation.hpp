// The exact table generator's continuation of a node's multiple scattering below its first
// well-measured radius (generator version 9; data/exact/README.md): y_ms ~ r^s from that radius
// inward, s in [1, 2], chosen so the continued radii hold the energy the run tallied there.
#pragma once

#include <cmath>
#include <cstddef>

namespace bssrdf::exact_table {

// y_ms at radius index k < first, continued from y_first at index `first` with slope s in ln r.
inline double near_field_continued(double y_first, double slope, std::size_t k, std::size_t first, double d_ln_r) {
  return y_first * std::exp(slope * d_ln_r * (static_cast<double>(k) - static_cast<double>(first)));
}

// The slope s of ln y_ms in ln r below radius index `first` (radii spaced d_ln_r in ln r), where
// y_ms is `y_first` at that radius and the run's tallies at the `first` radii inside it sum to
// `pooled` (each radius's bin mean of y) with standard error `pooled_se`. As r -> 0 multiple
// scattering is flat in R (s = 2); within a mean free path of the entry a strongly forward medium
// is not there yet (R ~ 1/r, s = 1: single scattering's singularity, the strongest there is). The
// pooled tally decides where it is measured within 30 % (as a well-measured bin); else s = 2.
inline double near_field_slope(double y_first, double pooled, double pooled_se, std::size_t first, double d_ln_r) {
  const auto continued_sum = [&](double slope) {  // falls as the slope grows
    double sum = 0;
    for (std::size_t k = 0; k < first; ++k) sum += near_field_continued(y_first, slope, k, first, d_ln_r);
    return sum;
  };
  if (first == 0 || !(pooled > 0 && pooled_se < 0.3 * pooled) || pooled <= continued_sum(2)) return 2;
  if (pooled >= continued_sum(1)) return 1;
  double lo = 1, hi = 2;  // bisection: the sum at lo is above the tally, at hi below it
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    (continued_sum(mid) > pooled ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace bssrdf::exact_table
