// The multipole against the Monte Carlo reference on the same geometry: a slab at 2 and 8 ell (g = 0
// and, with the same reduced coefficients, g = 0.9) and
// two- and three-layer stacks (a thin epidermis-like layer over dermis-like ones). Like with like:
// per ENTERED flux; R is the MC's diffuse reflectance (single scattering included, as in the
// adding-doubling comparison of the dipoles), T the MC's total transmittance minus its ballistic
// part. Radial profiles compare the model averaged over each MC bin with the bin, for bins from 2
// transport mean free paths of the top layer to where the MC's relative error stays below 10 %.
//
// The model's error is systematic; each case asserts the error measured here (rounded up, the
// documented behaviour in the README) plus 4 MC standard errors. 100 000 photons per case.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "bssrdf/models/layered.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/quadrature.hpp"

using namespace bssrdf;

namespace {

Layer layer(double sigma_a, double sigma_s, double n, double thickness, const char* name, double g = 0) {
  return Layer::of(Medium::single_channel(sigma_a, sigma_s, g, n), thickness, name);
}

struct Documented {
  double R_total, T_total, R_radial, T_radial;  // worst |relative error| allowed (measured)
};

void compare(const char* label, std::vector<Layer> layers, double r_max, Documented documented) {
  LayerStack stack;
  stack.channel_names = {"c0"};
  stack.layers = std::move(layers);
  MonteCarloOptions o;
  o.photons = 100000;
  o.seed = 3;
  o.bins = 40;
  o.r_max = r_max;
  const auto result = run_monte_carlo(stack, o);
  const auto c = result.channels[0].per_entered_flux();
  const layered::Stack model(stack, 0);
  const double R_mc = c.diffuse_reflectance.value - c.unscattered_reflectance.value;
  const double T_mc = c.total_transmittance.value - c.unscattered_transmittance.value;
  const double R = model.total_reflectance(), T = model.total_transmittance();
  std::printf("  %-34s R_total %.4f vs MC %.4f +- %.4f (%+5.1f%%)   T_total %.4f vs MC %.4f +- %.4f (%+5.1f%%)\n",
              label, R, R_mc, c.diffuse_reflectance.standard_error, 100 * (R / R_mc - 1), T, T_mc,
              c.total_transmittance.standard_error, 100 * (T / T_mc - 1));
  EXPECT_LE(std::abs(R - R_mc), documented.R_total * R_mc + 4 * c.diffuse_reflectance.standard_error) << label;
  EXPECT_LE(std::abs(T - T_mc), documented.T_total * T_mc + 4 * c.total_transmittance.standard_error) << label;

  // Radial: the model averaged over each bin (4-point Gauss in r, weight r).
  const auto bin_average = [&](bool transmitted, std::size_t i) {
    const double a = result.bin_inner[i], b = result.bin_outer[i];
    const auto f = [&](double r) { return (transmitted ? model.transmittance(r) : model.reflectance(r)) * r; };
    return integrate_gauss_legendre<double>(f, a, b, 4) * 2 / (b * b - a * a);
  };
  double worst[2] = {0, 0};
  int compared[2] = {0, 0};
  const double r_from = 2 * model.medium(0).ell;
  for (int t = 0; t < 2; ++t) {
    const auto& value = t ? c.transmittance : c.reflectance;
    const auto& error = t ? c.transmittance_stderr : c.reflectance_stderr;
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (result.bin_inner[i] < r_from || !(error[i] < 0.1 * value[i])) continue;
      const double m = bin_average(t == 1, i), deviation = std::abs(m / value[i] - 1);
      worst[t] = std::max(worst[t], deviation);
      ++compared[t];
      EXPECT_LE(std::abs(m - value[i]), (t ? documented.T_radial : documented.R_radial) * value[i] + 4 * error[i])
          << label << (t ? " T" : " R") << " bin r = " << result.bin_radius[i];
    }
  }
  std::printf("  %-34s R(r): %2d bins, worst %5.1f%%   T(r): %2d bins, worst %5.1f%%  (r >= 2 ell = %.2f mm)\n", "",
              compared[0], 100 * worst[0], compared[1], 100 * worst[1], r_from);
  EXPECT_GT(compared[0], 5);
}

}  // namespace

TEST(MultipoleMonteCarlo, SlabAtTwoTransportMeanFreePaths) {
  // eta 1.3, alpha' 0.99, g 0, ell = 1 mm (the multipole slab check of tests/data/REFERENCE_CHECKS.md).
  compare("slab d = 2 ell", {layer(0.01, 0.99, 1.3, 2.0, "slab")}, 8.0, {0.04, 0.31, 0.23, 0.39});
}

TEST(MultipoleMonteCarlo, SlabAtEightTransportMeanFreePaths) {
  compare("slab d = 8 ell", {layer(0.01, 0.99, 1.3, 8.0, "slab")}, 8.0, {0.02, 0.01, 0.11, 0.12});
}

TEST(MultipoleMonteCarlo, ForwardScatteringSlabAtEightTransportMeanFreePaths) {
  // The same reduced coefficients with g = 0.9 (sigma_s = 9.9): the multipole sees only sigma_s',
  // the Monte Carlo the true Henyey-Greenstein phase function.
  compare("slab d = 8 ell, g = 0.9", {layer(0.01, 9.9, 1.3, 8.0, "slab", 0.9)}, 8.0, {0.02, 0.01, 0.20, 0.12});
}

TEST(MultipoleMonteCarlo, ForwardScatteringSlabAtTwoTransportMeanFreePaths) {
  compare("slab d = 2 ell, g = 0.9", {layer(0.01, 9.9, 1.3, 2.0, "slab", 0.9)}, 8.0, {0.02, 0.03, 0.22, 0.18});
}

TEST(MultipoleMonteCarlo, TwoLayers) {
  // An epidermis-like layer (ell = 0.2 mm, 2.5 ell thick) over a thicker dermis-like one.
  compare("2 layers (0.5 mm over 5 mm)",
          {layer(0.05, 5.0, 1.4, 0.5, "epidermis"), layer(0.02, 2.0, 1.4, 5.0, "dermis")}, 4.0,
          {0.02, 0.02, 0.19, 0.24});
}

TEST(MultipoleMonteCarlo, ThreeLayers) {
  compare("3 layers (0.5, 1, 4 mm)",
          {layer(0.05, 5.0, 1.4, 0.5, "epidermis"), layer(0.1, 3.0, 1.4, 1.0, "papillary dermis"),
           layer(0.02, 2.0, 1.35, 4.0, "reticular dermis")},
          4.0, {0.02, 0.08, 0.20, 0.34});
}
