// The model registry is the one place a model is described: every name constructs as itself,
// names are unique, every model fits through its forward form, `bssrdf models` lists every listed
// row, and `--model auto` serves exactly the registry's candidates.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/profile_fit.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/profile.hpp"
#include "cli_runner.hpp"

using namespace bssrdf;

TEST(ModelRegistry, EveryNameConstructsAsItselfAndNamesAreUnique) {
  std::set<std::string> seen;
  for (const auto& e : model_registry()) {
    EXPECT_TRUE(seen.insert(e.name).second) << e.name << " appears twice";
    const auto model = make_model(e.name);
    ASSERT_TRUE(model) << e.name;
    EXPECT_EQ(model->name(), e.name);
    EXPECT_EQ(model->includes_single_scattering(), e.includes_single_scattering) << e.name;
    EXPECT_EQ(&model_entry(e.name), &e);
    const auto m = reduce(0.1, 10.0, 0.0, 1.3);
    EXPECT_GT(model->reflectance(m, m.ell), 0) << e.name;
    if (!e.base.empty()) {  // NAME+ss: NAME omits single scattering and is a row too
      ASSERT_NE(find_model_entry(e.base), nullptr) << e.name;
      EXPECT_FALSE(model_entry(e.base).includes_single_scattering) << e.name;
      EXPECT_EQ(e.name, e.base + "+ss");
    }
  }
  EXPECT_EQ(find_model_entry("tripole"), nullptr);
  EXPECT_THROW(model_entry("tripole"), InvalidInput);
  EXPECT_THROW(make_model("pbd+ss"), InvalidInput);  // pbd already includes single scattering
}

TEST(ModelRegistry, ModelNamesAreTheListedRows) {
  std::vector<std::string> listed;
  for (const auto& e : model_registry())
    if (e.listed) listed.push_back(e.name);
  EXPECT_EQ(model_names(), listed);
  EXPECT_GE(listed.size(), 7u);
}

TEST(ModelRegistry, ValidityBandsComeFromTheRegistry) {
  for (const auto& e : model_registry()) {
    if (!e.limits) {
      EXPECT_THROW(measured_limits(e.name), std::out_of_range) << e.name;
      continue;
    }
    // The registry quotes the bands of models/measured_bands.cpp (below it): the same numbers.
    const auto& bands = measured_limits(e.name);
    ASSERT_EQ(bands.isotropic_bands.size(), e.limits->isotropic_bands.size()) << e.name;
    for (std::size_t i = 0; i < bands.isotropic_bands.size(); ++i) {
      EXPECT_EQ(bands.isotropic_bands[i].worst_error, e.limits->isotropic_bands[i].worst_error) << e.name;
      EXPECT_EQ(bands.forward_bands[i].worst_error, e.limits->forward_bands[i].worst_error) << e.name;
    }
  }
}

// Noise-free data from each model, fitted with the same model through its registry forward form
// (templated forms by automatic differentiation, numeric forms by finite differences): the
// coefficients come back.
TEST(ModelRegistry, EveryModelFitsItsOwnProfile) {
  const double sigma_a = 0.05, sigma_s_prime = 2.0, eta = 1.3;
  for (const auto& e : model_registry()) {
    const auto model = e.make();
    MeasuredProfile data;
    data.file = "synthetic " + e.name;
    data.radius = log_spaced(0.05, 10.0, 48);
    MeasuredProfile::Channel ch{"R", {}, {}};
    const auto m = reduce(sigma_a, sigma_s_prime, 0.0, eta);
    for (double r : data.radius) ch.value.push_back(model->reflectance(m, r));
    data.channels.push_back(ch);
    ProfileFitOptions options;
    options.model = e.name;
    options.eta = eta;
    const auto report = fit_profile(data, options);
    EXPECT_TRUE(report.converged) << e.name << ": " << report.termination;
    EXPECT_NEAR(report.find("sigma_a", "R")->value / sigma_a, 1, 2e-3) << e.name;
    EXPECT_NEAR(report.find("sigma_s_prime", "R")->value / sigma_s_prime, 1, 2e-3) << e.name;
  }
}

TEST(ModelRegistry, AutoCandidatesAreTheRegistryCandidates) {
  std::set<std::string> candidates, measured;
  for (const auto& e : model_registry())
    if (e.auto_candidate) {
      candidates.insert(e.name);
      EXPECT_TRUE(e.limits || e.reference_accuracy)
          << e.name << ": a candidate needs measured bands for its validity report";
      EXPECT_GT(e.cost_ns, 0) << e.name;
    }
  std::set<std::string> tabulated;  // the candidates with a column of the Monte Carlo table: all but reference models
  for (const auto& name : candidates)
    if (!model_entry(name).reference_accuracy) tabulated.insert(name);
  for (const auto& m : measured_models()) {
    measured.insert(m.model);
    EXPECT_EQ(m.cost_ns, model_entry(m.model).cost_ns) << m.model;
  }
  EXPECT_EQ(measured, tabulated);
  const auto estimates = estimate_model_errors(reduce(0.01, 1.0, 0.0, 1.3));
  ASSERT_TRUE(estimates);
  std::set<std::string> estimated;
  for (const auto& e : *estimates) estimated.insert(e.model);
  EXPECT_EQ(estimated, candidates);
}

TEST(ModelRegistry, CapabilitiesAreTyped) {
  for (const auto& e : model_registry()) {
    if (e.with_surface_albedo) {
      const auto with_a = e.with_surface_albedo(0.5);
      EXPECT_EQ(with_a->name(), e.name);
      EXPECT_NEAR(with_a->total_reflectance(reduce(0.1, 10.0, 0.0, 1.3)), 0.5, 1e-12) << e.name;
    }
  }
  for (const auto& e : model_registry())
    if (e.own_gaussians) {  // its own mixture carries its total
      const auto m = reduce(0.1, 10.0, 0.0, 1.3);
      const auto model = e.make();
      double sum = 0;
      for (double w : e.own_gaussians(*model, m).weight) sum += w;
      EXPECT_NEAR(sum / model->total_reflectance(m), 1, 1e-3) << e.name;
    }
  EXPECT_TRUE(model_entry("quantized").own_gaussians);
  EXPECT_FALSE(model_entry("pbd").own_gaussians);
  EXPECT_TRUE(model_entry("burley-dmfp").with_surface_albedo);
  EXPECT_FALSE(model_entry("dipole").with_surface_albedo);
}

TEST(ModelRegistry, ModelsCommandListsEveryListedRow) {
  const auto run = test_cli::run("models --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto list = nlohmann::json::parse(run.out);
  std::vector<std::string> names;
  for (const auto& item : list) names.push_back(item.at("name").get<std::string>());
  EXPECT_EQ(names, model_names());
  for (const auto& item : list)
    EXPECT_EQ(item.at("includes_single_scattering").get<bool>(),
              model_entry(item.at("name").get<std::string>()).includes_single_scattering);
}
