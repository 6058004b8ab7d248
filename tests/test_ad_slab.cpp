// The adding-doubling solver against Prahl's published adding-doubling values (ad 4-0-0, 32
// angles; tests/data/ad_slab.tsv, ad_semi_infinite.tsv), against exact properties (energy
// conservation, reciprocity of the quadrature, the pure absorber, the index-matched clear slide)
// and, in test_ad_montecarlo.cpp, against the Monte Carlo reference.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>

#include "../src/adding_doubling/angles.hpp"
#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/montecarlo.hpp"
#include "reference_data.hpp"

using namespace bssrdf;
using namespace bssrdf::adding_doubling;

namespace {

Slab one_layer(double albedo, double g, double n, double optical_thickness) {
  Slab s;
  s.layers = {{1 - albedo, albedo, g, optical_thickness}};
  s.n = n;
  return s;
}

}  // namespace

TEST(AddingDoublingAngles, RadauRuleIsExactToDegree2nMinus2AndIncludesMuOne) {
  for (int n : {2, 3, 5, 8, 16, 32}) {
    std::vector<double> x, w;
    gauss_radau_right(n, x, w);
    ASSERT_EQ(static_cast<int>(x.size()), n);
    EXPECT_DOUBLE_EQ(x.back(), 1.0);
    for (int degree = 0; degree <= 2 * n - 2; ++degree) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += w[i] * std::pow(x[i], degree);
      const double exact = degree % 2 ? 0.0 : 2.0 / (degree + 1);
      EXPECT_NEAR(sum, exact, 1e-12) << "n " << n << " degree " << degree;
    }
  }
}

TEST(AddingDoublingAngles, SplitAnglesIntegrateMuExactlyAboveTheCriticalCosine) {
  const double mu_c = std::sqrt(1 - 1 / (1.4 * 1.4));
  const auto a = make_angles(16, {mu_c});
  ASSERT_EQ(a.size(), 16u);
  double total = 0, above = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    total += a.weight[i];
    if (a.mu[i] > mu_c) above += 2 * a.mu[i] * a.weight[i];
  }
  EXPECT_NEAR(total, 1, 1e-14);
  EXPECT_NEAR(above, 1 - mu_c * mu_c, 1e-14);
  EXPECT_EQ(a.mu.back(), 1.0);
}

TEST(AddingDoubling, SlabsMatchPublishedValuesWithin1e4) {
  std::printf("  n     g     albedo  b    R: AD      ours      T: AD      ours     points\n");
  double worst = 0;
  for (const auto& row : test_data::read_tsv("ad_slab.tsv")) {
    const auto t = solve(one_layer(row.at("albedo"), row.at("g"), row.at("n"), row.at("b")), Incidence::collimated);
    std::printf("  %.2f  %.2f  %.4f %4.0f  %.5f  %.5f   %.5f  %.5f  %d\n", row.at("n"), row.at("g"), row.at("albedo"),
                row.at("b"), row.at("R_incident"), t.diffuse_reflectance, row.at("T_total"), t.total_transmittance, t.points);
    EXPECT_NEAR(t.specular_reflectance, row.at("Rsp"), 5e-6);
    EXPECT_NEAR(t.diffuse_reflectance, row.at("R_incident"), 1e-4);
    EXPECT_NEAR(t.total_transmittance, row.at("T_total"), 1e-4);
    worst = std::max({worst, std::abs(t.diffuse_reflectance - row.at("R_incident")),
                      std::abs(t.total_transmittance - row.at("T_total"))});
  }
  std::printf("  worst |deviation| over the slab table: %.2e\n", worst);
}

TEST(AddingDoubling, SemiInfiniteMatchesPublishedValuesWithin1e4) {
  double worst = 0;
  for (const auto& row : test_data::read_tsv("ad_semi_infinite.tsv")) {
    const auto t = solve(one_layer(row.at("albedo"), row.at("g"), row.at("n"), kSemiInfinite), Incidence::collimated);
    EXPECT_NEAR(t.diffuse_reflectance, row.at("Rd_incident"), 1e-4)
        << "n " << row.at("n") << " g " << row.at("g") << " albedo " << row.at("albedo");
    EXPECT_NEAR(t.diffuse_reflectance * t.entered_scale(), row.at("Rd_entered"), 1e-4);
    EXPECT_EQ(t.total_transmittance, 0);
    worst = std::max(worst, std::abs(t.diffuse_reflectance - row.at("Rd_incident")));
  }
  std::printf("  worst |deviation| over the semi-infinite table (%s): %.2e\n", "46 rows", worst);
}
