// iad's constraints in 'fit slab --rxt' (-a, -b, -A, -F with its power law, -j): the rows a file
// of forward readings makes are solved back to the truth with each constraint held at its true
// value, g fitted from M_R and M_T when not given (iad's two-parameter searches) and the other
// coefficient from M_T alone when g is given (iad's one-parameter searches, which ignore M_R);
// M_R alone gives a semi-infinite sample's albedo; bad constraints fail with one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/integrating_sphere.hpp"
#include "bssrdf/fit/rxt_fit.hpp"
#include "bssrdf/io/rxt.hpp"
#include "cli_runner.hpp"

using namespace bssrdf;

namespace {

std::string header(int spheres, const char* legend) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "IAD1\n1.40\n1.50\n1.0\n1.0\n5.0\n0.98\n%d\n203.2 25.4 12.7 1.0 0.96\n203.2 25.4 12.7 1.0 0.96\n%s\n",
                spheres, legend);
  return buffer;
}

struct Truth {
  double lambda, mu_a, mu_s, g;
};

// A file whose rows are what the instrument reads for each truth (32 angles, as the fit).
RxtFile file_of(int spheres, const std::vector<Truth>& truths, bool with_m_t = true) {
  const auto setup = parse_rxt(header(spheres, "2") + "0.3 0.3\n", "setup");
  std::ostringstream text;
  text.precision(14);
  text << header(spheres, with_m_t ? "Lrt" : "Lr");
  for (const auto& t : truths) {
    adding_doubling::Slab slab;
    slab.layers = {{t.mu_a, t.mu_s, t.g, setup.sample_thickness}};
    slab.n = setup.sample_n;
    slab.above = slab.below = {{setup.slide_n, setup.slide_thickness, 0.0}};
    adding_doubling::Options ad;
    ad.points = 32;
    const auto both =
        adding_doubling::solve(slab, {adding_doubling::Incidence::collimated, adding_doubling::Incidence::diffuse}, ad);
    const auto [m_r, m_t] = sphere_measurements(
        setup, {both[0].specular_reflectance + both[0].diffuse_reflectance, both[0].total_transmittance,
                both[1].specular_reflectance + both[1].diffuse_reflectance, both[1].total_transmittance,
                both[0].unscattered_reflectance, both[0].unscattered_transmittance});
    text << t.lambda << ' ' << m_r;
    if (with_m_t) text << ' ' << m_t;
    text << '\n';
  }
  return parse_rxt(text.str(), "truth.rxt");
}

const std::vector<Truth> kTruths = {{500, 0.05, 2.0, 0.6}, {600, 0.2, 4.0, 0.3}, {700, 0.01, 1.0, 0.8}};

// The truth, to 1e-5 where the rows determine it; where they do not (a held mu_a leaves mu_s and g
// nearly interchangeable through mu_s' in a thin sample: g +- 0.6) the fit must reproduce the
// readings exactly and say so in its errors, the truth within 3 of them.
int expect_truth(const RxtFit& fit, const std::vector<Truth>& truths, bool g_fitted, const std::string& what) {
  EXPECT_EQ(fit.rows.size(), truths.size());
  int ambiguous = 0;
  for (std::size_t k = 0; k < truths.size() && k < fit.rows.size(); ++k) {
    const auto& r = fit.rows[k];
    const auto& t = truths[k];
    const std::string where = what + " row " + std::to_string(k) + ": " + r.constraint;
    EXPECT_TRUE(r.converged) << where << "; " << r.status;
    EXPECT_EQ(r.g_stderr > 0, g_fitted) << where;
    EXPECT_FALSE(r.constraint.empty());
    const double mu_s_prime = t.mu_s * (1 - t.g);
    const bool recovered = std::abs(r.mu_a / t.mu_a - 1) < 1e-5 && std::abs(r.mu_s_prime / mu_s_prime - 1) < 1e-5 &&
                           std::abs(r.g - t.g) < 1e-5;
    if (!recovered && r.g_stderr > 0.05) {
      ++ambiguous;
      EXPECT_LT(r.chi2, 1e-12) << where;
      EXPECT_LT(std::abs(r.g - t.g), 3 * r.g_stderr) << where;
      EXPECT_LT(std::abs(r.mu_s_prime - mu_s_prime), 3 * r.mu_s_prime_stderr) << where;
      EXPECT_LT(std::abs(r.mu_a - t.mu_a), 3 * r.mu_a_stderr + 1e-12 * t.mu_a) << where;
      continue;
    }
    EXPECT_NEAR(r.mu_a / t.mu_a, 1, 1e-5) << where;
    EXPECT_NEAR(r.mu_s_prime / mu_s_prime, 1, 1e-5) << where;
    EXPECT_NEAR(r.g, t.g, 1e-5) << where;
  }
  return ambiguous;
}

}  // namespace

TEST(RxtConstraints, EachConstraintWithMrMtSolvesTheOtherCoefficientAndG) {
  int ambiguous = 0;
  for (int spheres : {0, 1, 2}) {
    const auto file = file_of(spheres, kTruths);
    for (int which = 0; which < 4; ++which) {
      // The constraint at the truth of every row needs a row column (the options hold one value
      // for all rows): write the truths as the file's constraint column instead.
      std::ostringstream text;
      text.precision(14);
      const char* letter = "abAF";
      text << header(spheres, (std::string("Lrt") + letter[which]).c_str());
      for (std::size_t k = 0; k < kTruths.size(); ++k) {
        const auto& t = kTruths[k];
        const double held[] = {t.mu_s / (t.mu_a + t.mu_s), t.mu_a + t.mu_s, t.mu_a, t.mu_s};  // d = 1 mm
        text << t.lambda << ' ' << file.rows[k].m_r << ' ' << file.rows[k].m_t << ' ' << held[which] << '\n';
      }
      const auto fit = fit_rxt(parse_rxt(text.str(), "held.rxt"));
      ambiguous += expect_truth(fit, kTruths, true, std::to_string(spheres) + " spheres, column " + letter[which]);
      EXPECT_NE(fit.rows[0].constraint.find("g from M_R, M_T"), std::string::npos) << fit.rows[0].constraint;
    }
  }
  EXPECT_LE(ambiguous, 2) << "of 36 rows";  // measured: 2 (mu_a held, row 0, 0 and 2 spheres)
}

TEST(RxtConstraints, OptionsHoldEveryRowAndThePowerLawFollowsTheWavelength) {
  // mu_s = 2 (lambda / 500)^-1.5 and mu_a = 0.05 in every row; g differs per row.
  std::vector<Truth> truths;
  for (double lambda : {450.0, 500.0, 650.0}) truths.push_back({lambda, 0.05, 2 * std::pow(lambda / 500, -1.5), 0.5});
  truths[1].g = 0.7;
  const auto file = file_of(1, truths);
  RxtFitOptions options;
  options.constraints.power_lambda0 = 500;
  options.constraints.power_mu_s0 = 2;
  options.constraints.power_gamma = -1.5;
  expect_truth(fit_rxt(file, options), truths, true, "power law");
  options.constraints = {};
  options.constraints.mu_a = 0.05;
  expect_truth(fit_rxt(file, options), truths, true, "mu_a option");
  // Held wrong, the solution moves: mu_a 10 % high gives another mu_s', and the status says what was held.
  options.constraints.mu_a = 0.055;
  const auto wrong = fit_rxt(file, options);
  EXPECT_GT(std::abs(wrong.rows[0].mu_s_prime / (truths[0].mu_s * 0.5) - 1), 1e-3);
  EXPECT_NE(wrong.rows[0].constraint.find("mu_a = 0.055 (iad -A) held"), std::string::npos) << wrong.rows[0].constraint;
}

TEST(RxtConstraints, WithGGivenTheOtherCoefficientComesFromMtAloneAsIad) {
  const std::vector<Truth> truths = {{500, 0.05, 2.0, 0.6}};
  const auto file = file_of(0, truths);
  RxtFitOptions options;
  options.g = 0.6;
  options.constraints.albedo = 2.0 / 2.05;
  expect_truth(fit_rxt(file, options), truths, false, "a held, g given");
  // g given wrong: M_T is still matched exactly, M_R is not (iad's one-parameter search ignores it).
  options.g = 0.3;
  const auto r = fit_rxt(file, options).rows[0];
  EXPECT_TRUE(r.converged) << r.status;
  EXPECT_NEAR(r.fitted_m_t, file.rows[0].m_t, 1e-9);
  EXPECT_GT(std::abs(r.fitted_m_r - file.rows[0].m_r), 1e-3);
  EXPECT_NE(r.constraint.find("b from M_T"), std::string::npos) << r.constraint;
}

TEST(RxtConstraints, MrAloneWithMuSHeldIsASemiInfiniteSampleOfThatMuS) {
  // iad: with M_T = 0 a held mu_s leaves a half-space's albedo a, and mu_a = mu_s (1/a - 1); without
  // a constraint mu_s = 1/mm by convention. Both from the same albedo: mu_a scales with the held mu_s.
  const auto file = file_of(0, {{500, 0.1, 2.0, 0.0}}, false);
  const auto plain = fit_rxt(file).rows[0];
  RxtFitOptions options;
  options.constraints.mu_s = 3;
  const auto held = fit_rxt(file, options).rows[0];
  ASSERT_TRUE(held.converged) << held.status;
  EXPECT_NEAR(held.mu_a / (3 * plain.mu_a), 1, 1e-6);
  EXPECT_NEAR(held.mu_s_prime, 3, 1e-12);
  EXPECT_NE(held.constraint.find("semi-infinite"), std::string::npos) << held.constraint;
}

TEST(RxtConstraints, BadConstraintsFailWithOneLine) {
  const auto file = file_of(0, kTruths);
  RxtFitOptions options;
  options.constraints.albedo = 0.9;
  options.constraints.mu_a = 0.1;
  EXPECT_THROW(fit_rxt(file, options), InvalidInput);
  options.constraints = {};
  options.constraints.albedo = 1.5;
  EXPECT_THROW(fit_rxt(file, options), InvalidInput);
  using namespace bssrdf::test_cli;
  const auto no_lambda = temp("no_lambda.rxt");
  { std::ofstream(no_lambda) << header(0, "2") << "0.35 0.25\n"; }
  auto r = run("fit slab --rxt " + no_lambda.string() + " --fixed-mu-s 'P 500 1 -1'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("without a wavelength"), std::string::npos) << r.err;
  for (const char* bad : {"--fixed-mu-s 'P 500 1'", "--fixed-albedo x", "--fixed-mu-a -1",
                          "--fixed-mu-s 1 --fixed-mu-s-prime 1", "--fixed-albedo 0.5 --fixed-optical-thickness 2"}) {
    r = run("fit slab --rxt " + no_lambda.string() + " " + bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_EQ(count_lines(r.err), 1) << bad << ": " << r.err;
  }
  r = run("fit slab --reflectance 0.3 --transmittance 0.3 --thickness 1 --fixed-albedo 0.9");
  EXPECT_EQ(r.status, 2) << "a constraint without --rxt";
  r = run("fit slab --rxt " + no_lambda.string() + " --fixed-albedo 0.9 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["constraints"]["albedo"], 0.9);
  EXPECT_TRUE(doc["constraints"]["mu_a"].is_null());
  EXPECT_TRUE(doc["g_held"].is_null());
  EXPECT_NE(doc["rows"][0]["constraint"].get<std::string>().find("a = 0.9 (iad -a) held; b, g from M_R, M_T"),
            std::string::npos)
      << doc["rows"][0]["constraint"];
  r = run("fit slab --rxt " + no_lambda.string() + " --fixed-albedo 0.9");
  EXPECT_NE(r.out.find("constraints (iad's): albedo a = 0.9 held"), std::string::npos) << r.out;
}
