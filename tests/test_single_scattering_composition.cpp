// Which composition of each model reproduces the full radiative-transfer total (single scattering
// included): the model alone or NAME+ss (plus the exact single scattering)? Exact totals by
// adding-doubling; the chosen labels (includes_single_scattering, which NAME+ss exist) must be the
// nearer composition. The Monte Carlo check of the same table (its single-scattering part
// included) is tools/validation/single_scattering_composition.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/single_scattering.hpp"

using namespace bssrdf;

namespace {

struct Case {
  double albedo_prime, g, eta, exact;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (double g : {0.0, 0.9})
    for (double eta : {1.0, 1.4})
      for (double a : {0.8, 0.9, 0.95, 0.99}) {
        const auto t = adding_doubling::solve(adding_doubling::half_space(reduce(1 - a, a / (1 - g), g, eta)),
                                              adding_doubling::Incidence::collimated);
        out.push_back({a, g, eta, t.diffuse_reflectance * t.entered_scale()});
      }
  return out;
}

// |relative error| of the model's total alone and with the exact single scattering added.
struct Errors {
  double alone, plus_ss;
};
Errors errors(const Model& model, const Case& c) {
  const auto m = reduce(1 - c.albedo_prime, c.albedo_prime / (1 - c.g), c.g, c.eta);
  const double total = model.total_reflectance(m);
  const double ss = single_scattering_total(m.albedo(), m.g, m.eta);
  return {std::abs(total / c.exact - 1), std::abs((total + ss) / c.exact - 1)};
}

}  // namespace

TEST(SingleScatteringComposition, LabelsAgreeWithWhatEachModelReproduces) {
  const auto table = cases();
  for (const char* name : {"dipole", "better-dipole", "quantized"}) {
    const auto model = make_model(name);
    double sum_alone[2] = {0, 0}, sum_ss[2] = {0, 0};
    int alone_nearer[2] = {0, 0};
    for (const auto& c : table) {
      const auto e = errors(*model, c);
      const int k = c.g > 0.5;
      sum_alone[k] += e.alone;
      sum_ss[k] += e.plus_ss;
      alone_nearer[k] += e.alone < e.plus_ss;
      const auto m = reduce(1 - c.albedo_prime, c.albedo_prime / (1 - c.g), c.g, c.eta);
      const double total = model->total_reflectance(m), ss = single_scattering_total(m.albedo(), m.g, m.eta);
      std::printf("  %-14s alpha' %.2f g %.1f eta %.1f exact %.5f  alone %+.3f  +ss %+.3f\n", name, c.albedo_prime, c.g,
                  c.eta, c.exact, total / c.exact - 1, (total + ss) / c.exact - 1);
    }
    const bool has_plus_ss = find_model_entry(std::string(name) + "+ss") != nullptr;
    if (std::string(name) == "dipole") {
      // Alone nearer in every case at g = 0 and overall: it includes single scattering, no dipole+ss.
      EXPECT_EQ(alone_nearer[0], 8);
      EXPECT_LT(sum_alone[0] + sum_alone[1], sum_ss[0] + sum_ss[1]);
      EXPECT_TRUE(model->includes_single_scattering());
      EXPECT_FALSE(has_plus_ss);
    } else if (std::string(name) == "better-dipole") {
      // NAME+ss nearer overall and at g = 0.9: it omits single scattering.
      EXPECT_LT(sum_ss[0] + sum_ss[1], sum_alone[0] + sum_alone[1]);
      EXPECT_LT(sum_ss[1], sum_alone[1]);
      EXPECT_FALSE(model->includes_single_scattering());
      EXPECT_TRUE(has_plus_ss);
    } else {
      // Quantized: alone nearer at g = 0 (its label says so), NAME+ss nearer at g = 0.9.
      EXPECT_EQ(alone_nearer[0], 8);
      EXPECT_LT(sum_ss[1], sum_alone[1]);
      EXPECT_FALSE(model->includes_single_scattering());
      EXPECT_TRUE(has_plus_ss);
    }
  }
}
