// The Monte Carlo tracer's arithmetic kernels (src/montecarlo/fastmath.hpp) against long-double
// references, and the vectorised tracer's independence of the instruction set.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>

#include "../src/montecarlo/fastmath.hpp"
#include "../src/montecarlo/tracer.hpp"

using namespace bssrdf;
using namespace bssrdf::mc;

namespace {

double ulp(double x) { return std::nextafter(std::abs(x), INFINITY) - std::abs(x); }

}  // namespace

TEST(MonteCarloKernel, LogarithmWithinOneUlp) {
  std::uint64_t state = 12345;
  double worst = 0;
  const auto check = [&](double u) {
    const double ours = log_normal(u);
    const auto exact = std::log(static_cast<long double>(u));
    if (u == 1.0) {
      EXPECT_EQ(ours, 0.0);
      return;
    }
    const double error =
        static_cast<double>(std::abs(static_cast<long double>(ours) - exact)) / ulp(static_cast<double>(exact));
    worst = std::max(worst, error);
    EXPECT_LT(error, 1.0) << u;
  };
  for (int i = 0; i < 1'000'000; ++i) check(uniform_open0_52(splitmix64(state)));
  for (int e = -1022; e <= 1023; e += 7) check(std::ldexp(1.37, e));
  for (double u : {1.0, 0x1p-52, 0.5, std::nextafter(1.0, 0.0), 0.70710678118654752440, 0.7071067811865475,
                   0.7071067811865476, 1.4142135623730951, 1 - 0x1p-40, 1 + 0x1p-40, 3.0, 1e300, 1e-300})
    check(u);
  std::printf("  log_normal: worst error %.3f ulp\n", worst);
  // The tracer shares one reciprocal between divisions: a quotient s a few ulp off must still give
  // the logarithm to about 1 ulp.
  double worst_perturbed = 0;
  for (int i = 0; i < 200'000; ++i) {
    const double u = uniform_open0_52(splitmix64(state));
    if (u == 1.0) continue;
    const auto p = log_reduce(u);
    const double s = p.f / (2.0 + p.f);
    const auto exact = std::log(static_cast<long double>(u));
    for (const double factor : {1 + 4 * 0x1p-53, 1 - 4 * 0x1p-53}) {
      const double ours = log_finish(p, s * factor);
      const double error =
          static_cast<double>(std::abs(static_cast<long double>(ours) - exact)) / ulp(static_cast<double>(exact));
      worst_perturbed = std::max(worst_perturbed, error);
    }
  }
  std::printf("  log with the quotient 4 ulp off: worst error %.3f ulp\n", worst_perturbed);
  EXPECT_LT(worst_perturbed, 1.5);
  // The vector form is the same arithmetic.
  const d2 v = log_normal(d2{0.3, 0x1p-52});
  EXPECT_EQ(v[0], log_normal(0.3));
  EXPECT_EQ(v[1], log_normal(0x1p-52));
}

TEST(MonteCarloKernel, AzimuthCosineAndSineAccurate) {
  std::uint64_t state = 777;
  double worst = 0, sum_c = 0, sum_s = 0;
  const auto check = [&](std::uint64_t v) {
    double c, s;
    azimuth_cos_sin(v, c, s);
    // The angle this v stands for: quadrant q (bits 31-30), cell midpoint of the other 30 bits.
    const long double q = static_cast<long double>((v >> 30) & 3), cell = static_cast<long double>(v & 0x3fffffff);
    const long double phi = (q + (cell + 0.5L) / 1073741824.0L) * std::numbers::pi_v<long double> / 2;
    worst = std::max(
        {worst, static_cast<double>(std::abs(c - std::cos(phi))), static_cast<double>(std::abs(s - std::sin(phi)))});
    EXPECT_LT(std::abs(c - std::cos(phi)), 4e-16L) << v;
    EXPECT_LT(std::abs(s - std::sin(phi)), 4e-16L) << v;
    EXPECT_LT(std::abs(c * c + s * s - 1), 1e-15) << v;  // includes the rounding of c^2 + s^2
  };
  for (int i = 0; i < 1'000'000; ++i) {
    const std::uint64_t v = splitmix64(state);
    check(v);
    double c, s;
    azimuth_cos_sin(v, c, s);
    sum_c += c;
    sum_s += s;
  }
  for (std::uint64_t q = 0; q < 4; ++q)
    for (std::uint64_t cell : {0ull, 1ull, 0x1fffffffull, 0x20000000ull, 0x3ffffffeull, 0x3fffffffull})
      check((q << 30) | cell);
  std::printf("  azimuth_cos_sin: worst error %.3g; means of cos, sin over 1e6 draws %.2g %.2g\n", worst, sum_c / 1e6,
              sum_s / 1e6);
  EXPECT_LT(std::abs(sum_c / 1e6), 5 * std::sqrt(0.5 / 1e6));
  EXPECT_LT(std::abs(sum_s / 1e6), 5 * std::sqrt(0.5 / 1e6));
  d2 vc, vs;
  azimuth_cos_sin(u2{0x12345678ull, 0xfedcba98ull}, vc, vs);
  double c0, s0, c1, s1;
  azimuth_cos_sin(std::uint64_t{0x12345678ull}, c0, s0);
  azimuth_cos_sin(std::uint64_t{0xfedcba98ull}, c1, s1);
  EXPECT_EQ(vc[0], c0);
  EXPECT_EQ(vs[0], s0);
  EXPECT_EQ(vc[1], c1);
  EXPECT_EQ(vs[1], s1);
}

TEST(MonteCarloKernel, UniformsInTheirIntervals) {
  EXPECT_EQ(uniform_open0_52(std::uint64_t{0}), 1.0);
  EXPECT_EQ(uniform_open0_52(~std::uint64_t{0}), 0x1p-52);
  EXPECT_EQ(uniform_mid32(std::uint64_t{0}), 0x1p-33);
  EXPECT_EQ(uniform_mid32(std::uint64_t{0xffffffff}), 1 - 0x1p-33);
  EXPECT_EQ(uniform_mid32(std::uint64_t{0x80000000}), 0.5 + 0x1p-33);
}

TEST(MonteCarloKernel, Sse2AndAvx2GiveIdenticalTallies) {
  // A two-layer stack with an index step, a clear top layer, isotropic and forward scattering and
  // depth bins: every path of the tracer. Implicit capture and analog absorption.
  LayerStack stack;
  stack.channel_names = {"c0", "c1"};
  Layer glass;
  glass.sigma_a = {0, 0};
  glass.sigma_s = {0, 0};
  glass.g = {0, 0};
  glass.n = 1.5;
  glass.thickness = 0.2;
  Layer a;
  a.sigma_a = {0.05, 0.3};
  a.sigma_s = {2.0, 1.0};
  a.g = {0.8, 0.0};
  a.n = 1.4;
  a.thickness = 0.7;
  Layer b = a;
  b.g = {-0.3, 0.95};
  b.n = 1.33;
  b.thickness = 2.0;
  stack.layers = {glass, a, b};
  const RadialBinning binning(BinSpacing::log, 40, 0.01, 5.0);
  for (const auto absorption : {AbsorptionEstimator::implicit_capture, AbsorptionEstimator::analog}) {
    for (std::size_t c = 0; c < 2; ++c) {
      const ChannelGeometry geometry = make_geometry(stack, c);
      TraceSettings settings;
      settings.binning = &binning;
      settings.transmission_bins = true;
      settings.depth_bins = 12;
      settings.inv_depth_width = 12 / stack.depth();
      settings.absorption = absorption;
      settings.roulette_threshold = 0.1;
      settings.roulette_survival = 0.5;
      settings.max_interactions = 100000;
      BatchTally best, sse2;
      best.reset(binning.bins, true, 12);
      sse2.reset(binning.bins, true, 12);
      Rng rng_best(9, c, 3), rng_sse2(9, c, 3);
      trace_batch(geometry, settings, rng_best, 3000, best);
      settings.simd = SimdLevel::sse2;
      trace_batch(geometry, settings, rng_sse2, 3000, sse2);
      EXPECT_EQ(best.interactions, sse2.interactions);
      EXPECT_GT(best.interactions, 3000u);
      for (int i = 0; i < kTotals; ++i) {
        EXPECT_EQ(best.sum[i], sse2.sum[i]) << i;
        EXPECT_EQ(best.sum_sq[i], sse2.sum_sq[i]) << i;
      }
      EXPECT_EQ(best.r_sum, sse2.r_sum);
      EXPECT_EQ(best.t_sq, sse2.t_sq);
      EXPECT_EQ(best.a_sum, sse2.a_sum);
      EXPECT_EQ(best.lost, sse2.lost);
    }
  }
  std::printf("  AVX2 %s on this machine\n",
              avx2_available() ? "available: compared with SSE2" : "not available: SSE2 only");
}
