// The pbrt-layout albedo-radius table (100 x 64, photon beam diffusion) against the Monte Carlo
// reference, for the tables bench_lut times: pbrt's construction (100 + 100 midpoint samples per
// cell, tools/bench/pbrt_style.hpp), ours at the default quadrature tolerance 1e-2 and at 1e-3, and
// the same layout filled with the converged model (1024-point Gauss-Legendre: what any quadrature
// converges to; the floor set by the model itself) -- these four with the model's own row energy
// (RowEnergy::model, pbrt's construction) -- and the default table, ours at 1e-2 with each row
// scaled to the radiative-transfer total (RowEnergy::transport: "rt"), and the rows from the exact
// model (RowShape::exact, `lut --kind albedo-radius --model exact`: "exact").
//
// For each (g, eta) and six stored albedo rows (nearest pbrt rows to 0.3, 0.6, 0.8, 0.9, 0.95,
// 0.99), the Monte Carlo reference (semi-infinite medium, sigma_t = 1 /mm so mm = mean free paths,
// true HG phase function, per entered flux, single scattering included as in the table) is tallied
// in log radial bins: [0, r_min) then geometric bins up to r_max, the radius where the row's own
// CDF reaches 0.999 (the radii holding the energy), r_min = r_max / 1000. Like with like: each
// table is read as a renderer reads it (Catmull-Rom along the row) and averaged over every bin
// exactly (2-point Gauss-Legendre between the table's nodes is exact for the cubic pieces); the
// Monte Carlo bin value is 2 pi r R averaged over the bin, R_bin pi (b^2 - a^2) / (b - a).
//   L2     - relative L2 error of the bin-averaged 2 pi r R over [0, r_max] (weight dr):
//            sqrt(sum (f - f_mc)^2 dr / sum f_mc^2 dr); "noise" is the Monte Carlo's own figure
//            (standard errors in place of the differences);
//   L2 ln  - the same with weight d(ln r) (the table's own geometric spacing; brings out the small
//            radii, where pbrt's midpoint rule errs most and the Monte Carlo bins are noisiest);
//            the first bin [0, r_min) is left out of it;
//   worst  - largest relative bin error among bins holding >= 1 % of the row's energy;
//   rho_eff - the row's effective albedo (its Catmull-Rom integral, as pbrt) against the Monte Carlo
//            total diffuse reflectance per entered flux, relative error.
//
//   validate_albedo_radius [photons=1000000] [bins=50]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "../bench/pbrt_style.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/lut/albedo_radius_table.hpp"
#include "bssrdf/lut/interpolation.hpp"
#include "bssrdf/models/photon_beam_diffusion.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/parallel.hpp"

using namespace bssrdf;

namespace {


struct Errors {
  double l2 = 0, l2_log = 0, worst = 0, rho_eff = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const std::size_t bins = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 50;
  const auto layout = AlbedoRadiusLayout::pbrt();
  const std::size_t cols = layout.radius.size();
  constexpr int kTables = 6;
  const char* names[kTables] = {"pbrt-style", "ours 1e-2", "ours 1e-3", "converged", "rt 1e-2", "exact"};
  std::printf(
      "pbrt-layout albedo-radius table (100 x 64, photon beam diffusion) against Monte Carlo, %llu photons per row, "
      "%zu log bins\n",
      static_cast<unsigned long long>(photons), bins);
  std::printf(
      "L2 and worst: bin-averaged 2 pi r R over the radii holding 99.9 %% of the row's energy; rho_eff: relative error "
      "of the row's effective albedo (%%)\n\n");
  std::printf(
      "g    eta  rho     r_max   MC rho_eff       noise |  L2 %%: pbrt ours-2 ours-3   conv     rt  exact | noise | "
      "L2 ln %%: pbrt ours-2 ours-3   conv     rt  exact | worst %%: pbrt ours-2 ours-3   conv     rt  exact | "
      "rho_eff %%: pbrt ours-2 ours-3   conv     rt  exact\n");
  std::vector<double> all[kTables], all_log[kTables], all_eff[kTables];
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& [g, eta] : {std::pair{0.0, 1.3}, std::pair{0.9, 1.3}, std::pair{0.0, 1.0}, std::pair{0.9, 1.0}}) {
    AlbedoRadiusOptions o2, o3, rt;
    o2.tolerance = 1e-2;
    o3.tolerance = 1e-3;
    o2.energy = o3.energy = RowEnergy::model;
    AlbedoRadiusTable tables[kTables];
    tables[4] = build_albedo_radius_table(layout, g, eta, rt);
    AlbedoRadiusOptions exact;
    exact.shape = RowShape::exact;
    tables[5] = build_albedo_radius_table(layout, g, eta, exact);
    tables[1] = build_albedo_radius_table(layout, g, eta, o2);
    tables[2] = build_albedo_radius_table(layout, g, eta, o3);
    tables[0] = tables[1];
    tables[3] = tables[1];
    const auto b = improved_boundary(eta);
    parallel_for(layout.albedo.size(), 0, [&](std::size_t i) {
      const auto m = reduced_unit_extinction(layout.albedo[i], g, eta);
      for (std::size_t j = 0; j < cols; ++j) {
        const double r = layout.radius[j];
        tables[0].profile[i * cols + j] = kTwoPi * r * bench::pbrt_style_pbd(m, b, r);
        tables[3].profile[i * cols + j] = r > 0 ? kTwoPi * r * photon_beam_diffusion::reflectance(m, b, r, 1024) : 0.0;
      }
    });
    for (auto* t : {&tables[0], &tables[3]})
      for (std::size_t i = 0; i < t->rows(); ++i)
        t->effective_albedo[i] =
            catmull_rom_integral(layout.radius, std::span(&t->profile[i * cols], cols), 0, layout.radius.back());

    for (double target : {0.3, 0.6, 0.8, 0.9, 0.95, 0.99}) {
      std::size_t row = 0;
      for (std::size_t i = 0; i < layout.albedo.size(); ++i)
        if (std::abs(layout.albedo[i] - target) < std::abs(layout.albedo[row] - target)) row = i;
      const double rho = layout.albedo[row];
      // r_max: where our row's CDF reaches 0.999.
      const std::span<const double> cdf(&tables[1].cdf[row * cols], cols);
      std::size_t k = 1;
      while (k + 1 < cols && cdf[k] < 0.999) ++k;
      const double r_max = layout.radius[k - 1] +
                           (layout.radius[k] - layout.radius[k - 1]) * (0.999 - cdf[k - 1]) / (cdf[k] - cdf[k - 1]);

      const auto medium = Medium::single_channel(1 - rho, rho, g, eta);
      MonteCarloOptions options;
      options.photons = photons;
      options.seed = 11;
      options.spacing = BinSpacing::log;
      options.r_max = r_max;
      options.r_min = r_max / 1000;
      options.bins = bins;
      const auto result = run_monte_carlo(LayerStack::half_space(medium), options);
      const auto mc = result.channels[0].per_entered_flux();

      std::vector<double> f_mc(bins), se_mc(bins), width(bins);
      double norm = 0, noise = 0, energy = 0, norm_log = 0, noise_log = 0;
      for (std::size_t n = 0; n < bins; ++n) {
        const double a = result.bin_inner[n], c = result.bin_outer[n];
        width[n] = c - a;
        const double area = std::numbers::pi * (c * c - a * a);
        f_mc[n] = mc.reflectance[n] * area / width[n];
        se_mc[n] = mc.reflectance_stderr[n] * area / width[n];
        norm += f_mc[n] * f_mc[n] * width[n];
        noise += se_mc[n] * se_mc[n] * width[n];
        energy += f_mc[n] * width[n];
        const double wl = n == 0 ? 0.0 : std::log(c / a);
        norm_log += f_mc[n] * f_mc[n] * wl;
        noise_log += se_mc[n] * se_mc[n] * wl;
      }
      Errors e[kTables];
      for (int t = 0; t < kTables; ++t) {
        const std::span<const double> f(&tables[t].profile[row * cols], cols);
        double sq = 0, sq_log = 0;
        for (std::size_t n = 0; n < bins; ++n) {
          const double v = catmull_rom_integral(layout.radius, f, result.bin_inner[n], result.bin_outer[n]) / width[n];
          sq += (v - f_mc[n]) * (v - f_mc[n]) * width[n];
          if (n > 0) sq_log += (v - f_mc[n]) * (v - f_mc[n]) * std::log(result.bin_outer[n] / result.bin_inner[n]);
          if (f_mc[n] * width[n] >= 0.01 * energy) e[t].worst = std::max(e[t].worst, std::abs(v / f_mc[n] - 1));
        }
        e[t].l2 = std::sqrt(sq / norm);
        e[t].l2_log = std::sqrt(sq_log / norm_log);
        all_log[t].push_back(e[t].l2_log);
        e[t].rho_eff = tables[t].effective_albedo[row] / mc.diffuse_reflectance.value - 1;
        all[t].push_back(e[t].l2);
        all_eff[t].push_back(std::abs(e[t].rho_eff));
      }
      std::printf("%-4.1f %-4.1f %-6.4f %7.2f  %.4f±%.4f %5.2f |     ", g, eta, rho, r_max,
                  mc.diffuse_reflectance.value, mc.diffuse_reflectance.standard_error, 100 * std::sqrt(noise / norm));
      for (int t = 0; t < kTables; ++t) std::printf(" %6.2f", 100 * e[t].l2);
      std::printf(" | %5.2f |      ", 100 * std::sqrt(noise_log / norm_log));
      for (int t = 0; t < kTables; ++t) std::printf(" %6.2f", 100 * e[t].l2_log);
      std::printf(" |     ");
      for (int t = 0; t < kTables; ++t) std::printf(" %6.2f", 100 * e[t].worst);
      std::printf(" |        ");
      for (int t = 0; t < kTables; ++t) std::printf(" %+6.2f", 100 * e[t].rho_eff);
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  std::printf("\nmedian over rows:\n");
  for (int t = 0; t < kTables; ++t)
    std::printf("  %-11s  L2 %6.2f %%   L2 ln %6.2f %%   |rho_eff err| %5.2f %%   max L2 %6.2f %%\n", names[t],
                100 * median(all[t]), 100 * median(all_log[t]), 100 * median(all_eff[t]),
                100 * *std::max_element(all[t].begin(), all[t].end()));
  // Paired comparison with pbrt-style (the same Monte Carlo run serves both tables of a row).
  const auto paired = [&](const char* what, const std::vector<double>* v, int t) {
    int better = 0;
    double worse_by = -1e300, better_by = -1e300;
    for (std::size_t k = 0; k < v[0].size(); ++k) {
      const double d = v[t][k] - v[0][k];
      if (d <= 0) ++better;
      worse_by = std::max(worse_by, d);
      better_by = std::max(better_by, -d);
    }
    std::printf(
        "  %-11s vs pbrt-style, %-12s  as good or better in %2d of %zu rows; at most %.2f pp worse, up to %.2f pp "
        "better\n",
        names[t], what, better, v[0].size(), 100 * worse_by, 100 * better_by);
  };
  for (int t = 1; t < kTables; ++t) {
    paired("L2", all, t);
    paired("L2 ln", all_log, t);
    paired("|rho_eff err|", all_eff, t);
  }
  std::printf("(%.0f s)\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return 0;
}
