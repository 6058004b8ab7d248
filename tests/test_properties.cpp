// Property tests over randomised inputs (seeded, so reproducible): for every model, R(r) is finite
// and >= 0, its total equals an independent quadrature of 2 pi r R, the CDF rises monotonically and
// radius_for_fraction inverts it; fits cover the truth at their stated 1-sigma rate and widen their
// 1-sigma when chi^2/dof says the model cannot explain the data; writers read back exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/profile_fit.hpp"
#include "bssrdf/io/profile_csv.hpp"
#include "bssrdf/io/renderer_export.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/profile_report.hpp"

using namespace bssrdf;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Media a renderer meets: alpha' 0.5-0.999, sigma_t' 0.1-100 /mm, eta 1.0-1.6, g -0.3-0.9.
std::vector<Reduced<double>> random_media(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Reduced<double>> out;
  for (int i = 0; i < count; ++i) {
    const double albedo = 1 - std::pow(10.0, -0.3 - 2.7 * u(rng));  // 0.5 .. 0.998, log-uniform in 1 - alpha'
    const double sigma_t = std::pow(10.0, -1 + 3 * u(rng));
    const double g = -0.3 + 1.2 * u(rng), eta = 1.0 + 0.6 * u(rng);
    const double sigma_s_prime = albedo * sigma_t;
    out.push_back(reduce(sigma_t - sigma_s_prime, sigma_s_prime / (1 - g), g, eta));
  }
  return out;
}

// Outside a tabulated model's table (exact: g < 0 here) it refuses, its validity report says why.
bool outside_its_table(const Model& model, const Reduced<double>& m) {
  for (const auto& note : model.validity(m))
    if (note.severity == Severity::invalid && note.code.rfind("exact_", 0) == 0) return true;
  return false;
}

class ModelProperties : public ::testing::TestWithParam<std::string> {};

TEST_P(ModelProperties, ProfileIsFiniteNonNegativeAndIntegratesToItsTotal) {
  const auto model = make_model(GetParam());
  int checked = 0, refused = 0;
  for (const auto& m : random_media(7, 12)) {
    if (outside_its_table(*model, m)) {
      EXPECT_THROW(model->total_reflectance(m), InvalidInput) << GetParam();
      ++refused;
      continue;
    }
    const double total = model->total_reflectance(m);
    ASSERT_TRUE(std::isfinite(total) && total >= 0) << GetParam() << " total " << total;
    // Independent quadrature: trapezoid in ln r of 2 pi r^2 R(r) over 1e-6 .. 1e3 transport mfp.
    const auto radii = log_spaced(1e-6 * m.ell, 1e3 * m.ell, 1500);
    double integral = 0, previous = 0;
    for (std::size_t i = 0; i < radii.size(); ++i) {
      const double R = model->reflectance(m, radii[i]);
      ASSERT_TRUE(std::isfinite(R)) << GetParam() << " R(" << radii[i] << ") = " << R;
      ASSERT_GE(R, 0.0) << GetParam() << " at r = " << radii[i] << ", alpha' = " << m.albedo_prime;
      const double f = 2 * kPi * radii[i] * radii[i] * R;
      if (i > 0) integral += 0.5 * (f + previous) * std::log(radii[i] / radii[i - 1]);
      previous = f;
    }
    // The part inside 1e-6 ell is below 1e-6 of the total for every model (R ~ 1/r at worst).
    EXPECT_NEAR(integral, total, 2e-3 * total + 1e-9)
        << GetParam() << " alpha' = " << m.albedo_prime << ", eta = " << m.eta;
    ++checked;
  }
  EXPECT_EQ(checked + refused, 12);
  EXPECT_GE(checked, 6) << GetParam();
}

// Monotone to within the quadrature: models without a closed-form CDF integrate R(r) adaptively to
// a relative tolerance of 1e-9 (Model::cumulative_reflectance), so a decrease below 1e-9 of the
// total is quadrature noise; the worst one seen is printed.
TEST_P(ModelProperties, CdfIsMonotoneAndRadiusForFractionInvertsIt) {
  const auto model = make_model(GetParam());
  double worst_decrease = 0;
  for (const auto& m : random_media(11, 8)) {
    const double total = model->total_reflectance(m);
    double last = 0;
    for (double r : log_spaced(1e-3 * m.ell, 100 * m.ell, 40)) {
      const double c = model->cumulative_reflectance(m, r);
      EXPECT_GE(c, last - 1e-9 * total) << GetParam() << " at r = " << r;
      EXPECT_LE(c, total * (1 + 1e-6)) << GetParam();
      worst_decrease = std::max(worst_decrease, (last - c) / total);
      last = c;
    }
    for (double fraction : {0.05, 0.5, 0.9, 0.99}) {
      const double r = model->radius_for_fraction(m, fraction);
      ASSERT_TRUE(std::isfinite(r) && r > 0) << GetParam();
      EXPECT_NEAR(model->cumulative_reflectance(m, r) / total, fraction, 1e-6)
          << GetParam() << " fraction " << fraction;
    }
  }
  std::printf("%s: largest CDF decrease %.2g of the total\n", GetParam().c_str(), worst_decrease);
}

INSTANTIATE_TEST_SUITE_P(EveryModel, ModelProperties, ::testing::ValuesIn(model_names()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

// Synthetic measurement of one channel: 48 log-spaced radii, relative Gaussian noise `noise`.
MeasuredProfile measure(const std::string& model_name, double sigma_a, double sigma_s_prime, double noise,
                        std::mt19937_64& rng) {
  const auto model = make_model(model_name);
  const auto m = reduce(sigma_a, sigma_s_prime, 0.0, 1.3);
  MeasuredProfile data;
  data.file = "synthetic";
  data.radius = log_spaced(0.05, 10.0, 48);
  std::normal_distribution<double> gauss(0.0, 1.0);
  MeasuredProfile::Channel ch{"R", {}, {}};
  for (double r : data.radius) {
    const double v = model->reflectance(m, r);
    ch.value.push_back(v * (1 + noise * gauss(rng)));
    ch.standard_error.push_back(noise * v);
  }
  data.channels.push_back(ch);
  return data;
}

// The reported 1-sigma covers the truth at the normal rates: 68 % within 1 sigma, 95 % within 2.
TEST(FitProperties, OneSigmaCoversTheTruthAtItsStatedRate) {
  std::mt19937_64 rng(2026);
  const int trials = 60;
  int within1 = 0, within2 = 0;
  for (int t = 0; t < trials; ++t) {
    const auto data = measure("better-dipole", 0.05, 1.2, 0.03, rng);
    ProfileFitOptions options;
    options.model = "better-dipole";  // the model that made the data
    const auto report = fit_profile(data, options);
    const auto* a = report.find("sigma_a", "R");
    ASSERT_TRUE(std::isfinite(a->standard_error) && a->standard_error > 0);
    const double z = std::abs(a->value - 0.05) / a->standard_error;
    within1 += z <= 1;
    within2 += z <= 2;
  }
  // Binomial 3-sigma bands around 0.683 and 0.954 for 60 trials.
  EXPECT_NEAR(within1 / double(trials), 0.683, 0.18) << within1;
  EXPECT_GE(within2 / double(trials), 0.954 - 0.081) << within2;
}

// chi^2/dof > 1: the 1-sigma are widened by sqrt(chi^2/dof), so they equal those of the same fit
// with standard errors scaled to make chi^2/dof = 1, and the report says so.
TEST(FitProperties, UncertaintiesWidenWhenTheModelCannotExplainTheData) {
  std::mt19937_64 rng(5);
  auto data = measure("dipole", 0.05, 1.2, 0.01, rng);  // dipole data, fitted with pbd: a model error
  ProfileFitOptions options;
  options.model = "pbd";
  const auto misfit = fit_profile(data, options);
  double chi2_dof = 0;
  for (const auto& r : misfit.residuals) chi2_dof += r.weighted * r.weighted;
  chi2_dof /= static_cast<double>(misfit.residuals.size() - 2);
  ASSERT_GT(chi2_dof, 4.0);
  bool said = false;
  for (const auto& w : misfit.warnings) said |= w.find("widened by sqrt(chi^2/dof)") != std::string::npos;
  EXPECT_TRUE(said) << misfit.full_report();

  for (auto& s : data.channels[0].standard_error) s *= std::sqrt(chi2_dof);
  const auto scaled = fit_profile(data, options);
  for (const char* p : {"sigma_a", "sigma_s_prime", "albedo_prime"}) {
    EXPECT_NEAR(misfit.find(p, "R")->value, scaled.find(p, "R")->value, 1e-6 * misfit.find(p, "R")->value) << p;
    EXPECT_NEAR(misfit.find(p, "R")->standard_error / scaled.find(p, "R")->standard_error, 1.0, 1e-3) << p;
  }
}

// The profile CSV writer's output reads back to the same numbers (shortest round-trip formatting).
TEST(WriterProperties, ProfileCsvReadsBackExactly) {
  Medium medium;
  medium.channel_names = {"R", "G", "B"};
  medium.sigma_a = {0.032, 0.17, 0.48};
  medium.sigma_s = {0.74, 0.88, 1.01};
  medium.g = {0, 0, 0};
  medium.eta = 1.3;
  const auto model = make_model("better-dipole");
  for (const auto unit : {LengthUnit::millimetre, LengthUnit::centimetre}) {
    const auto report = compute_profile_report(medium, *model, log_spaced(0.01, 20, 37), unit);
    const auto back = parse_profile_csv(to_csv(report), "written.csv");
    ASSERT_EQ(back.channels.size(), 3u);
    for (std::size_t c = 0; c < 3; ++c) {
      const auto& written = report.channels[c].profile;
      ASSERT_EQ(back.channels[c].value.size(), written.value.size());
      const double mm = millimetres_per(unit);
      for (std::size_t i = 0; i < written.value.size(); ++i) {
        // Read back in mm: equal to the written value (in the file's unit) converted, to rounding.
        EXPECT_NEAR(back.radius[i], written.radius[i] * mm, 1e-15 * written.radius[i] * mm);
        EXPECT_NEAR(back.channels[c].value[i], written.value[i] / (mm * mm), 1e-15 * written.value[i] / (mm * mm));
      }
    }
  }
}

// The materials JSON export loads back to the same media, for every bundled material and unit.
TEST(WriterProperties, MaterialsJsonExportLoadsBack) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  for (const auto unit : {LengthUnit::millimetre, LengthUnit::micrometre, LengthUnit::metre}) {
    std::vector<ExportEntry> entries;
    for (const auto& m : db.all()) entries.push_back({m, {}});
    MaterialDatabase back;
    back.add_text(export_materials(RendererTarget::json, entries, unit), "exported.json");
    ASSERT_EQ(back.all().size(), db.all().size());
    for (std::size_t i = 0; i < db.all().size(); ++i) {
      const Medium& a = db.all()[i].medium;
      const Medium& b = back.find(db.all()[i].name).medium;
      EXPECT_DOUBLE_EQ(a.eta, b.eta);
      for (std::size_t c = 0; c < a.channels(); ++c) {
        EXPECT_NEAR(b.sigma_a[c], a.sigma_a[c], 1e-14 * a.sigma_a[c]) << db.all()[i].name;
        EXPECT_NEAR(b.sigma_s[c] * (1 - b.g[c]), a.sigma_s[c] * (1 - a.g[c]), 1e-14 * a.sigma_s[c]) << db.all()[i].name;
      }
    }
  }
}

// The Monte Carlo CSV reads back (as 'fit profile' reads it) to the run's per-entered-flux R(r).
TEST(WriterProperties, MonteCarloCsvReadsBackAsItsEnteredFluxProfile) {
  Medium medium = Medium::single_channel(0.1, 5, 0.5, 1.4);
  MonteCarloOptions options;
  options.photons = 20000;
  options.bins = 30;
  const auto result = run_monte_carlo(LayerStack::half_space(medium), options);
  const auto back = parse_profile_csv(to_csv(result, LengthUnit::millimetre), "mc.csv");
  ASSERT_EQ(back.channels.size(), 1u);
  const auto entered = result.channels[0].per_entered_flux();
  std::size_t k = 0;
  for (std::size_t i = 0; i < result.bin_radius.size(); ++i) {
    if (entered.reflectance[i] == 0 && entered.reflectance_stderr[i] == 0) continue;  // skipped: no photon
    ASSERT_LT(k, back.radius.size());
    EXPECT_DOUBLE_EQ(back.radius[k], result.bin_radius[i]);
    EXPECT_DOUBLE_EQ(back.channels[0].value[k], entered.reflectance[i]);
    EXPECT_DOUBLE_EQ(back.channels[0].standard_error[k], entered.reflectance_stderr[i]);
    ++k;
  }
  EXPECT_EQ(k, back.radius.size());
  EXPECT_EQ(back.empty_bins, result.bin_radius.size() - k);
}

}  // namespace
