// The exact table generator's near-field fit (tools/exact_table/near_field_fit.hpp): one Poisson fit
// of a cubic in ln r over a noisy near field recovers the profile, with honest errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

#include "../tools/exact_table/near_field_fit.hpp"

using bssrdf::exact_table::fit_near_field;

namespace {

constexpr double kStep = 0.19188209108483255;  // the table's ln-radius step, ln 10 / 12
constexpr std::size_t kLast = 30;              // the generator's longest range

// A near field like a g 0.999 non-absorbing node's (alpha' 0.99, eta 1.6): y ~ r from 0.001 to 0.3
// transport mfp, the slope from 1.03 to 1.05 outwards, about 2 photons in the first bin and 600 in the last.
double truth(std::size_t k) {
  const double x = (static_cast<double>(k) - kLast) * kStep;
  return std::exp(std::log(600.0) + 1.05 * x + 0.01 * x * x + 0.001 * x * x * x);
}

// Bin means of y from `photons` unit-weight photons of expected counts truth(k), with their standard
// errors (sqrt(count), as a run's tally gives them).
void tally(std::mt19937_64& rng, std::vector<double>& mean, std::vector<double>& se) {
  mean.assign(kLast + 1, 0.0);
  se.assign(kLast + 1, 0.0);
  for (std::size_t k = 0; k <= kLast; ++k) {
    std::poisson_distribution<int> count(truth(k));
    mean[k] = count(rng);
    se[k] = std::sqrt(mean[k]);
  }
}

}  // namespace

TEST(NearFieldFit, RecoversACubicInLnRExactly) {
  std::vector<double> mean(kLast + 1), se(kLast + 1);
  for (std::size_t k = 0; k <= kLast; ++k) {
    mean[k] = truth(k);
    se[k] = std::sqrt(mean[k]);
  }
  const auto fit = fit_near_field(mean, se, kLast, kStep);
  ASSERT_TRUE(fit.converged);
  for (std::size_t k = 0; k <= kLast; ++k) EXPECT_NEAR(fit.mean[k] / mean[k], 1.0, 1e-9) << k;
  EXPECT_LT(fit.chi2_per_dof, 1e-12);
}

TEST(NearFieldFit, PoolsTheNoiseAndStatesItsErrorHonestly) {
  // 400 runs with Poisson tallies (some inner bins empty). At the first bin (about 2 photons) and at
  // the sixth (0.003 transport mfp, about 10) the fit is at least twice as close to the truth as the
  // bin's own tally; its stated error covers the truth as a normal error would; chi2 per degree of
  // freedom is near 1.
  std::mt19937_64 rng(20261207);
  std::vector<double> mean, se;
  const int runs = 400;
  int within_2se = 0, converged = 0;
  double squared_fit[2] = {}, squared_raw[2] = {}, chi2 = 0;
  for (int run = 0; run < runs; ++run) {
    tally(rng, mean, se);
    const auto fit = fit_near_field(mean, se, kLast, kStep);
    if (!fit.converged) continue;
    ++converged;
    chi2 += fit.chi2_per_dof;
    for (std::size_t k : {0u, 6u, 12u})
      if (std::abs(fit.mean[k] - truth(k)) < 2 * fit.se[k]) ++within_2se;
    for (int i = 0; i < 2; ++i) {
      const std::size_t k = i == 0 ? 0 : 6;
      squared_fit[i] += std::pow(fit.mean[k] / truth(k) - 1, 2);
      squared_raw[i] += std::pow(mean[k] / truth(k) - 1, 2);
    }
  }
  std::printf(
      "converged %d of %d; within 2 se %.3f; rms at bins 0 and 6: fit %.3f %.3f, tally %.3f %.3f; chi2/dof %.3f\n",
      converged, runs, within_2se / (3.0 * runs), std::sqrt(squared_fit[0] / runs), std::sqrt(squared_fit[1] / runs),
      std::sqrt(squared_raw[0] / runs), std::sqrt(squared_raw[1] / runs), chi2 / converged);
  EXPECT_EQ(converged, runs);
  EXPECT_GT(within_2se, 0.90 * 3 * runs);
  EXPECT_LT(within_2se, 0.99 * 3 * runs);
  for (int i = 0; i < 2; ++i) EXPECT_LT(std::sqrt(squared_fit[i]), 0.5 * std::sqrt(squared_raw[i])) << i;
  EXPECT_NEAR(chi2 / converged, 1.0, 0.1);
}

TEST(NearFieldFit, RefusesTooFewBinsOrNothingTallied) {
  std::vector<double> mean(kLast + 1, 0.0), se(kLast + 1, 0.0);
  EXPECT_FALSE(fit_near_field(mean, se, kLast, kStep).converged);  // nothing tallied
  for (std::size_t k = 0; k <= kLast; ++k) {
    mean[k] = truth(k);
    se[k] = std::sqrt(mean[k]);
  }
  EXPECT_FALSE(fit_near_field(mean, se, 5, kStep).converged);  // a cubic through 6 bins would follow noise
  EXPECT_TRUE(fit_near_field(mean, se, 6, kStep).converged);
}
