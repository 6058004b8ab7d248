// The exact table generator's near-field continuation (tools/exact_table/near_field_continuation.hpp):
// the slope below a node's first well-measured radius holds the energy the run tallied there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "../tools/exact_table/near_field_continuation.hpp"

using bssrdf::exact_table::near_field_slope;

namespace {

constexpr double kStep = 0.19188209108483255;  // the table's ln-radius step, ln 10 / 12

// What a run tallies at the `first` radii r_k = r_first e^{(k - first) step} inside the first measured
// one when y follows the power law y0 (r / r_first)^s there.
double tally(double y0, double s, std::size_t first) {
  double sum = 0;
  for (std::size_t k = 0; k < first; ++k) {
    const double r_over_first = std::exp(kStep * (static_cast<double>(k) - static_cast<double>(first)));
    sum += y0 * std::pow(r_over_first, s);
  }
  return sum;
}

}  // namespace

TEST(NearFieldContinuation, RecoversThePowerLawTheTallyHolds) {
  // A measured near field that is a power law between single scattering's (s = 1) and flat R (s = 2)
  // gives back its slope, whatever the value at the first measured radius.
  for (double s : {1.0, 1.17, 1.5, 1.83, 2.0})
    for (std::size_t first : {3u, 10u, 25u})
      EXPECT_NEAR(near_field_slope(2.5, tally(2.5, s, first), 0.01 * tally(2.5, s, first), first, kStep), s, 1e-9)
          << s << " " << first;
}

TEST(NearFieldContinuation, StaysBetweenSingleScatteringAndFlatR) {
  // More energy inside than R ~ 1/r can hold: s = 1 (no singularity stronger than single
  // scattering's); less than flat R holds: s = 2, the r -> 0 limit (version 8's rule).
  EXPECT_EQ(near_field_slope(1.0, 3 * tally(1.0, 1.0, 10), 0.01, 10, kStep), 1.0);
  EXPECT_EQ(near_field_slope(1.0, 0.5 * tally(1.0, 2.0, 10), 0.001, 10, kStep), 2.0);
}

TEST(NearFieldContinuation, AnUnmeasuredTallyKeepsFlatR) {
  // The pooled tally decides only where it is measured within 30 %, as a well-measured bin; no radii
  // inside, or nothing tallied: flat R.
  const double pooled = tally(1.0, 1.3, 12);
  EXPECT_NEAR(near_field_slope(1.0, pooled, 0.29 * pooled, 12, kStep), 1.3, 1e-9);
  EXPECT_EQ(near_field_slope(1.0, pooled, 0.31 * pooled, 12, kStep), 2.0);
  EXPECT_EQ(near_field_slope(1.0, 0.0, 0.0, 12, kStep), 2.0);
  EXPECT_EQ(near_field_slope(1.0, pooled, 0.0, 0, kStep), 2.0);
}
