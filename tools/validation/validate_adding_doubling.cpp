// Adding-doubling against the Monte Carlo reference over the range: slabs of 0.1 to 100
// mean free paths, single-scattering albedo 0.01 to 0.9999, eta 1 to 1.6, g 0 to 0.99, with and
// without 1 mm glass slides (n 1.5). Prints one line per case and the worst deviations, in
// absolute terms and in Monte Carlo standard errors. Output recorded in
// tools/validation/adding_doubling_vs_montecarlo.txt.
//
//   validate_adding_doubling [photons=200000]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/montecarlo.hpp"

using namespace bssrdf;

int main(int argc, char** argv) {
  const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 200000;
  struct Case {
    double b, albedo, n, g;
    bool slides;
  };
  const Case cases[] = {
      {0.1, 0.9, 1.4, 0.9, false},    {0.1, 0.01, 1.0, 0.0, false}, {0.1, 0.9999, 1.6, 0.99, true},
      {1, 0.5, 1.33, 0.5, false},     {1, 0.99, 1.0, 0.0, true},    {1, 0.9999, 1.4, 0.9, false},
      {2, 0.9, 1.33, 0.99, false},    {4, 0.5, 1.6, 0.5, true},     {4, 0.99, 1.4, 0.8, false},
      {10, 0.01, 1.4, 0.0, false},    {10, 0.99, 1.4, 0.8, true},   {10, 0.9999, 1.0, 0.0, false},
      {30, 0.95, 1.6, 0.9, false},    {100, 0.9, 1.0, 0.9, false},  {100, 0.99, 1.4, 0.0, true},
      {100, 0.999, 1.33, 0.9, false},
  };
  std::printf(
      "Adding-doubling (default tolerance 1e-4) vs Monte Carlo reference (%llu photons, seed 1), sigma_t = 1/mm\n",
      static_cast<unsigned long long>(photons));
  std::printf("%6s %7s %5s %5s %6s | %-8s %-8s %-8s %6s | %-8s %-8s %-8s %6s | %-8s %-8s %6s | N\n", "b", "albedo", "n",
              "g", "slides", "R AD", "R MC", "+-", "sigma", "T AD", "T MC", "+-", "sigma", "U AD", "U MC", "sigma");
  double worst_abs = 0, worst_sigma = 0;
  for (const auto& c : cases) {
    LayerStack stack;
    stack.channel_names = {"c0"};
    Layer glass;
    glass.n = 1.5;
    glass.thickness = 1;
    glass.sigma_a = glass.sigma_s = glass.g = {0.0};
    Layer medium;
    medium.n = c.n;
    medium.thickness = c.b;
    medium.sigma_a = {1 - c.albedo};
    medium.sigma_s = {c.albedo};
    medium.g = {c.g};
    if (c.slides) stack.layers.push_back(glass);
    stack.layers.push_back(medium);
    if (c.slides) stack.layers.push_back(glass);
    const auto ad = adding_doubling::solve(adding_doubling::slab_of(stack, 0), adding_doubling::Incidence::collimated);
    MonteCarloOptions options;
    options.photons = photons;
    options.bins = 2;
    const auto mc = run_monte_carlo(stack, options).channels[0];
    auto sigmas = [](double a, const Estimate& e) {
      return e.standard_error > 0 ? (a - e.value) / e.standard_error : 0.0;
    };
    const double sr = sigmas(ad.diffuse_reflectance, mc.diffuse_reflectance),
                 st = sigmas(ad.total_transmittance, mc.total_transmittance),
                 su = sigmas(ad.unscattered_transmittance, mc.unscattered_transmittance);
    std::printf("%6g %7g %5g %5g %6s | %.5f  %.5f  %.5f %+6.2f | %.5f  %.5f  %.5f %+6.2f | %.5f  %.5f  %+6.2f | %d\n",
                c.b, c.albedo, c.n, c.g, c.slides ? "yes" : "no", ad.diffuse_reflectance, mc.diffuse_reflectance.value,
                mc.diffuse_reflectance.standard_error, sr, ad.total_transmittance, mc.total_transmittance.value,
                mc.total_transmittance.standard_error, st, ad.unscattered_transmittance,
                mc.unscattered_transmittance.value, su, ad.points);
    std::fflush(stdout);
    worst_abs = std::max({worst_abs, std::abs(ad.diffuse_reflectance - mc.diffuse_reflectance.value),
                          std::abs(ad.total_transmittance - mc.total_transmittance.value),
                          std::abs(ad.unscattered_transmittance - mc.unscattered_transmittance.value)});
    worst_sigma = std::max({worst_sigma, std::abs(sr), std::abs(st), std::abs(su)});
  }
  std::printf("worst |AD - MC| = %.2e absolute, worst deviation %.2f standard errors (%zu cases x 3 quantities)\n",
              worst_abs, worst_sigma, std::size(cases));
}
