// The adding-doubling solver against Prahl's published adding-doubling values (ad 4-0-0, 32
// angles; tests/data/ad_slab.tsv, ad_semi_infinite.tsv), against exact properties (energy
// conservation, reciprocity of the quadrature, the pure absorber, the index-matched clear slide)
// and, in test_ad_montecarlo.cpp, against the Monte Carlo reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
                row.at("b"), row.at("R_incident"), t.diffuse_reflectance, row.at("T_total"), t.total_transmittance,
                t.points);
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

TEST(AddingDoubling, ConservesEnergyWithoutAbsorption) {
  // No absorption: everything is reflected or transmitted, for any boundary, slides and light.
  for (auto incidence : {Incidence::collimated, Incidence::diffuse}) {
    Slab s = one_layer(1.0, 0.8, 1.4, 3.0);
    s.above = s.below = {{1.5, 1.0, 0.0}};
    const auto t = solve(s, incidence);
    EXPECT_NEAR(t.specular_reflectance + t.diffuse_reflectance + t.total_transmittance, 1, 1e-9)
        << to_string(incidence);
    EXPECT_NEAR(t.absorbed(), 0, 1e-9);
  }
}

TEST(AddingDoubling, FixedSizeAngleCountsConserveEnergyAndKeepTrappedLightDark) {
  // 8, 12 and 16 angles run on fixed-size matrices, 9 and 17 on the general path. A clear slab of
  // index 1.4 in air traps the grazing angles between two total reflections (a zero row with a
  // zero source): they must stay dark, not 0/0. Collimated T of the clear slab is (1 - r)/(1 + r).
  const double r = std::pow(0.4 / 2.4, 2);
  for (int points : {8, 9, 12, 16, 17}) {
    Options o;
    o.points = points;
    for (auto incidence : {Incidence::collimated, Incidence::diffuse}) {
      Slab clear = one_layer(0.0, 0.0, 1.4, 1.0);
      clear.layers[0].sigma_a = 0;
      const auto c = solve(clear, incidence, o);
      EXPECT_NEAR(c.specular_reflectance + c.diffuse_reflectance + c.total_transmittance, 1, 1e-12)
          << points << " angles, " << to_string(incidence);
      if (incidence == Incidence::collimated) {
        EXPECT_NEAR(c.total_transmittance, (1 - r) / (1 + r), 1e-14);
      }
      Slab s = one_layer(1.0, 0.8, 1.4, 3.0);
      s.above = s.below = {{1.5, 1.0, 0.0}};
      const auto t = solve(s, incidence, o);
      EXPECT_NEAR(t.specular_reflectance + t.diffuse_reflectance + t.total_transmittance, 1, 1e-9)
          << points << " angles, " << to_string(incidence);
    }
  }
}

TEST(AddingDoubling, PureAbsorberMatchesExactExponentialIntegrals) {
  // Index-matched, no scattering: collimated T = exp(-b); diffuse T = 2 E_3(b) = int 2 mu exp(-b/mu).
  for (double b : {0.1, 1.0, 3.0}) {
    const auto c = solve(one_layer(0.0, 0.0, 1.0, b), Incidence::collimated);
    EXPECT_NEAR(c.total_transmittance, std::exp(-b), 1e-12);
    EXPECT_NEAR(c.unscattered_transmittance, std::exp(-b), 1e-12);
    double e3 = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double mu = (i + 0.5) / n;
      e3 += 2 * mu * std::exp(-b / mu) / n;
    }
    const auto d = solve(one_layer(0.0, 0.0, 1.0, b), Incidence::diffuse);
    EXPECT_NEAR(d.total_transmittance, e3, 1e-4) << "b " << b;
    EXPECT_EQ(d.diffuse_reflectance, 0);
  }
}

TEST(AddingDoubling, AnglesChosenFromTheToleranceStayWithin1e4Of128Angles) {
  // Hard cases: strong forward scattering, thin and near-conservative slabs, slides, high index.
  struct Case {
    double albedo, g, n, b;
    bool slides;
  };
  for (const auto& c :
       {Case{0.9, 0.99, 1.33, 2.0, false}, Case{0.9999, 0.9, 1.4, 1.0, false}, Case{0.99, 0.0, 1.6, 10.0, true},
        Case{0.5, 0.5, 1.6, 0.1, true}, Case{0.999, 0.9, 1.4, kSemiInfinite, false}}) {
    Slab s = one_layer(c.albedo, c.g, c.n, c.b);
    if (c.slides) s.above = s.below = {{1.5, 1.0, 0.0}};
    const auto chosen = solve(s, Incidence::collimated);
    Options fine;
    fine.points = 128;
    const auto reference = solve(s, Incidence::collimated, fine);
    const double change = std::max(std::abs(chosen.diffuse_reflectance - reference.diffuse_reflectance),
                                   std::abs(chosen.total_transmittance - reference.total_transmittance));
    std::printf("  albedo %.4f g %.2f n %.2f b %g%s: %d angles, estimate %.1e, |change to 128| %.1e\n", c.albedo, c.g,
                c.n, c.b, c.slides ? " slides" : "", chosen.points, chosen.error_estimate, change);
    EXPECT_LE(change, 1e-4);
    EXPECT_LE(chosen.error_estimate, 1e-4);
  }
}

TEST(AddingDoubling, BadSlabsNameTheField) {
  Slab s = one_layer(0.9, 0.0, 1.4, 1.0);
  s.layers[0].g = 1;
  EXPECT_THROW(solve(s, Incidence::collimated), InvalidInput);
  s = one_layer(0.9, 0.0, 1.4, -1.0);
  try {
    solve(s, Incidence::collimated);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("layers[0].thickness = -1"), std::string::npos) << e.what();
  }
  s = one_layer(0.9, 0.0, 1.4, 1.0);
  s.above = {{1.5, 0.0, 0.0}};
  EXPECT_THROW(solve(s, Incidence::collimated), InvalidInput);
  EXPECT_THROW(parse_incidence("sideways"), InvalidInput);
}

TEST(AddingDoubling, StackedLayersAddUpAndMatchMonteCarlo) {
  // Two layers of one medium are one layer of their summed thickness (the adding equations).
  Slab two = one_layer(0.95, 0.7, 1.4, 0.7);
  two.layers.push_back({0.05, 0.95, 0.7, 1.8});
  const auto a = solve(two, Incidence::collimated);
  const auto b = solve(one_layer(0.95, 0.7, 1.4, 2.5), Incidence::collimated);
  EXPECT_NEAR(a.diffuse_reflectance, b.diffuse_reflectance, 1e-6);
  EXPECT_NEAR(a.total_transmittance, b.total_transmittance, 1e-6);
  EXPECT_NEAR(a.unscattered_transmittance, b.unscattered_transmittance, 1e-12);
  // A thin epidermis over a semi-infinite dermis (tests/data/two_layer_skin.json's media, 0.1 mm):
  // against the Monte Carlo reference.
  LayerStack stack;
  stack.channel_names = {"c0"};
  Layer top, bottom;
  top.n = bottom.n = 1.4;
  top.thickness = 0.1;
  top.sigma_a = {0.05}, top.sigma_s = {5}, top.g = {0.8};
  bottom.sigma_a = {0.02}, bottom.sigma_s = {2}, bottom.g = {0.0};
  stack.layers = {top, bottom};
  const auto ad = solve(slab_of(stack, 0), Incidence::collimated);
  MonteCarloOptions options;
  options.photons = 100000;
  options.seed = 9;
  options.bins = 2;
  const auto mc = run_monte_carlo(stack, options).channels[0];
  std::printf("  two layers: AD %.5f, MC %.5f +- %.5f\n", ad.diffuse_reflectance, mc.diffuse_reflectance.value,
              mc.diffuse_reflectance.standard_error);
  EXPECT_LE(std::abs(ad.diffuse_reflectance - mc.diffuse_reflectance.value),
            4 * mc.diffuse_reflectance.standard_error + 1e-4);
  // Layers of different index cannot share the angles: refused, naming the layer.
  stack.layers[1].n = 1.33;
  EXPECT_THROW(slab_of(stack, 0), InvalidInput);
}
