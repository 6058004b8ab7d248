// A homogeneous layer from its discrete-ordinate modes (32 angles and more): the same discrete
// equations as the doubling, solved at any thickness without a thin start.
#include <gtest/gtest.h>

#include <cmath>

#include "../src/adding_doubling/angles.hpp"
#include "../src/adding_doubling/layer_modes.hpp"
#include "../src/adding_doubling/layer_operator.hpp"

namespace bssrdf::adding_doubling {
namespace {

// Largest difference of the reflected or transmitted flux for any incident angle.
double largest_difference(const LayerOperator& a, const LayerOperator& b) {
  return std::max((a.R_top - b.R_top).colwise().sum().cwiseAbs().maxCoeff(),
                  (a.T_down - b.T_down).colwise().sum().cwiseAbs().maxCoeff());
}

TEST(AddingDoublingModes, TwoLayersAddUpToTheLayerOfTheirSummedThickness) {
  // The modes' layers obey the adding equations exactly (no start-thickness error to accumulate).
  const Angles angles = make_angles(32, {std::sqrt(1 - 1 / (1.4 * 1.4))});
  for (const double g : {0.0, 0.9})
    for (const double albedo : {0.5, 0.9999}) {
      const auto modes = layer_modes(angles, delta_m_albedo(albedo, g, 32), phase_blocks(angles, g));
      ASSERT_TRUE(modes_well_conditioned(modes));
      for (const double tau : {0.003, 0.4, 7.0, 90.0}) {
        const auto whole = layer_from_modes(modes, tau);
        const auto added = add(layer_from_modes(modes, 0.3 * tau), layer_from_modes(modes, 0.7 * tau));
        EXPECT_LT(largest_difference(whole, added), 1e-11) << g << ' ' << albedo << ' ' << tau;
      }
    }
}

TEST(AddingDoublingModes, ThickLayersAgreeWithDoublingAndConservativeScatteringFallsBack) {
  // Thick layers: the doubling's thin-start error has died out and both give the same operators. At 16
  // angles homogeneous_layer doubles; the modes serve any angle count.
  const Angles angles = make_angles(16, {std::sqrt(1 - 1 / (1.3 * 1.3))});
  const auto phase = phase_blocks(angles, 0.8);
  const auto modes = layer_modes(angles, delta_m_albedo(0.99, 0.8, 16), phase);
  const double tau = 200.0 * (1 - 0.99 * std::pow(0.8, 32));  // delta-M scaled
  EXPECT_LT(largest_difference(layer_from_modes(modes, tau), homogeneous_layer(angles, 0.99, 0.8, 200.0, &phase)),
            1e-11);  // the doubling's rounding over its ~14 doublings: 2.5e-12
  // Without absorption the slowest mode does not decay (k = 0): homogeneous_layer doubles instead.
  EXPECT_FALSE(modes_well_conditioned(layer_modes(angles, 1.0, phase)));
}

}  // namespace
}  // namespace bssrdf::adding_doubling
