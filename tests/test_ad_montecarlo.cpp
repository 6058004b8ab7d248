// Adding-doubling against the project's Monte Carlo reference (an independent solver of the same
// transfer equation): short runs here, each total within 4 standard errors plus 1e-4 (the
// solver's stated accuracy). Longer runs over the whole parameter range:
// tools/validation/validate_adding_doubling (table in tools/validation/adding_doubling_vs_montecarlo.txt).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/montecarlo.hpp"

using namespace bssrdf;

namespace {

struct Case {
  const char* name;
  double albedo, g, n, optical_thickness;  // sigma_t = 1/mm
  bool slides;                             // 1 mm glass (n 1.5) above and below
  std::uint64_t photons;
};

LayerStack stack_of(const Case& c) {
  LayerStack s;
  s.channel_names = {"c0"};
  auto layer = [](double sigma_a, double sigma_s, double g, double n, double d) {
    Layer l;
    l.sigma_a = {sigma_a};
    l.sigma_s = {sigma_s};
    l.g = {g};
    l.n = n;
    l.thickness = d;
    return l;
  };
  if (c.slides) s.layers.push_back(layer(0, 0, 0, 1.5, 1.0));
  s.layers.push_back(layer(1 - c.albedo, c.albedo, c.g, c.n, c.optical_thickness));
  if (c.slides) s.layers.push_back(layer(0, 0, 0, 1.5, 1.0));
  return s;
}

void expect_within(const char* what, const Case& c, double ad, const Estimate& mc) {
  const double sigmas = (ad - mc.value) / std::max(mc.standard_error, 1e-300);
  std::printf("  %-34s %-26s AD %.5f  MC %.5f +- %.5f  (%+.1f sigma)\n", c.name, what, ad, mc.value, mc.standard_error,
              sigmas);
  EXPECT_LE(std::abs(ad - mc.value), 4 * mc.standard_error + 1e-4) << c.name << " " << what;
}

}  // namespace

TEST(AddingDoublingVsMonteCarlo, TotalsAgreeWithinFourSigma) {
  const Case cases[] = {
      {"0.1 mfp, a 0.9, g 0.9, n 1.4", 0.9, 0.9, 1.4, 0.1, false, 200000},
      {"1 mfp, a 0.99, g 0, n 1.0", 0.99, 0.0, 1.0, 1.0, false, 100000},
      {"2 mfp, a 0.9, g 0.99, n 1.33", 0.9, 0.99, 1.33, 2.0, false, 100000},
      {"4 mfp, a 0.5, g 0.5, n 1.6, slides", 0.5, 0.5, 1.6, 4.0, true, 100000},
      {"10 mfp, a 0.99, g 0.8, n 1.4, slides", 0.99, 0.8, 1.4, 10.0, true, 50000},
      {"semi-infinite, a 0.95, g 0.9, n 1.4", 0.95, 0.9, 1.4, kSemiInfinite, false, 50000},
  };
  for (const auto& c : cases) {
    const auto stack = stack_of(c);
    const auto ad = adding_doubling::solve(adding_doubling::slab_of(stack, 0), adding_doubling::Incidence::collimated);
    MonteCarloOptions options;
    options.photons = c.photons;
    options.seed = 11;
    options.bins = 4;
    const auto mc = run_monte_carlo(stack, options).channels[0];
    EXPECT_NEAR(ad.specular_reflectance, mc.specular_reflectance, 1e-12) << c.name;
    expect_within("diffuse_reflectance", c, ad.diffuse_reflectance, mc.diffuse_reflectance);
    expect_within("total_transmittance", c, ad.total_transmittance, mc.total_transmittance);
    expect_within("unscattered_transmittance", c, ad.unscattered_transmittance, mc.unscattered_transmittance);
  }
}
