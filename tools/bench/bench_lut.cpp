// Lookup-table construction speed. The headline: pbrt-v3's 100 x 64 photon-beam-diffusion
// albedo-radius table built the pbrt way (100 + 100 midpoint samples per evaluation, rows in
// parallel) against ours with the same layout, in the same process, with both tables' accuracy
// against a converged evaluation of the same model (1024-point Gauss-Legendre); then a radial
// table per material and the whole database. Accuracy against the Monte Carlo reference, the
// issue's criterion, is measured by tools/validation/validate_albedo_radius (recorded in
// tools/validation/albedo_radius_vs_montecarlo.txt) and quoted in the conclusion line. "ours" is
// built with RowEnergy::model (pbrt's construction) to compare like with like; the default table
// and the exact rows are timed after it.
//
//   bench_lut [repetitions=9]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <thread>
#include <vector>

#include "bssrdf/lut/albedo_radius_table.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/photon_beam_diffusion.hpp"
#include "bssrdf/parallel.hpp"
#include "pbrt_style.hpp"

using namespace bssrdf;

namespace {

// pbrt's ComputeBeamDiffusionBSSRDF: sigma_t = 1, rho = sigma_s; profile 2 pi r (MS + SS).
std::vector<double> pbrt_style_table(const AlbedoRadiusLayout& layout, double g, double eta, unsigned threads) {
  const std::size_t rows = layout.albedo.size(), cols = layout.radius.size();
  std::vector<double> profile(rows * cols);
  const auto b = improved_boundary(eta);
  parallel_for(rows, threads, [&](std::size_t i) {
    const auto m = reduced_unit_extinction(layout.albedo[i], g, eta);
    for (std::size_t j = 0; j < cols; ++j)
      profile[i * cols + j] = 2 * std::numbers::pi * layout.radius[j] * bench::pbrt_style_pbd(m, b, layout.radius[j]);
  });
  return profile;
}

template <class F>
double median_ms(F&& f, int repetitions) {
  std::vector<double> t;
  for (int k = 0; k < repetitions; ++k) {
    const auto start = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(t.begin(), t.begin() + repetitions / 2, t.end());
  return t[repetitions / 2];
}

// Worst and median relative error over cells holding at least 1e-3 of their row's peak (r > 0).
std::pair<double, double> errors(const std::vector<double>& table, const std::vector<double>& reference,
                                 std::size_t cols) {
  std::vector<double> e;
  for (std::size_t i = 0; i < table.size() / cols; ++i) {
    double peak = 0;
    for (std::size_t j = 0; j < cols; ++j) peak = std::max(peak, reference[i * cols + j]);
    for (std::size_t j = 1; j < cols; ++j)
      if (reference[i * cols + j] > 1e-3 * peak)
        e.push_back(std::abs(table[i * cols + j] / reference[i * cols + j] - 1));
  }
  std::sort(e.begin(), e.end());
  return {e.back(), e[e.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 9;
  const auto layout = AlbedoRadiusLayout::pbrt();
  const std::size_t cols = layout.radius.size();
  std::printf(
      "pbrt-layout albedo-radius table (100 x 64, photon beam diffusion), median of %d builds, %u hardware threads\n",
      repetitions, std::thread::hardware_concurrency());
  std::printf(
      "  case (g, eta)   builder                         threads   ms      worst err   median err   speed-up vs pbrt 1 "
      "thread\n");
  double pbrt_ms[2][2] = {}, ours_ms[2][2] = {};  // [case][threads - 1], ours at the default tolerance
  int case_index = 0;
  for (const auto& [g, eta] : {std::pair{0.0, 1.3}, std::pair{0.9, 1.4}}) {
    // Reference: the same model converged (the table's own physics, quadrature error ~1e-10).
    std::vector<double> reference(layout.albedo.size() * cols);
    {
      const auto b = improved_boundary(eta);
      parallel_for(layout.albedo.size(), 0, [&](std::size_t i) {
        const auto m = reduced_unit_extinction(layout.albedo[i], g, eta);
        for (std::size_t j = 0; j < cols; ++j)
          reference[i * cols + j] = layout.radius[j] > 0
                                        ? 2 * std::numbers::pi * layout.radius[j] *
                                              photon_beam_diffusion::reflectance(m, b, layout.radius[j], 1024)
                                        : 0.0;
      });
    }
    std::vector<double> pbrt;
    double pbrt_1 = 0;
    for (unsigned threads : {1u, 2u}) {
      const double ms = median_ms([&] { pbrt = pbrt_style_table(layout, g, eta, threads); }, repetitions);
      if (threads == 1) pbrt_1 = ms;
      pbrt_ms[case_index][threads - 1] = ms;
      const auto [worst, median] = errors(pbrt, reference, cols);
      std::printf("  g %.1f eta %.1f  pbrt-style (100+100 midpoint)     %u     %7.2f   %9.2e   %9.2e    %6.1fx\n", g,
                  eta, threads, ms, worst, median, pbrt_1 / ms);
    }
    for (double tolerance : {1e-3, 1e-2})
      for (unsigned threads : {1u, 2u}) {
        AlbedoRadiusOptions options;
        options.tolerance = tolerance;
        options.threads = threads;
        options.energy = RowEnergy::model;  // pbrt's construction: the same cells as pbrt-style's
        AlbedoRadiusTable t;
        const double ms = median_ms([&] { t = build_albedo_radius_table(layout, g, eta, options); }, repetitions);
        const auto [worst, median] = errors(t.profile, reference, cols);
        if (tolerance == AlbedoRadiusOptions{}.tolerance) ours_ms[case_index][threads - 1] = ms;
        std::printf("  g %.1f eta %.1f  ours, tolerance %.0e (GL %3d)      %u     %7.2f   %9.2e   %9.2e    %6.1fx\n", g,
                    eta, tolerance, t.quadrature_order, threads, ms, worst, median, pbrt_1 / ms);
      }
    // The default table (multiple scattering scaled to the radiative-transfer total) and the exact
    // model's rows: what the energy and the shape cost on top (their errors against pbd are by design).
    for (const auto& [name, shape] : {std::pair{"ours, transport energy (default)", RowShape::pbd},
                                      std::pair{"ours, exact rows (--model exact)", RowShape::exact}}) {
      AlbedoRadiusOptions options;
      options.threads = 1;
      options.shape = shape;
      AlbedoRadiusTable t;
      const double ms = median_ms([&] { t = build_albedo_radius_table(layout, g, eta, options); }, repetitions);
      std::printf("  g %.1f eta %.1f  %-32s  1     %7.2f   %9s   %9s    %6.1fx\n", g, eta, name, ms, "-", "-",
                  pbrt_1 / ms);
    }
    ++case_index;
  }
  // Figures from tools/validation/albedo_radius_vs_montecarlo.txt (validate_albedo_radius 10000000 50:
  // 24 rows, g 0 and 0.9, eta 1.0 and 1.3, rho 0.28-0.99; the tables are deterministic, so these
  // hold for every run of this benchmark).
  std::printf(
      "\nAccuracy against the Monte Carlo reference (tools/validation/albedo_radius_vs_montecarlo.txt, 24 rows, 10M "
      "photons each),\n"
      "medians over rows, pbrt-style vs ours at the default tolerance: L2 of 2 pi r R 13.16 %% vs 13.21 %%, L2 in ln r "
      "8.25 %% vs 8.25 %%,\n"
      "|rho_eff error| 13.94 %% vs 13.81 %%; at g 0, eta 1.3 ours is closer in all 6 rows (L2 by 0.09-1.84 pp), "
      "elsewhere pbrt-style is\n"
      "closer in some rows (g 0.9; eta 1.0) by at most 0.10 pp (L2), 0.39 pp (L2 ln), 0.21 pp (rho_eff) - closer than "
      "the converged model too, so\n"
      "no tolerance of ours can gain it: the model's own error (L2 5.8-35 %%) dominates. (The Monte Carlo rows are at "
      "eta 1.0 and 1.3.)\n");
  std::printf(
      "Conclusion: equal accuracy against Monte Carlo (better at g 0, eta 1.3); ours at the default tolerance builds "
      "the 100 x 64 table\n"
      "%.1fx faster on one thread and %.1fx on two at g 0, eta 1.3 (%.1fx / %.1fx at g 0.9, eta 1.4): the 10x goal is "
      "%s.\n",
      pbrt_ms[0][0] / ours_ms[0][0], pbrt_ms[0][1] / ours_ms[0][1], pbrt_ms[1][0] / ours_ms[1][0],
      pbrt_ms[1][1] / ours_ms[1][1],
      std::min({pbrt_ms[0][0] / ours_ms[0][0], pbrt_ms[1][0] / ours_ms[1][0]}) >= 10 ? "met" : "NOT met in this run");

  const auto db = MaterialDatabase::load(default_materials_dir());
  std::printf("\nRadial tables (tolerance 1e-3, energy 0.999, Catmull-Rom), one thread, median of %d\n", repetitions);
  std::printf("  material      model            radii   ms\n");
  double all_ms = 0;
  for (const char* model_name : {"pbd", "better-dipole", "burley"}) {
    const auto model = make_model(model_name);
    for (const auto& material : db.all()) {
      RadialTable t;
      const double ms = median_ms([&] { t = build_radial_table(material.medium, *model, {}); }, repetitions);
      if (std::string(model_name) == "pbd") all_ms += ms;
      if (material.name == "Skin1" || material.name == "Marble" || material.name == "Ketchup" ||
          std::string(model_name) == "pbd")
        std::printf("  %-12s  %-15s  %5zu  %6.2f\n", material.name.c_str(), model_name, t.size(), ms);
    }
  }
  std::printf("  whole database, pbd: %.1f ms\n", all_ms);
  return 0;
}
