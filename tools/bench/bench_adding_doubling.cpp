// Adding-doubling speed (medians), with the multipole's closed-form slab totals timed in the same
// run as the baseline: forward slabs at the default tolerance and at fixed angle counts, and the
// inversions (fit slab on adding-doubling, one .rxt row with 0 and 1 sphere).
//
//   bench_adding_doubling [repetitions=51]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/fit/rxt_fit.hpp"
#include "bssrdf/io/rxt.hpp"

using namespace bssrdf;

namespace {
template <class F>
double median_us(F&& f, int repetitions) {
  std::vector<double> t;
  for (int i = 0; i < repetitions; ++i) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(t.begin(), t.begin() + repetitions / 2, t.end());
  return t[repetitions / 2];
}
volatile double sink = 0;
}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 51;
  const double baseline = median_us([] { sink = slab_measurables(0.1, 2.0, 0.0, 1.4, 2.0).first; }, repetitions);
  std::printf("median of %d; baseline: multipole slab totals (closed form), %.2f us\n", repetitions, baseline);
  struct Case {
    const char* name;
    double n, g, b;
    bool slides;
    int points;
  };
  const Case cases[] = {
      {"n 1.0, g 0,   4 mfp, tolerance 1e-4", 1.0, 0.0, 4, false, 0},  {"n 1.4, g 0.9, 4 mfp, tolerance 1e-4", 1.4, 0.9, 4, false, 0},
      {"n 1.4, g 0.9, 4 mfp, slides, tol 1e-4", 1.4, 0.9, 4, true, 0}, {"n 1.4, g 0.9, semi-infinite, tol 1e-4", 1.4, 0.9, kSemiInfinite, false, 0},
      {"n 1.4, g 0.9, 4 mfp, 16 angles", 1.4, 0.9, 4, false, 16},     {"n 1.4, g 0.9, 4 mfp, 32 angles", 1.4, 0.9, 4, false, 32},
      {"n 1.4, g 0.9, 100 mfp, 32 angles", 1.4, 0.9, 100, false, 32},
  };
  std::printf("%-42s %10s %8s %s\n", "forward slab (alpha 0.99)", "us", "x base", "angles");
  for (const auto& c : cases) {
    adding_doubling::Slab slab;
    slab.layers = {{0.01, 0.99, c.g, c.b}};
    slab.n = c.n;
    if (c.slides) slab.above = slab.below = {{1.5, 1.0, 0.0}};
    adding_doubling::Options o;
    o.points = c.points;
    int points = 0;
    const double us = median_us([&] { points = adding_doubling::solve(slab, adding_doubling::Incidence::collimated, o).points; }, repetitions);
    std::printf("%-42s %10.1f %8.0f %d\n", c.name, us, us / baseline, points);
  }
  const int fits = std::max(3, repetitions / 5);
  const auto t = adding_doubling::solve({{{0.05, 2.0, 0.0, 2.0}}, 1.4, 1, 1, {}, {}}, adding_doubling::Incidence::collimated);
  const double fit_ad = median_us([&] {
    sink = fit_slab({{"x", t.diffuse_reflectance, t.total_transmittance, 1e-3, 1e-3, 0.0}}, 2.0, LengthUnit::millimetre, 1.4).iterations;
  }, fits);
  SlabFitOptions mp;
  mp.model = "multipole";
  const double fit_mp = median_us([&] {
    sink = fit_slab({{"x", t.diffuse_reflectance, t.total_transmittance, 1e-3, 1e-3, 0.0}}, 2.0, LengthUnit::millimetre, 1.4, mp).iterations;
  }, fits);
  std::printf("inverse, one wavelength (median of %d):\n  fit slab adding-doubling %.2f ms, multipole %.2f ms (x %.1f)\n", fits,
              fit_ad / 1000, fit_mp / 1000, fit_ad / fit_mp);
  for (int spheres : {0, 1}) {
    char text[512];
    std::snprintf(text, sizeof text, "IAD1\n1.4 1.5 1.0 1.0 5 0.98 %d\n203.2 25.4 12.7 1.0 0.96\n203.2 25.4 12.7 1.0 0.96\n2\n0.35 0.25\n",
                  spheres);
    const auto file = parse_rxt(text, "bench");
    const double us = median_us([&] { sink = fit_rxt(file).rows[0].mu_a; }, fits);
    std::printf("  .rxt row, %d sphere(s), slides: %.2f ms\n", spheres, us / 1000);
  }
}
