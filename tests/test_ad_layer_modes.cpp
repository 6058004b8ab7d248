// A homogeneous layer from its discrete-ordinate modes (every finite layer not near conservative
// scattering): the same discrete equations as the doubling, solved at any thickness without a thin start.
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

TEST(AddingDoublingModes, AnyLayerAgreesWithDoublingFromAFarThinnerStart) {
  // The discrete equations' own solution, by doubling a start 2^24 times thinner than the layer (its
  // diamond-scheme error then negligible): the modes meet it at every thickness (measured within
  // 8.3e-9); doubled_layer, from a start up to 4 mu_min thick, is off by up to 0.13 at 8 angles and
  // 1.4e-3 at 32 for layers of tau 1e-3 to 3 (the start's error at the grazing angles, which doubling
  // damps only in thick layers).
  for (const int points : {8, 32}) {
    const Angles angles = make_angles(points, {std::sqrt(1 - 1 / (1.4 * 1.4))});
    for (const double g : {0.0, 0.9})
      for (const double albedo : {0.1, 0.9}) {
        const auto phase = phase_blocks(angles, g);
        const double albedo_m = delta_m_albedo(albedo, g, static_cast<std::size_t>(points));
        const auto modes = layer_modes(angles, albedo_m, phase);
        for (const double tau : {1e-3, 0.1, 3.0}) {
          constexpr int kDoublings = 24;
          LayerOperator reference = doubled_layer(angles, albedo_m, phase, std::ldexp(tau, -kDoublings));
          for (int k = 0; k < kDoublings; ++k) reference = add(reference, reference);
          EXPECT_LT(largest_difference(layer_from_modes(modes, tau), reference), 3e-8)
              << points << ' ' << g << ' ' << albedo << ' ' << tau;
        }
      }
  }
}

TEST(AddingDoublingModes, ThickLayersAgreeWithDoublingAndConservativeScatteringFallsBack) {
  // Thick layers: the doubling's thin-start error has died out and both give the same operators, at
  // every angle count the solver uses.
  for (const int points : {8, 16, 32}) {
    const Angles angles = make_angles(points, {std::sqrt(1 - 1 / (1.3 * 1.3))});
    const auto phase = phase_blocks(angles, 0.8);
    const double albedo_m = delta_m_albedo(0.99, 0.8, static_cast<std::size_t>(points));
    const auto modes = layer_modes(angles, albedo_m, phase);
    const double tau = 200.0 * (1 - 0.99 * std::pow(0.8, 2 * points));  // delta-M scaled
    // What is left is the doubling's thin-start error at the grazing angles, which shrinks as they do:
    // measured 1.0e-11 at 8 angles, 2.5e-12 at 16, 1.6e-13 at 32.
    EXPECT_LT(largest_difference(layer_from_modes(modes, tau), doubled_layer(angles, albedo_m, phase, tau)), 3e-11)
        << points;
    // homogeneous_layer takes the modes.
    EXPECT_EQ(largest_difference(layer_from_modes(modes, tau), homogeneous_layer(angles, 0.99, 0.8, 200.0, &phase)),
              0.0)
        << points;
  }
  // Without absorption the slowest mode does not decay (k = 0): homogeneous_layer doubles instead.
  const Angles angles = make_angles(16, {std::sqrt(1 - 1 / (1.3 * 1.3))});
  const auto phase = phase_blocks(angles, 0.8);
  EXPECT_FALSE(modes_well_conditioned(layer_modes(angles, 1.0, phase)));
  const double tau = 5.0 * (1 - std::pow(0.8, 32));  // delta-M scaled
  EXPECT_EQ(
      largest_difference(homogeneous_layer(angles, 1.0, 0.8, 5.0, &phase), doubled_layer(angles, 1.0, phase, tau)),
      0.0);
}

}  // namespace
}  // namespace bssrdf::adding_doubling
