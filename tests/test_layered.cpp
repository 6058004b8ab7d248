// Hankel transform round trips and layer stacks under the multipole: a one-layer stack is the
// multipole slab, a semi-infinite one the dipole, and the adding equations behave as they must.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "bssrdf/error.hpp"
#include "bssrdf/hankel.hpp"
#include "bssrdf/models/dipole.hpp"
#include "bssrdf/models/layered.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/profile.hpp"

using namespace bssrdf;

namespace {

Layer layer(double sigma_a, double sigma_s, double g, double n, double thickness, const char* name = "") {
  return Layer::of(Medium::single_channel(sigma_a, sigma_s, g, n), thickness, name);
}

LayerStack stack_of(std::vector<Layer> layers) {
  LayerStack s;
  s.channel_names = {"c0"};
  s.layers = std::move(layers);
  return s;
}

}  // namespace

TEST(Hankel, BesselZeros) {
  EXPECT_NEAR(bessel_j0_zero(1), 2.404825557695773, 1e-12);
  EXPECT_NEAR(bessel_j0_zero(2), 5.520078110286311, 1e-12);
  EXPECT_NEAR(bessel_j0_zero(10), 30.634606468431976, 1e-11);
  for (int m : {1, 5, 50, 500}) EXPECT_LT(std::abs(std::cyl_bessel_j(0.0, bessel_j0_zero(m))), 1e-13);
}

TEST(Hankel, KnownPairs) {
  // e^{-a r}/r <-> 1/sqrt(a^2 + k^2) and the Gaussian e^{-r^2/2} <-> e^{-k^2/2}.
  for (double k : {0.0, 0.3, 2.0, 10.0}) {
    EXPECT_NEAR(hankel_transform([](double r) { return std::exp(-1.5 * r) / r; }, k, 1.0), 1 / std::sqrt(2.25 + k * k),
                1e-9)
        << k;
    EXPECT_NEAR(hankel_transform([](double r) { return std::exp(-r * r / 2); }, k, 1.0), std::exp(-k * k / 2), 1e-10)
        << k;
  }
}

TEST(Hankel, RoundTripOfAMultipoleProfile) {
  // Forward: the numerical transform of R(r) against the closed-form spectrum. Inverse: the
  // numerical transform of the closed-form spectrum against R(r). Round trip: R -> F sampled on
  // a log grid of k (40 per decade, interpolated) -> R.
  const auto m = reduced_optical(0.99, 1.3);
  const multipole::Model model(3.0);
  const auto slab = model.slab(m);
  const auto spectrum = [&](double k) { return multipole::spectra_at_k(m, slab, k).reflectance(); };
  const auto R = [&](double r) { return model.reflectance(m, r); };
  double forward = 0, inverse = 0, trip = 0;
  for (double k : {0.0, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0}) {
    const double F = 2 * std::numbers::pi * hankel_transform(R, k, m.ell);
    forward = std::max(forward, std::abs(F / spectrum(k) - 1));
  }
  SampledProfile grid;  // F(k) on a log grid (SampledProfile's interpolation: cubic in log-log)
  grid.radius = log_spaced(1e-3, 40.0, 4 * 40 + 1);
  for (double k : grid.radius) grid.value.push_back(2 * std::numbers::pi * hankel_transform(R, k, m.ell));
  for (double r : {0.0, 0.1, 1.0, 3.0, 10.0, 20.0}) {
    const double back = hankel_transform([&](double k) { return spectrum(k); }, r, 1.0) / (2 * std::numbers::pi);
    inverse = std::max(inverse, std::abs(back / R(r) - 1));
    const double round =
        hankel_transform([&](double k) { return grid.interpolate(k); }, r, 1.0) / (2 * std::numbers::pi);
    std::printf("  r = %4.1f ell: R %.6e, inverse %.1e, round trip %.1e\n", r, R(r), back / R(r) - 1, round / R(r) - 1);
    if (r <= 10) trip = std::max(trip, std::abs(round / R(r) - 1));
    EXPECT_LT(std::abs(round - R(r)), 5e-5 * R(0.0)) << r;  // absolute: the grid's interpolation error
  }
  std::printf(
      "  Hankel transform, worst relative error: forward %.1e, inverse %.1e, round trip via a log grid %.1e (r <= 10 "
      "ell)\n",
      forward, inverse, trip);
  EXPECT_LT(forward, 1e-7);
  EXPECT_LT(inverse, 1e-8);
  // Interpolating a sampled spectrum costs accuracy where R(r) is small: the layered model therefore
  // transforms its closed-form spectra directly (the "inverse" column).
  EXPECT_LT(trip, 5e-4);
}

TEST(Layered, OneLayerIsTheMultipoleSlab) {
  const auto stack = stack_of({layer(0.02, 1.5, 0.0, 1.4, 3.0)});
  const layered::Stack model(stack, 0);
  const auto m = reduce(0.02, 1.5, 0.0, 1.4);
  const multipole::Model slab(3.0);
  EXPECT_NEAR(model.total_reflectance(), multipole::total_reflectance(m, slab.slab(m)), 1e-14);
  EXPECT_NEAR(model.total_transmittance(), multipole::total_transmittance(m, slab.slab(m)), 1e-14);
  for (double r : {0.0, 0.5, 2.0, 8.0}) {
    EXPECT_NEAR(model.reflectance(r) / slab.reflectance(m, r), 1.0, 1e-7) << r;
    EXPECT_NEAR(model.transmittance(r) / slab.transmittance(m, r), 1.0, 1e-7) << r;
  }
}

TEST(Layered, SemiInfiniteLayerIsTheDipole) {
  const auto stack = stack_of({layer(0.02, 1.5, 0.0, 1.3, kSemiInfinite)});
  const layered::Stack model(stack, 0);
  const auto m = reduce(0.02, 1.5, 0.0, 1.3);
  EXPECT_NEAR(model.total_reflectance(), classical_dipole::total_reflectance(m.albedo_prime, 1.3), 1e-14);
  EXPECT_EQ(model.total_transmittance(), 0.0);
  for (double r : {0.1, 1.0, 5.0})
    EXPECT_NEAR(model.reflectance(r) / classical_dipole::reflectance(m, r), 1.0, 1e-7) << r;
}

TEST(Layered, AddingEquationsBehave) {
  // A layer over a deep copy of itself (same index) is close to one thick slab; a darker
  // substrate lowers R and a brighter one raises it; a non-absorbing top layer keeps R + T = 1 at
  // k = 0 when nothing below absorbs either.
  const auto top = layer(0.01, 2.0, 0.0, 1.4, 2.0);
  const double alone = layered::Stack(stack_of({layer(0.01, 2.0, 0.0, 1.4, 40.0)}), 0).total_reflectance();
  const double stacked = layered::Stack(stack_of({top, layer(0.01, 2.0, 0.0, 1.4, 38.0)}), 0).total_reflectance();
  EXPECT_NEAR(stacked / alone, 1.0, 0.05);
  const double dark = layered::Stack(stack_of({top, layer(0.5, 2.0, 0.0, 1.4, kSemiInfinite)}), 0).total_reflectance();
  const double bright =
      layered::Stack(stack_of({top, layer(0.001, 2.0, 0.0, 1.4, kSemiInfinite)}), 0).total_reflectance();
  EXPECT_LT(dark, stacked);
  EXPECT_GT(bright, stacked);
  const layered::Stack conservative(stack_of({layer(0.0, 2.0, 0.0, 1.4, 3.0), layer(0.0, 1.0, 0.0, 1.3, 5.0)}), 0);
  EXPECT_NEAR(conservative.total_reflectance() + conservative.total_transmittance(), 1.0, 1e-9);
}

TEST(Layered, ThinLayersAndClearLayersAreReported) {
  const layered::Stack thin(
      stack_of({layer(0.01, 2.0, 0.0, 1.4, 0.5, "epidermis"), layer(0.01, 2.0, 0.0, 1.4, kSemiInfinite)}), 0);
  const auto report = thin.validity();
  EXPECT_EQ(worst(report), Severity::invalid);
  bool named = false;
  for (const auto& note : report) named |= note.code == "thin_layer" && note.message.find("epidermis") == 0;
  EXPECT_TRUE(named);
  EXPECT_THROW(layered::Stack(stack_of({layer(0.0, 0.0, 0.0, 1.5, 1.0), layer(0.01, 2.0, 0.0, 1.4, kSemiInfinite)}), 0),
               InvalidInput);
}
