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

// ln u with the kernel's a b + c fused (M = Fused) or rounded twice (M = Unfused).
template <class M>
double log_with(double u) {
  const auto p = log_reduce(u);
  return log_finish<M>(p, p.f / (2.0 + p.f));
}

// Both the fused kernels and the unfused one (machines without FMA) must keep the error bounds.
template <class M>
void check_logarithm(const char* name) {
  std::uint64_t state = 12345;
  double worst = 0;
  const auto check = [&](double u) {
    const double ours = log_with<M>(u);
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
  std::printf("  log (%s): worst error %.3f ulp\n", name, worst);
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
      const double ours = log_finish<M>(p, s * factor);
      const double error =
          static_cast<double>(std::abs(static_cast<long double>(ours) - exact)) / ulp(static_cast<double>(exact));
      worst_perturbed = std::max(worst_perturbed, error);
    }
  }
  std::printf("  log (%s) with the quotient 4 ulp off: worst error %.3f ulp\n", name, worst_perturbed);
  EXPECT_LT(worst_perturbed, 1.5);
}

}  // namespace

TEST(MonteCarloKernel, LogarithmWithinOneUlp) {
  check_logarithm<Fused>("fused");
  check_logarithm<Unfused>("unfused");
  // The vector form is the same arithmetic.
  const d2 v = log_normal(d2{0.3, 0x1p-52});
  EXPECT_EQ(v[0], log_normal(0.3));
  EXPECT_EQ(v[1], log_normal(0x1p-52));
}

namespace {

template <class M>
void check_azimuth(const char* name) {
  std::uint64_t state = 777;
  double worst = 0, sum_c = 0, sum_s = 0;
  const auto check = [&](std::uint64_t v) {
    double c, s;
    azimuth_cos_sin<M>(v, c, s);
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
    azimuth_cos_sin<M>(v, c, s);
    sum_c += c;
    sum_s += s;
  }
  for (std::uint64_t q = 0; q < 4; ++q)
    for (std::uint64_t cell : {0ull, 1ull, 0x1fffffffull, 0x20000000ull, 0x3ffffffeull, 0x3fffffffull})
      check((q << 30) | cell);
  std::printf("  azimuth_cos_sin (%s): worst error %.3g; means of cos, sin over 1e6 draws %.2g %.2g\n", name, worst,
              sum_c / 1e6, sum_s / 1e6);
  EXPECT_LT(std::abs(sum_c / 1e6), 5 * std::sqrt(0.5 / 1e6));
  EXPECT_LT(std::abs(sum_s / 1e6), 5 * std::sqrt(0.5 / 1e6));
}

}  // namespace

TEST(MonteCarloKernel, AzimuthCosineAndSineAccurate) {
  check_azimuth<Fused>("fused");
  check_azimuth<Unfused>("unfused");
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

TEST(MonteCarloKernel, FusedKernelsGiveIdenticalResults) {
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
      settings.record_reflected = true;  // exit radii: bits the tallies' sums would round away
      BatchTally best;
      best.reset(binning.bins, true, 12);
      Rng rng_best(9, c, 3);
      trace_batch(geometry, settings, rng_best, 3000, best);
      EXPECT_GT(best.interactions, 3000u);
      for (const SimdLevel level : {SimdLevel::avx2, SimdLevel::sse2}) {
        BatchTally other;
        other.reset(binning.bins, true, 12);
        Rng rng_other(9, c, 3);
        settings.simd = level;
        trace_batch(geometry, settings, rng_other, 3000, other);
        EXPECT_EQ(best.interactions, other.interactions);
        for (int i = 0; i < kTotals; ++i) {
          EXPECT_EQ(best.sum[i], other.sum[i]) << i;
          EXPECT_EQ(best.sum_sq[i], other.sum_sq[i]) << i;
        }
        EXPECT_EQ(best.r_sum, other.r_sum);
        EXPECT_EQ(best.t_sq, other.t_sq);
        EXPECT_EQ(best.a_sum, other.a_sum);
        EXPECT_EQ(best.lost, other.lost);
        ASSERT_EQ(best.reflected.size(), other.reflected.size());
        for (std::size_t i = 0; i < best.reflected.size(); ++i)
          EXPECT_EQ(best.reflected[i].radius, other.reflected[i].radius) << i;
      }
    }
  }
  // Which kernels this machine compared (the same kernel twice where it lacks an instruction set).
  const auto name = [](SimdLevel k) {
    return k == SimdLevel::best ? "AVX-512" : k == SimdLevel::avx2 ? "AVX2" : k == SimdLevel::sse2 ? "SSE2+FMA" : "SSE2";
  };
  std::printf("  kernels compared on this machine: %s, %s, %s\n", name(kernel_for(SimdLevel::best)),
              name(kernel_for(SimdLevel::avx2)), name(kernel_for(SimdLevel::sse2)));
}

TEST(MonteCarloKernel, UnfusedKernelTracesTheSamePhotons) {
  // Processors without FMA run the kernel with each a b + c rounded twice. Rounding moves a photon
  // by a tiny fraction of its path, and the tallies depend on positions only through discrete
  // events (which bin, which side of a boundary), which a shift that small almost never flips: the
  // same photons leave at nearly the same radii, and the totals and the profile agree (compared as
  // two samples, within 5 sigma and by a chi-square, so that a wrong formula in either kernel fails).
  LayerStack stack;
  stack.channel_names = {"c0", "c1"};
  Layer medium;
  medium.sigma_a = {0.01, 0.5};
  medium.sigma_s = {10.0, 5.0};
  medium.g = {0.8, 0.0};
  medium.n = 1.4;
  medium.thickness = 30.0;
  stack.layers = {medium};
  const RadialBinning binning(BinSpacing::log, 30, 0.01, 10.0);
  for (std::size_t c = 0; c < 2; ++c) {
    const ChannelGeometry geometry = make_geometry(stack, c);
    TraceSettings settings;
    settings.binning = &binning;
    settings.max_interactions = 1'000'000;
    settings.record_reflected = true;
    BatchTally fused, unfused;
    fused.reset(binning.bins, false, 0);
    unfused.reset(binning.bins, false, 0);
    constexpr std::uint64_t photons = 100'000;
    Rng rng_fused(11, c, 0), rng_unfused(11, c, 0);
    trace_batch(geometry, settings, rng_fused, photons, fused);
    settings.simd = SimdLevel::unfused;
    trace_batch(geometry, settings, rng_unfused, photons, unfused);

    ASSERT_EQ(fused.reflected.size(), unfused.reflected.size()) << c;
    ASSERT_GT(fused.reflected.size(), photons / 10) << c;
    double worst = 0;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < fused.reflected.size(); ++i) {
      const ReflectedPhoton &a = fused.reflected[i], &b = unfused.reflected[i];
      EXPECT_EQ(a.scatterings, b.scatterings) << i;
      EXPECT_EQ(a.weight, b.weight) << i;
      // Per step of a mean free path: each step's rounding, ~1e-16 of it, adds to the shift.
      const double path = (a.scatterings + 1) / geometry.layers[0].sigma_t;
      worst = std::max(worst, std::abs(a.radius - b.radius) / path);
      differing += a.radius != b.radius;
    }
    // Measured 3e-11 (the rotation's 1 - uz^2 near the pole amplifies a rounding): a thousand times
    // below where a bin or a boundary would notice on the scale of a mean free path.
    EXPECT_LT(worst, 1e-9) << c;
    // With FMA on this machine the two really are different kernels.
    if (kernel_for(SimdLevel::sse2) != SimdLevel::unfused) {
      EXPECT_GT(differing, 0u) << c;
    }

    const auto variance_of_mean = [&](double sum, double sum_sq) {
      const double mean = sum / photons;
      return (sum_sq / photons - mean * mean) / photons;
    };
    for (const int i : {kR, kAbsorbed}) {
      const double a = fused.sum[i] / photons, b = unfused.sum[i] / photons;
      const double sigma = std::sqrt(variance_of_mean(fused.sum[i], fused.sum_sq[i]) +
                                     variance_of_mean(unfused.sum[i], unfused.sum_sq[i]));
      EXPECT_GT(a, 0.1) << c << " " << i;
      EXPECT_LT(std::abs(a - b), 5 * sigma) << c << " " << i << ": " << a << " vs " << b;
    }
    double chi2 = 0;
    int dof = 0;
    for (std::size_t k = 0; k < binning.bins; ++k) {
      const double var =
          variance_of_mean(fused.r_sum[k], fused.r_sq[k]) + variance_of_mean(unfused.r_sum[k], unfused.r_sq[k]);
      if (var <= 0) continue;
      const double d = (fused.r_sum[k] - unfused.r_sum[k]) / photons;
      chi2 += d * d / var;
      ++dof;
    }
    EXPECT_GT(dof, 20);
    // p = 1e-6 for 30 degrees of freedom is 81.
    EXPECT_LT(chi2, 81.0) << c;
    std::printf("  channel %zu: %zu reflected photons, %zu radii differ in their bits, worst by %.2g; R %.5f / %.5f, "
                "radial chi-square %.2g over %d bins\n",
                c, fused.reflected.size(), differing, worst, fused.sum[kR] / photons, unfused.sum[kR] / photons, chi2,
                dof);
  }
}
