// Integrating-sphere files (.rxt, the format of Prahl's iad): the reader's errors, the published
// example test/basic-B.rxt of iad (forward values by Prahl's adding-doubling with the truth in
// its comments), and round trips through the sphere equations with 0, 1 and 2 spheres and M_U.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../src/fit/iad_search_edge.hpp"
#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/integrating_sphere.hpp"
#include "bssrdf/fit/rxt_fit.hpp"
#include "bssrdf/io/rxt.hpp"
#include "bssrdf/montecarlo.hpp"
#include "cli_runner.hpp"

using namespace bssrdf;

namespace {

const char* const kHeader = R"(IAD1
1.40   # sample index
1.50   # slide index
1.0    # sample thickness
1.0    # slide thickness
5.0    # beam diameter
0.98   # standard
%d     # spheres
203.2 25.4 12.7 1.0 0.96
203.2 25.4 12.7 1.0 0.96
%s
)";

std::string header(int spheres, const char* measurements) {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer, kHeader, spheres, measurements);
  return buffer;
}

// What the instrument of `f` reports for a sample (the forward direction of the fit).
std::array<double, 3> measure(const RxtFile& f, double mu_a, double mu_s_prime, double g) {
  adding_doubling::Slab slab;
  slab.layers = {{mu_a, mu_s_prime / (1 - g), g, f.sample_thickness}};
  slab.n = f.sample_n;
  slab.above = slab.below = {{f.slide_n, f.slide_thickness, 0.0}};
  const auto c = adding_doubling::solve(slab, adding_doubling::Incidence::collimated);
  const auto d = adding_doubling::solve(slab, adding_doubling::Incidence::diffuse);
  const auto [m_r, m_t] = sphere_measurements(f, {c.specular_reflectance + c.diffuse_reflectance, c.total_transmittance,
                                                  d.specular_reflectance + d.diffuse_reflectance, d.total_transmittance,
                                                  c.unscattered_reflectance, c.unscattered_transmittance});
  return {m_r, m_t, c.unscattered_transmittance};
}

void expect_file_error(const std::string& text, const std::string& where, const std::string& what) {
  try {
    parse_rxt(text, "x.rxt");
    ADD_FAILURE() << "accepted: " << what;
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Rxt, PublishedExampleRecoversTheTruthOfEveryRow) {
  const auto file = read_rxt(std::string(BSSRDF_TEST_DATA) + "/iad_basic_B.rxt");
  ASSERT_EQ(file.rows.size(), 25u);
  EXPECT_EQ(file.spheres, 0);
  EXPECT_TRUE(file.has_slides());
  RxtFitOptions options;
  options.reflectance_stderr = options.transmittance_stderr = 1e-4;
  const auto fit = fit_rxt(file, options);
  double worst = 0;
  for (std::size_t k = 0; k < fit.rows.size(); ++k) {
    const double mu_s = 5.0 * (1 + k / 5), mu_a = 0.1 + 0.2 * (k % 5);  // the file's comments, row order
    const auto& r = fit.rows[k];
    EXPECT_TRUE(r.converged) << r.status;
    EXPECT_EQ(r.status.rfind("converged", 0), 0u) << r.status;  // "converged" or "converged; ..." (near iad's edge)
    EXPECT_NEAR(r.mu_a / mu_a, 1, 5e-3) << "row " << k + 1;
    EXPECT_NEAR(r.mu_s_prime / mu_s, 1, 5e-3) << "row " << k + 1;
    worst = std::max({worst, std::abs(r.mu_a / mu_a - 1), std::abs(r.mu_s_prime / mu_s - 1)});
  }
  std::printf(
      "  iad test/basic-B.rxt: worst relative deviation of mu_a, mu_s' from the truth: %.2e (%.3f s for 25 rows)\n",
      worst, fit.seconds);
}

TEST(Rxt, RoundTripsThroughOneAndTwoSpheresAndTheUnscatteredBeam) {
  for (int spheres : {0, 1, 2})
    for (bool with_u : {false, true}) {
      const auto setup =
          parse_rxt(header(spheres, with_u ? "3" : "2") + "0.3 0.3" + (with_u ? " 0.01\n" : "\n"), "setup");
      std::ostringstream text;
      text << header(spheres, with_u ? "lrtu" : "lrt");
      const double truth[][3] = {{0.05, 1.0, with_u ? 0.7 : 0.0}, {0.2, 3.0, with_u ? 0.5 : 0.0}};
      for (int k = 0; k < 2; ++k) {
        const auto m = measure(setup, truth[k][0], truth[k][1], truth[k][2]);
        text.precision(12);
        text << 500 + 100 * k << ' ' << m[0] << ' ' << m[1];
        if (with_u) text << ' ' << m[2];
        text << '\n';
      }
      const auto fit = fit_rxt(parse_rxt(text.str(), "round-trip"));
      for (int k = 0; k < 2; ++k) {
        const auto& r = fit.rows[k];
        EXPECT_EQ(r.row.wavelength, 500 + 100 * k);
        EXPECT_NEAR(r.mu_a / truth[k][0], 1, 5e-3) << spheres << " spheres, M_U " << with_u << ", row " << k;
        EXPECT_NEAR(r.mu_s_prime / truth[k][1], 1, 5e-3) << spheres << " spheres, M_U " << with_u << ", row " << k;
        if (with_u) {
          EXPECT_NEAR(r.g, truth[k][2], 5e-3);
        }
        EXPECT_TRUE(std::isfinite(r.mu_a_stderr) && r.mu_a_stderr > 0);
      }
    }
}

TEST(Rxt, SpheresChangeWhatIsMeasured) {
  // A sphere's gain raises M_R (wall light returns to the sample and detector) and the sample's
  // own reflectance raises M_T; two coupled spheres differ from one.
  const SampleTotals t{0.4, 0.3, 0.45, 0.25};
  const auto none = sphere_measurements(parse_rxt(header(0, "2") + "0.1 0.1\n", "0"), t);
  const auto one = sphere_measurements(parse_rxt(header(1, "2") + "0.1 0.1\n", "1"), t);
  const auto two = sphere_measurements(parse_rxt(header(2, "2") + "0.1 0.1\n", "2"), t);
  EXPECT_EQ(none.first, 0.4);
  EXPECT_EQ(none.second, 0.3);
  EXPECT_NE(one.second, 0.3);
  EXPECT_NE(two.first, one.first);
  EXPECT_NE(two.second, one.second);
  // iad 4's options: without baffles a sample equal to the standard reads r_std; the dual-beam
  // method and no sphere read the totals; c = 0 drops the specular reflection; with f > 0 and no
  // baffle an empty sample port reads 0 (the wall-first light is subtracted); baffles change the reading.
  const auto sphere = parse_rxt(header(1, "2") + "0.1 0.1\n", "1");
  SphereModel open;
  open.baffle_r = open.baffle_t = false;
  const double r_std = sphere.standard_reflectance;
  EXPECT_NEAR(sphere_measurements(sphere, open, {r_std, 0, r_std, 0}).first, r_std, 1e-15);
  SphereModel dual;
  dual.dual_beam = true;
  const SampleTotals with_specular{0.4, 0.3, 0.45, 0.25, 0.05, 0.1};
  EXPECT_EQ(sphere_measurements(sphere, dual, with_specular),
            sphere_measurements(parse_rxt(header(0, "2") + "0.1 0.1\n", "0"), with_specular));
  SphereModel no_specular;
  no_specular.unscattered_in_m_r = 0;
  no_specular.unscattered_in_m_t = 0;
  const auto none_c0 = sphere_measurements(parse_rxt(header(0, "2") + "0.1 0.1\n", "0"), no_specular, with_specular);
  EXPECT_DOUBLE_EQ(none_c0.first, 0.4 - 0.05);
  EXPECT_DOUBLE_EQ(none_c0.second, 0.3 - 0.1);
  SphereModel wall_first = open;  // (behind a baffle iad lets the wall-first light bounce once more)
  wall_first.wall_first = 0.3;
  EXPECT_NEAR(sphere_measurements(sphere, wall_first, {}).first, 0, 1e-15);
  EXPECT_NE(sphere_measurements(sphere, open, t).first, one.first);
  EXPECT_NE(sphere_measurements(sphere, open, t).second, one.second);
}

TEST(Rxt, BadFilesNameTheLine) {
  expect_file_error("IAD2\n1.4\n", "x.rxt:1", "IAD1");
  expect_file_error(header(0, "2") + "0.3\n", "x.rxt:12", "row 1 ends after 1 of 2 values (missing M_T)");
  expect_file_error(header(0, "2") + "0.1 nan\n", "x.rxt:12", "M_T = 'nan'");
  expect_file_error(header(0, "2") + "0.1 0.2x\n", "x.rxt:12", "M_T = '0.2x'");
  expect_file_error(header(0, "2"), "x.rxt:11", "no measurement rows");
  expect_file_error("IAD1\n1.4 # sample\n1.5\nabc\n", "x.rxt:4", "sample thickness = 'abc'");
  expect_file_error("IAD1\n1.4\n1.5\n1.0\n", "x.rxt:4", "missing slide thickness");
  expect_file_error(header(3, "2") + "0.1 0.1\n", "x.rxt:8", "number of spheres = 3");
  expect_file_error(header(0, "8") + "0.1\n", "x.rxt:11", "number of measurements = 8: accepted range is 1 to 7");
  expect_file_error(header(0, "r t x") + "0.1 0.2 0.3\n", "x.rxt:11", "column 'x' in 'rtx'");
  expect_file_error(header(0, "L n") + "500 1.4\n", "x.rxt:11", "at least one of r, t, u");
  expect_file_error(header(0, "r t n") + "0.1 0.2 7\n", "x.rxt:12", "sample index of refraction (n) = 7");
  expect_file_error(header(0, "r t i") + "0.1 0.2 95\n", "x.rxt:12", "angle of incidence (i) = 95");
}

TEST(Rxt, ReadsEveryLayoutIadReads) {
  // A count with wavelengths in some rows only (iad: a first value above 1 is a wavelength), rows
  // split across lines, comments anywhere.
  auto f = parse_rxt(header(1, "2") + "500 0.3 # c\n0.4\n0.2 0.1\n", "legacy");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_TRUE(f.rows[0].has_wavelength);
  EXPECT_EQ(f.rows[0].wavelength, 500);
  EXPECT_EQ(f.rows[0].m_t, 0.4);
  EXPECT_EQ(f.rows[0].line, 12);
  EXPECT_FALSE(f.rows[1].has_wavelength);
  EXPECT_EQ(f.rows[1].wavelength, 2);
  // Counts 1 to 7: M_R alone; M_R M_T M_U r_w t_w r_std t_std, the last four overriding the header.
  f = parse_rxt(header(1, "1") + "0.3\n0.25\n", "one");
  EXPECT_EQ(f.measurements, 1);
  EXPECT_EQ(f.rows[1].m_r, 0.25);
  EXPECT_EQ(f.rows[1].m_t, 0);
  f = parse_rxt(header(1, "7") + "0.3 0.2 0.01 0.9 0.8 0.97 0.95\n", "seven");
  EXPECT_EQ(f.measurements, 3);
  EXPECT_EQ(f.rows[0].setup.reflection.wall_reflectance, 0.9);
  EXPECT_EQ(f.rows[0].setup.transmission.wall_reflectance, 0.8);
  EXPECT_EQ(f.rows[0].setup.standard_reflectance, 0.97);
  EXPECT_EQ(f.rows[0].setup.standard_transmittance, 0.95);
  EXPECT_EQ(f.reflection.wall_reflectance, 0.96);  // the header keeps its own
  // Column letters: per-row values override the header from that row on; g holds for its row.
  f = parse_rxt(header(1, "L  r  t  n  d  g  -  w") + "600 0.3 0.2 1.33 2.0 0.8 0.9\n700 0.3 0.2 1.35 2.5 0.7 0.9\n",
                "columns");
  EXPECT_EQ(f.columns, "Lrtndgw");
  EXPECT_EQ(f.measurements, 2);
  EXPECT_EQ(f.rows[1].wavelength, 700);
  EXPECT_EQ(f.rows[1].setup.sample_n, 1.35);
  EXPECT_EQ(f.rows[1].setup.sample_thickness, 2.5);
  EXPECT_EQ(f.rows[1].constraints.g, 0.7);
  EXPECT_EQ(f.rows[1].setup.transmission.wall_reflectance, 0.9);  // w sets both walls
  EXPECT_EQ(f.sample_n, 1.40);
  // The terse layout: everything on one line (iad 4 itself ignores values after the count).
  f = parse_rxt("IAD1 1.34 1.5 1 1 5 .96 1 203.2 25.4 12.7 1 .96 203.2 25.4 12.7 1 .96 2 0.168 0.249 0.162 0.264#",
                "terse");
  ASSERT_EQ(f.rows.size(), 2u);
  EXPECT_EQ(f.rows[1].m_t, 0.264);
  // A slide of index 0 or thickness 0 is no slide (iad).
  f = parse_rxt("IAD1 1.4 0 1 1 5 .96 0 0 0 0 0 0 0 0 0 0 0 2 0.1 0.2", "no slide");
  EXPECT_FALSE(f.has_slides());
}

TEST(Rxt, RowsIadCannotSolveAreFlaggedNotFitted) {
  const auto fit = fit_rxt(parse_rxt(header(0, "3") + "0.6 0.5 0.01\n-0.1 0.5 0.01\n0.1 0.2 0.3\n0.3 0.3 0.01\n", "x"));
  ASSERT_EQ(fit.rows.size(), 4u);
  EXPECT_NE(fit.rows[0].status.find("M_R + M_T = 1.1"), std::string::npos) << fit.rows[0].status;
  EXPECT_NE(fit.rows[1].status.find("M_R = -0.1"), std::string::npos) << fit.rows[1].status;
  EXPECT_NE(fit.rows[2].status.find("M_U = 0.3"), std::string::npos) << fit.rows[2].status;
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(fit.rows[k].converged);
  EXPECT_TRUE(fit.rows[3].converged) << fit.rows[3].status;
}

TEST(Rxt, CommandLineWritesRowsOrFailsWithOneLine) {
  using namespace bssrdf::test_cli;
  const auto good = temp("good.rxt");
  { std::ofstream(good) << header(1, "2") << "0.35 0.25\n0.30 0.20\n"; }
  auto r = run("fit slab --rxt " + good.string() + " -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  ASSERT_EQ(doc["rows"].size(), 2u);
  EXPECT_EQ(doc["header"]["spheres"], 1);
  EXPECT_EQ(doc["rows"][0]["status"], "converged");
  for (const char* key : {"mu_a", "mu_s_prime", "g"}) {
    EXPECT_TRUE(doc["rows"][0][key]["value"].is_number()) << key;
    EXPECT_TRUE(doc["rows"][0][key]["stderr"].is_number()) << key;
  }
  EXPECT_NEAR(doc["rows"][0]["m_r"]["fitted"].get<double>(), 0.35, 1e-3);
  r = run("fit slab --rxt " + good.string() + " -f csv");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(count_lines(r.out), 3);
  const auto bad = temp("bad.rxt");
  { std::ofstream(bad) << header(1, "2") << "0.35 0.25\n0.70 0.4x\n"; }
  const auto out = temp("never.json");
  r = run("fit slab --rxt " + bad.string() + " -o " + out.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.rxt:13: M_T = '0.4x'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Rxt, LostLightCorrectionRecoversWhatTheSmallPortMissed) {
  // A 1 mm sample (mu_s' 1/mm, ell 1 mm) on a 6 mm sample port loses light beyond 3 mm. Data: the
  // sphere's reading of the totals minus the light the Monte Carlo reference sends beyond the
  // port. Without the correction the fit is biased; with it the truth is the fixed point (the
  // correction's Monte Carlo noise, ~7e-4 in R and T here, moves it by ~2 % in mu_a otherwise).
  std::string text = header(1, "2");
  text.replace(text.find("203.2 25.4 12.7 1.0 0.96\n203.2 25.4 12.7 1.0 0.96"), 49,
               "203.2 6.0 12.7 1.0 0.96\n203.2 6.0 12.7 1.0 0.96");
  auto setup = parse_rxt(text + "0.3 0.3\n", "setup");
  const double mu_a = 0.05, mu_s_prime = 1.0;
  LayerStack stack;
  stack.channel_names = {"x"};
  Layer glass, sample;
  glass.n = 1.5, glass.thickness = 1, glass.sigma_a = glass.sigma_s = glass.g = {0.0};
  sample.n = 1.4, sample.thickness = 1, sample.sigma_a = {mu_a}, sample.sigma_s = {mu_s_prime}, sample.g = {0.0};
  stack.layers = {glass, sample, glass};
  MonteCarloOptions mc;
  mc.photons = 200000;  // the correction's own photons and seed: at the truth it computes these losses exactly
  mc.seed = 1;
  mc.bins = 2;
  mc.r_max = 3.0;
  const auto ch = run_monte_carlo(stack, mc).channels[0];
  const double ur1_lost = ch.reflectance_beyond, ut1_lost = ch.transmittance_beyond;
  ASSERT_GT(ut1_lost, 0.02);  // a real loss
  adding_doubling::Slab slab = adding_doubling::slab_of(stack, 0);
  const auto both =
      adding_doubling::solve(slab, {adding_doubling::Incidence::collimated, adding_doubling::Incidence::diffuse});
  const auto [m_r, m_t] = sphere_measurements(
      setup, {both[0].specular_reflectance + both[0].diffuse_reflectance - ur1_lost,
              both[0].total_transmittance - ut1_lost, both[1].specular_reflectance + both[1].diffuse_reflectance,
              both[1].total_transmittance, both[0].unscattered_reflectance, both[0].unscattered_transmittance});
  std::ostringstream rows;
  rows.precision(12);
  rows << m_r << ' ' << m_t << '\n';
  const auto file = parse_rxt(text + rows.str(), "lossy");
  RxtFitOptions options;
  const auto plain = fit_rxt(file, options);
  options.lost_light = true;
  options.lost_light_photons = 200000;
  const auto corrected = fit_rxt(file, options);
  std::printf("  mu_a, mu_s': truth %.4f %.4f; uncorrected %.4f %.4f; corrected %.4f %.4f (lost R %.4f, T %.4f)\n",
              mu_a, mu_s_prime, plain.rows[0].mu_a, plain.rows[0].mu_s_prime, corrected.rows[0].mu_a,
              corrected.rows[0].mu_s_prime, corrected.rows[0].ur1_lost, corrected.rows[0].ut1_lost);
  EXPECT_GT(std::abs(plain.rows[0].mu_a / mu_a - 1), 0.05);  // the loss looks like absorption
  EXPECT_NEAR(corrected.rows[0].mu_a / mu_a, 1, 0.01);
  EXPECT_NEAR(corrected.rows[0].mu_s_prime / mu_s_prime, 1, 0.01);
  EXPECT_THROW(fit_rxt(parse_rxt(header(0, "2") + "0.3 0.3\n", "no sphere"), options), InvalidInput);
}

TEST(Rxt, ConvergedRowsNearIadsAlbedoEdgesSayWhy) {
  // a = mu_s / (mu_a + mu_s), mu_s = mu_s' / (1 - g): marked within 1 % of a = 1 or a = 0 and on
  // either edge, plain "converged" elsewhere.
  EXPECT_EQ(converged_status(0.1, 5, 0, 1e-20), "converged");      // a = 0.980
  EXPECT_EQ(converged_status(0.1, 0.5, 0.8, 1e-20), "converged");  // a = 0.962
  const auto near_one = converged_status(0.01, 5, 0, 1.6e-24);     // a = 0.998
  EXPECT_EQ(near_one.rfind("converged; albedo a = 0.998004, within 1 % of 1", 0), 0u) << near_one;
  EXPECT_NE(near_one.find("flag the row 'x'"), std::string::npos) << near_one;
  EXPECT_NE(near_one.find("chi^2 = 1.6e-24"), std::string::npos) << near_one;
  EXPECT_EQ(converged_status(0.01, 0.5, 0.5, 0).rfind("converged; albedo a = 0.990099", 0), 0u);  // mu_s = 1
  EXPECT_NE(converged_status(5, 0.01, 0, 0).find("within 1 % of 0"), std::string::npos);          // a = 0.002
  EXPECT_EQ(converged_status(0, 5, 0, 2.8).rfind("converged at the edge mu_a = 0", 0), 0u);
  EXPECT_EQ(converged_status(1.4e-11, 5, 0, 2.8).rfind("converged at the edge mu_a = 0", 0), 0u);  // our bound
  EXPECT_EQ(converged_status(0.3, 0, 0, 0.085).rfind("converged at the edge mu_s' = 0", 0), 0u);
}
