// SampledProfile: integration accuracy on log-spaced radii, energy radii, interpolation, validation.
#include <gtest/gtest.h>

#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/profile.hpp"

using namespace bssrdf;

namespace {
// A dipole profile over 6 decades of radius, sampled on n log-spaced radii.
SampledProfile sampled(std::size_t n, const Reduced<double>& m, const Model& model) {
  return model.sample(m, log_spaced(1e-3 * m.ell, model.radius_for_fraction(m, 0.999999), n));
}
}  // namespace

TEST(Profile, IntegralConvergesAtFourthOrderOnLogRadii) {
  const auto model = make_model("better-dipole");
  const auto m = reduce_prime(0.032, 0.74, 1.3);
  const double exact = model->cumulative_reflectance(m, sampled(2, m, *model).radius.back());
  double previous_error = 1;
  for (std::size_t n : {32, 64, 128, 256}) {
    const double error = std::abs(sampled(n, m, *model).integrate() / exact - 1);
    std::printf("  %3zu log-spaced samples: relative integration error %.2e\n", n, error);
    if (n >= 64) {
      EXPECT_LT(error, previous_error / 8) << n;
    }  // 4th order: /16 per doubling
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-6);
  EXPECT_LT(std::abs(sampled(64, m, *model).integrate() / exact - 1), 1e-3);
}

TEST(Profile, CumulativeAndEnergyRadius) {
  const auto model = make_model("dipole");
  const auto m = reduce_prime(0.01, 2.0, 1.4);
  const auto p = sampled(400, m, *model);
  for (double r : {0.01, 0.5, 3.0}) EXPECT_NEAR(p.cumulative(r) / model->cumulative_reflectance(m, r), 1.0, 1e-5) << r;
  // The sampled profile's 90 % radius matches the model's (the profile holds 99.9999 % of the total).
  EXPECT_NEAR(p.radius_for_fraction(0.9) / model->radius_for_fraction(m, 0.9), 1.0, 1e-4);
  EXPECT_THROW(p.radius_for_fraction(0.0), InvalidInput);
  EXPECT_THROW(p.radius_for_fraction(1.5), InvalidInput);
}

TEST(Profile, InterpolationBetweenSamples) {
  // Cubic Hermite in (ln r, ln R) with three-point slopes: third order, so doubling the samples
  // cuts the worst error between samples by about 8.
  const auto model = make_model("better-dipole");
  const auto m = reduce_prime(0.05, 1.0, 1.3);
  double previous = 1;
  for (std::size_t n : {48, 96, 192}) {
    const auto p = model->sample(m, log_spaced(1e-3, 30.0, n));
    double worst = 0;
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const double r = std::sqrt(p.radius[i] * p.radius[i + 1]);  // midway in log r
      worst = std::max(worst, std::abs(p.interpolate(r) / model->reflectance(m, r) - 1));
    }
    std::printf("  worst relative interpolation error between %zu log samples: %.2e\n", n, worst);
    EXPECT_LT(worst, previous / 6) << n;
    previous = worst;
    if (n == 96) {
      EXPECT_LT(worst, 1e-3);  // documented in profile.hpp: ~20 samples per decade
      EXPECT_DOUBLE_EQ(p.interpolate(p.radius[5]), p.value[5]);
      EXPECT_EQ(p.interpolate(100.0), 0.0);
      EXPECT_EQ(p.interpolate(0.0), p.value[0]);
    }
  }
}

TEST(Profile, LinearGridFromZeroIntegrates) {
  const auto model = make_model("dipole");
  const auto m = reduce_prime(0.5, 1.0, 1.0);  // short profile: linear spacing resolves it
  const double r_max = model->radius_for_fraction(m, 0.99);
  const auto p = model->sample(m, linear_spaced(0.0, r_max, 2000));
  EXPECT_NEAR(p.integrate() / model->cumulative_reflectance(m, r_max), 1.0, 1e-6);
}

TEST(Profile, StandardErrorOfTheIntegral) {
  SampledProfile p;
  p.radius = {1, 2, 3};
  p.value = {1, 1, 1};
  EXPECT_EQ(p.integral_standard_error(), 0.0);
  p.standard_error = {0.1, 0.1, 0.1};
  EXPECT_GT(p.integral_standard_error(), 0.0);
  // Doubling every error doubles the integral's.
  const double one = p.integral_standard_error();
  p.standard_error = {0.2, 0.2, 0.2};
  EXPECT_NEAR(p.integral_standard_error(), 2 * one, 1e-12);
}

TEST(Profile, ValidationNamesTheProblem) {
  SampledProfile p;
  p.radius = {0.1, 0.2, 0.2};
  p.value = {1, 1, 1};
  try {
    p.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("radius[2]"), std::string::npos) << e.what();
  }
  p.radius = {0.1, 0.2};
  EXPECT_THROW(p.validate(), InvalidInput);  // 2 radii, 3 values
  EXPECT_THROW(log_spaced(0.0, 1.0, 10), InvalidInput);
  EXPECT_THROW(log_spaced(1.0, 0.5, 10), InvalidInput);
  EXPECT_THROW(linear_spaced(0.0, 1.0, 1), InvalidInput);
}

TEST(Profile, GridsAreExact) {
  const auto r = log_spaced(0.01, 100.0, 5);
  ASSERT_EQ(r.size(), 5u);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(r[i], 0.01 * std::pow(10.0, i), 1e-12 * r[i]);
  const auto l = linear_spaced(0.0, 1.0, 11);
  EXPECT_DOUBLE_EQ(l[3], 0.3);
  EXPECT_DOUBLE_EQ(l.back(), 1.0);
}
