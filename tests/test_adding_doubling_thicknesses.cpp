// Slabs of one medium at many thicknesses (transmission tables): solve_thicknesses shares the
// angles, boundaries and phase function between them and must give solve()'s totals bitwise.
#include <gtest/gtest.h>

#include <cstring>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf::adding_doubling {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(AddingDoublingThicknesses, SameTotalsAsOneSolvePerThickness) {
  Slab slab;
  slab.layers = {{0.05, 8.0, 0.85, 1.0}};
  slab.n = 1.4;
  slab.below = {{1.5, 1.0, 0.0}};  // a slide below: boundaries differ top and bottom
  const std::vector<double> thickness = {0.003, 0.05, 0.4, 1.0, 7.5, 60.0};
  for (const auto incidence : {Incidence::collimated, Incidence::diffuse}) {
    const auto shared = solve_thicknesses(slab, thickness, incidence);
    ASSERT_EQ(shared.size(), thickness.size());
    for (std::size_t k = 0; k < thickness.size(); ++k) {
      Slab one = slab;
      one.layers[0].thickness = thickness[k];
      const Totals alone = solve(one, incidence);
      EXPECT_TRUE(same_bits(shared[k].diffuse_reflectance, alone.diffuse_reflectance)) << thickness[k];
      EXPECT_TRUE(same_bits(shared[k].total_transmittance, alone.total_transmittance)) << thickness[k];
      EXPECT_TRUE(same_bits(shared[k].unscattered_transmittance, alone.unscattered_transmittance));
      EXPECT_TRUE(same_bits(shared[k].error_estimate, alone.error_estimate));
      EXPECT_EQ(shared[k].points, alone.points);
    }
  }
}

TEST(AddingDoublingThicknesses, RefusesStacksAndBadThicknesses) {
  Slab two;
  two.layers = {{0.1, 5.0, 0.5, 1.0}, {0.1, 5.0, 0.5, 1.0}};
  EXPECT_THROW(solve_thicknesses(two, {1.0}, Incidence::collimated), InvalidInput);
  Slab one;
  one.layers = {{0.1, 5.0, 0.5, 1.0}};
  EXPECT_THROW(solve_thicknesses(one, {1.0, -2.0}, Incidence::collimated), InvalidInput);
}

}  // namespace
}  // namespace bssrdf::adding_doubling
