// The Monte Carlo reference against exact and published values. Photon counts are modest so the
// suite stays fast; every tolerance is 4 standard errors of the Monte Carlo estimate, plus, where
// the reference is printed to a fixed number of decimals, half a unit of its last decimal (the
// reference's own rounding). Each check prints: case, value, stderr, reference, deviation in sigma.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/montecarlo.hpp"
#include "reference_data.hpp"

using namespace bssrdf;

namespace {

// Checks |value - reference| <= 4 sigma + rounding and prints one line of the validation table.
void check(const std::string& name, const Estimate& e, double reference, double rounding) {
  const double deviation = (e.value - reference) / e.standard_error;
  std::printf("  %-52s %10.6f %9.6f %10.6f %+7.2f\n", name.c_str(), e.value, e.standard_error, reference, deviation);
  EXPECT_LE(std::abs(e.value - reference), 4 * e.standard_error + rounding)
      << name << ": " << e.value << " +- " << e.standard_error << " vs " << reference;
}

void header() { std::printf("  %-52s %10s %9s %10s %7s\n", "case", "value", "stderr", "reference", "dev/sig"); }

LayerStack single(double sigma_a, double sigma_s, double g, double n, double thickness) {
  LayerStack s;
  s.channel_names = {"c0"};
  s.layers.push_back(Layer::of(Medium::single_channel(sigma_a, sigma_s, g, n), thickness, ""));
  return s;
}

MonteCarloOptions photons(std::uint64_t n, std::uint64_t seed = 7) {
  MonteCarloOptions o;
  o.photons = n;
  o.seed = seed;
  o.threads = 0;
  return o;
}

std::string fmt(const char* format, double a, double b, double c) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// Exact single-scattering reflectance per entered flux, semi-infinite medium, by a fine midpoint
// rule: alpha int_0^1 2 pi p(-mu) (1 - F(mu)) mu / (1 + mu) dmu.
double single_scattering_exact(double albedo, double g, double eta) {
  const int n = 200000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) / n;
    const double d = 1 + g * g + 2 * g * mu;
    const double p = (1 - g * g) / (4 * std::numbers::pi * d * std::sqrt(d));
    sum += 2 * std::numbers::pi * p * (1 - fresnel_reflectance(mu, eta)) * mu / (1 + mu);
  }
  return albedo * sum / n;
}

}  // namespace

TEST(MonteCarloValidation, SemiInfiniteAgainstAddingDoubling) {
  header();
  for (const auto& row : test_data::read_tsv("ad_semi_infinite.tsv")) {
    const double n = row.at("n"), g = row.at("g"), albedo = row.at("albedo");
    // The nearly conservative rows (albedo' = 0.999) need ~10^4 interactions per photon: left to
    // the benchmark, not CI.
    if (row.at("reduced_albedo") > 0.995) continue;
    const auto result =
        run_monte_carlo(single(1 - albedo, albedo, g, n, kSemiInfinite), photons(g > 0 ? 10000 : 20000));
    const auto& c = result.channels[0];
    EXPECT_NEAR(c.specular_reflectance, row.at("Rsp"), 5e-6);
    check(fmt("AD half-space n=%.1f g=%.1f a=%.6f  Rd_incident", n, g, albedo), c.diffuse_reflectance,
          row.at("Rd_incident"), 5e-6);
    check(fmt("AD half-space n=%.1f g=%.1f a=%.6f  Rd_entered", n, g, albedo), c.per_entered_flux().diffuse_reflectance,
          row.at("Rd_entered"), 5e-6);
  }
}

TEST(MonteCarloValidation, SlabAgainstAddingDoubling) {
  header();
  for (const auto& row : test_data::read_tsv("ad_slab.tsv")) {
    const double n = row.at("n"), g = row.at("g"), albedo = row.at("albedo"), b = row.at("b");
    const auto result = run_monte_carlo(single(1 - albedo, albedo, g, n, b), photons(20000));
    const auto& c = result.channels[0];
    check(fmt("AD slab n=%.1f a=%.2f b=%.0f  R_incident", n, albedo, b), c.diffuse_reflectance, row.at("R_incident"),
          5e-6);
    check(fmt("AD slab n=%.1f a=%.2f b=%.0f  T_total (ballistic incl.)", n, albedo, b), c.total_transmittance,
          row.at("T_total"), 5e-6);
    // The ballistic part alone is exact: (1 - R_sp) e^{-b} times the internal reflections
    // (checked where the photons give it a standard error, i.e. where some get through).
    const double r = c.specular_reflectance, e = std::exp(-b);
    if (b <= 4)
      check(fmt("slab n=%.1f a=%.2f b=%.0f  T_unscattered (exact)", n, albedo, b), c.unscattered_transmittance,
            (1 - r) * (1 - r) * e / (1 - r * r * e * e), 0);
  }
}

TEST(MonteCarloValidation, McmlManualTables61And62) {
  header();
  // Table 6.1: matched slab, mua = 10/cm, mus = 90/cm, g = 0.75, d = 0.02 cm (mm here).
  auto t61 = run_monte_carlo(single(1.0, 9.0, 0.75, 1.0, 0.2), photons(400000));
  check("MCML 6.1 slab Rd vs van de Hulst", t61.channels[0].diffuse_reflectance, 0.09739, 5e-6);
  check("MCML 6.1 slab Tt vs van de Hulst", t61.channels[0].total_transmittance, 0.66096, 5e-6);
  // Table 6.2: semi-infinite, n = 1.5, mua = 10/cm, mus = 90/cm, g = 0: total reflectance with
  // R_sp = 0.04; adding-doubling 0.25994 (diffuse 0.21994), Giovanelli 0.2600.
  auto t62 = run_monte_carlo(single(1.0, 9.0, 0.0, 1.5, kSemiInfinite), photons(100000));
  const auto& c = t62.channels[0];
  EXPECT_NEAR(c.specular_reflectance, 0.04, 1e-15);
  Estimate total = c.diffuse_reflectance;
  total.value += c.specular_reflectance;
  check("MCML 6.2 half-space n=1.5 R_total vs adding-doubling", total, 0.25994, 5e-6);
  check("MCML 6.2 half-space n=1.5 R_total vs Giovanelli", total, 0.2600, 5e-5);
}

TEST(MonteCarloValidation, ThickSlabAgainstAddingDoublingWithoutMcmlBias) {
  // 100 mean free paths, mua = 1/cm, mus = 100/cm, g = 0.9, n = 1: adding-doubling 0.40132 (MCML
  // 1.2.2 gives 0.40066, biased by its generator). 300 000 photons give sigma ~ 0.0006: this checks
  // agreement, it cannot resolve the 0.17 % bias (run the benchmark's long case for that).
  header();
  auto r = run_monte_carlo(single(0.1, 10.0, 0.9, 1.0, 100 / 10.1), photons(300000));
  check("100-mfp slab g=0.9 Rd vs adding-doubling", r.channels[0].diffuse_reflectance, 0.40132, 5e-6);
}

TEST(MonteCarloValidation, IndexMatchedHalfSpaceExact) {
  header();
  for (const auto& row : test_data::read_tsv("exact_halfspace_eta1.tsv")) {
    const double albedo = row.at("albedo");
    if (albedo > 0.995) continue;  // see SemiInfiniteAgainstAddingDoubling
    const auto r = run_monte_carlo(single(1 - albedo, albedo, 0.0, 1.0, kSemiInfinite), photons(20000, 11));
    const auto& c = r.channels[0];
    check(fmt("exact half-space eta=1 a=%.3f  R_normal", albedo, 0, 0), c.diffuse_reflectance, row.at("R_normal"),
          5e-6);
    check(fmt("exact half-space eta=1 a=%.3f  R_single", albedo, 0, 0), c.single_scattering_reflectance,
          row.at("R_single_normal"), 5e-5);
  }
  // Single scattering with the true phase function and Fresnel exit, against quadrature.
  for (const auto& [g, eta] : {std::pair{0.9, 1.4}, std::pair{0.0, 1.3}, std::pair{-0.5, 1.0}}) {
    const double albedo = 0.9;
    const auto r = run_monte_carlo(single(0.1, 0.9, g, eta, kSemiInfinite), photons(100000, 13));
    check(fmt("single scattering g=%.1f eta=%.1f a=%.1f (per entered)", g, eta, albedo),
          r.channels[0].per_entered_flux().single_scattering_reflectance, single_scattering_exact(albedo, g, eta), 0);
  }
}

TEST(MonteCarloValidation, RadialProfileAgainstMcml) {
  // Bins beyond the first few, out to where 200 000 photons still resolve R(r) (about 5 mm).
  // MCML 1.2.2, 5e6 photons: mua = 1/cm, mus = 100/cm, g = 0.9, n = 1.4, 10 cm thick (the .mci in
  // tests/data), bins of dr = 0.002 cm. MCML's file has no per-bin errors; its variance per photon
  // is that of the same estimator, so its standard error is ours scaled by sqrt(N_ours / 5e6).
  std::ifstream in(std::string(BSSRDF_TEST_DATA) + "/mcml_semi_infinite_n1.4_g0.9_Rd_r.csv");
  ASSERT_TRUE(in);
  std::vector<double> mcml;  // per mm^2
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'r') continue;
    std::stringstream fields(line);
    std::string field;
    for (int i = 0; i < 4; ++i) std::getline(fields, field, ',');
    mcml.push_back(std::stod(field));
  }
  ASSERT_EQ(mcml.size(), 500u);
  const std::uint64_t n = 200000;
  MonteCarloOptions o = photons(n, 17);
  o.bins = 499;  // MCML's last bin is an overflow bin: not compared
  o.r_max = 0.02 * 499;
  const auto r = run_monte_carlo(single(0.1, 10.0, 0.9, 1.4, 100.0), o);
  const auto& c = r.channels[0];
  const double scale = std::sqrt(static_cast<double>(n) / 5e6);
  int outside = 0, compared = 0;
  double chi2 = 0, worst = 0;
  for (std::size_t i = 3; i < 499; ++i) {  // bins beyond the first few
    // Only bins where our estimate is well resolved (relative error <= 10 %, i.e. ~100 or more
    // photons): with a handful of weighted hits the estimate is skewed and its standard error is
    // itself unreliable, so a Gaussian 4-sigma test would not mean what it says.
    if (!(c.reflectance_stderr[i] <= 0.1 * c.reflectance[i])) continue;
    const double sigma = c.reflectance_stderr[i] * std::sqrt(1 + scale * scale);
    const double z = (c.reflectance[i] - mcml[i]) / sigma;
    chi2 += z * z;
    worst = std::max(worst, std::abs(z));
    if (std::abs(z) > 4)
      std::printf("  bin %zu r = %.3f mm: %.5g +- %.2g (ours) vs %.5g (MCML), %.2f sigma\n", i, r.bin_radius[i],
                  c.reflectance[i], c.reflectance_stderr[i], mcml[i], z);
    outside += std::abs(z) > 4;
    ++compared;
  }
  std::printf("  R(r) vs MCML: %d bins compared, chi2/bin = %.3f, worst |dev| = %.2f sigma, %d beyond 4 sigma\n",
              compared, chi2 / compared, worst, outside);
  EXPECT_EQ(outside, 0);
  // Consistency as a whole: chi2/bin of 1 +- 4 sigma (sigma = sqrt(2/bins) for independent bins).
  EXPECT_NEAR(chi2 / compared, 1.0, 4 * std::sqrt(2.0 / compared));
  header();
  Estimate total = c.diffuse_reflectance;
  total.value += c.specular_reflectance;
  total.standard_error *= std::sqrt(1 + scale * scale);
  check("MCML case D half-space n=1.4 g=0.9 R_total (combined sigma)", total, 0.0277778 + 0.252271, 5e-7);
}

TEST(MonteCarloValidation, SameSeedSameResultForAnyThreadCount) {
  LayerStack s = single(0.05, 2.0, 0.8, 1.4, 3.0);
  s.channel_names = {"R", "G"};
  s.layers[0].sigma_a = {0.05, 0.3};
  s.layers[0].sigma_s = {2.0, 1.0};
  s.layers[0].g = {0.8, 0.2};
  MonteCarloOptions o = photons(20000, 5);
  o.batch_size = 1000;
  o.depth_bins = 10;
  o.spacing = BinSpacing::log;
  o.threads = 1;
  const auto one = run_monte_carlo(s, o);
  o.threads = 2;
  const auto two = run_monte_carlo(s, o);
  o.threads = 7;
  const auto seven = run_monte_carlo(s, o);
  for (const auto* other : {&two, &seven}) {
    EXPECT_EQ(to_csv(one, LengthUnit::millimetre), to_csv(*other, LengthUnit::millimetre));
    for (std::size_t c = 0; c < 2; ++c) {
      const auto &a = one.channels[c], &b = other->channels[c];
      EXPECT_EQ(a.diffuse_reflectance.value, b.diffuse_reflectance.value);
      EXPECT_EQ(a.diffuse_reflectance.standard_error, b.diffuse_reflectance.standard_error);
      EXPECT_EQ(a.total_transmittance.value, b.total_transmittance.value);
      EXPECT_EQ(a.absorbed.value, b.absorbed.value);
      EXPECT_EQ(a.reflectance, b.reflectance);
      EXPECT_EQ(a.transmittance_stderr, b.transmittance_stderr);
      EXPECT_EQ(a.absorbed_by_depth, b.absorbed_by_depth);
      EXPECT_EQ(a.interactions, b.interactions);
    }
  }
  o.seed = 6;
  const auto other_seed = run_monte_carlo(s, o);
  EXPECT_NE(one.channels[0].diffuse_reflectance.value, other_seed.channels[0].diffuse_reflectance.value);
}

TEST(MonteCarloValidation, TalliesAreConsistent) {
  LayerStack s = single(0.2, 5.0, 0.7, 1.33, 1.5);
  MonteCarloOptions o = photons(20000, 3);
  o.absorption = AbsorptionEstimator::analog;  // every photon ends absorbed or escaped: exact balance
  o.spacing = BinSpacing::log;
  o.r_max = 3;
  o.r_min = 0.01;
  o.depth_bins = 15;
  const auto r = run_monte_carlo(s, o);
  const auto& c = r.channels[0];
  EXPECT_NEAR(c.specular_reflectance + c.diffuse_reflectance.value + c.total_transmittance.value + c.absorbed.value,
              1.0, 1e-12);
  // Binned R(r) and T(r) times the bin areas, plus what lies beyond r_max, is the total.
  double binned_r = c.reflectance_beyond, binned_t = c.transmittance_beyond, binned_a = 0;
  for (std::size_t i = 0; i < r.bin_radius.size(); ++i) {
    const double area = std::numbers::pi * (r.bin_outer[i] * r.bin_outer[i] - r.bin_inner[i] * r.bin_inner[i]);
    binned_r += c.reflectance[i] * area;
    binned_t += c.transmittance[i] * area;
  }
  for (std::size_t i = 0; i < r.depth_inner.size(); ++i)
    binned_a += c.absorbed_by_depth[i] * (r.depth_outer[i] - r.depth_inner[i]);
  EXPECT_NEAR(binned_r, c.diffuse_reflectance.value, 1e-12);
  EXPECT_NEAR(binned_t, c.total_transmittance.value, 1e-12);
  EXPECT_NEAR(binned_a, c.absorbed.value, 1e-12);
  for (double e : c.absorbed_by_depth_stderr) EXPECT_GT(e, 0);
  // Per entered = per incident / (1 - R_sp).
  const auto entered = c.per_entered_flux();
  EXPECT_DOUBLE_EQ(entered.diffuse_reflectance.value, c.diffuse_reflectance.value / (1 - c.specular_reflectance));
  EXPECT_DOUBLE_EQ(entered.reflectance[5], c.reflectance[5] / (1 - c.specular_reflectance));
  // Implicit capture and analog absorption estimate the same quantities.
  o.absorption = AbsorptionEstimator::implicit_capture;
  const auto implicit = run_monte_carlo(s, o);
  const auto& d = implicit.channels[0];
  for (const auto& [a, b] :
       {std::pair{c.diffuse_reflectance, d.diffuse_reflectance},
        std::pair{c.total_transmittance, d.total_transmittance}, std::pair{c.absorbed, d.absorbed}}) {
    EXPECT_LE(std::abs(a.value - b.value), 4 * std::hypot(a.standard_error, b.standard_error));
  }
}

TEST(MonteCarloValidation, LayersAndClearLayers) {
  header();
  // Two identical layers behave as one layer of their total thickness.
  LayerStack one = single(0.1, 3.0, 0.8, 1.4, 2.0);
  LayerStack two = one;
  two.layers[0].thickness = 0.7;
  two.layers.push_back(two.layers[0]);
  two.layers[1].thickness = 1.3;
  const auto a = run_monte_carlo(one, photons(40000, 21)).channels[0];
  const auto b = run_monte_carlo(two, photons(40000, 22)).channels[0];
  Estimate diff{b.diffuse_reflectance.value - a.diffuse_reflectance.value,
                std::hypot(a.diffuse_reflectance.standard_error, b.diffuse_reflectance.standard_error)};
  check("two layers - one layer, R_d", diff, 0, 0);
  diff = {b.total_transmittance.value - a.total_transmittance.value,
          std::hypot(a.total_transmittance.standard_error, b.total_transmittance.standard_error)};
  check("two layers - one layer, T_t", diff, 0, 0);

  // A clear glass plate alone: every photon is ballistic; R and T follow from Fresnel exactly.
  LayerStack glass = single(0, 0, 0, 1.5, 1.0);
  const auto g = run_monte_carlo(glass, photons(40000, 23)).channels[0];
  const double r = 0.04;
  EXPECT_NEAR(g.specular_reflectance, r, 1e-15);
  check("glass plate n=1.5, reflected after entering", g.diffuse_reflectance, (1 - r) * (1 - r) * r / (1 - r * r), 0);
  check("glass plate n=1.5, transmitted", g.total_transmittance, (1 - r) * (1 - r) / (1 - r * r), 0);
  EXPECT_EQ(g.unscattered_transmittance.value, g.total_transmittance.value);
  // A glass slide on a medium: R_sp includes the slide's multiple reflections (MCML's convention).
  LayerStack slide = single(0.1, 3.0, 0.8, 1.4, kSemiInfinite);
  slide.layers.insert(slide.layers.begin(), single(0, 0, 0, 1.5, 0.5).layers[0]);
  const auto s = run_monte_carlo(slide, photons(2000, 24)).channels[0];
  const double r1 = 0.04, r2 = std::pow(0.1 / 2.9, 2);
  EXPECT_NEAR(s.specular_reflectance, r1 + (1 - r1) * (1 - r1) * r2 / (1 - r1 * r2), 1e-15);
}
