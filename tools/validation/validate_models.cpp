// Every profile model against the Monte Carlo reference on the grid of issue 5:
// alpha' in {0.5, 0.8, 0.9, 0.95, 0.99, 0.999} x eta in {1.0, 1.3, 1.4} x g in {0, 0.9}
// (semi-infinite, sigma_t = 1 /mm, true HG phase function in the Monte Carlo). For each model:
//   total  - relative error of the total reflectance (per entered flux, single scattering included
//            in the reference: models that omit it are measured as they would be used);
//   L2     - area-weighted L2 error of R(r) over the bins, relative to the reference's norm;
//   near   - the same over the bins inside one transport mean free path (r < ell);
//   far    - the same over the bins beyond it (r >= ell), where diffusion is meant to hold.
// (L2 is dominated by the near field, where R(r) is largest: near and far separate the two.)
// Model values are bin averages (from cumulative_reflectance), compared with the bin tallies.
// Also the single-scattering total against the Monte Carlo single-scattering tally.
//
//   validate_models [photons=200000] [out.tsv] [g list=0,0.9] [eta list=1,1.3,1.4] [alpha' list]
// models_vs_montecarlo.tsv is the default grid (issue 5's table); the table embedded for --model auto
// by embed_model_errors.py is `validate_models 2000000 models_vs_montecarlo_extended.tsv
// 0,0.9,0.95 1,1.3,1.4,1.5` (72 cases, about 7 minutes on 2 cores).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/reference_comparison.hpp"
#include "bssrdf/single_scattering.hpp"

using namespace bssrdf;

int main(int argc, char** argv) {
  const std::uint64_t photons = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 200000;
  const std::string tsv_path = argc > 2 ? argv[2] : "validation_models.tsv";
  const auto list = [](const char* text) {
    std::vector<double> v;
    for (char* end = nullptr; *text; text = *end ? end + 1 : end) v.push_back(std::strtod(text, &end));
    return v;
  };
  const auto gs = argc > 3 ? list(argv[3]) : std::vector<double>{0.0, 0.9};
  const auto etas = argc > 4 ? list(argv[4]) : std::vector<double>{1.0, 1.3, 1.4};
  const auto albedos = argc > 5 ? list(argv[5]) : std::vector<double>{0.5, 0.8, 0.9, 0.95, 0.99, 0.999};
  std::vector<std::string> models;  // every row of the model registry
  for (const auto& e : model_registry()) models.push_back(e.name);
  std::ofstream tsv(tsv_path);
  tsv << "albedo_prime\teta\tg\tmc_total\tmc_stderr\tmc_single\tmc_single_stderr\tss_exact\tmc_l2_noise";
  for (const auto& m : models) tsv << '\t' << m << "_total\t" << m << "_l2\t" << m << "_near\t" << m << "_far";
  tsv << '\n';
  std::printf("%-6s %-4s %-4s %-16s %-9s", "alpha'", "eta", "g", "MC total", "SS dev/σ");
  for (const auto& m : models) std::printf(" %16.16s", m.c_str());
  std::printf("\n%47s", "");
  for (std::size_t i = 0; i < models.size(); ++i) std::printf(" %16s", "tot/near/far %");
  std::printf("\n");

  for (double g : gs)
    for (double eta : etas)
      for (double ap : albedos) {
        const double albedo = albedo_from_reduced(ap, g);
        const auto medium = Medium::single_channel(1 - albedo, albedo, g, eta);
        const auto m = medium.reduced(0);
        MonteCarloOptions options;
        options.photons = photons;
        options.seed = 7;
        options.spacing = BinSpacing::log;
        options.r_min = 0.01 * m.ell;
        options.r_max = 30 * m.ell;
        options.bins = 70;
        const auto start = std::chrono::steady_clock::now();
        const auto result = run_monte_carlo(LayerStack::half_space(medium), options);
        const auto mc = result.channels[0].per_entered_flux();
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double ss_exact = single_scattering_total(albedo, g, eta);
        const double ss_dev = (mc.single_scattering_reflectance.value - ss_exact) /
                              std::max(mc.single_scattering_reflectance.standard_error, 1e-300);
        std::printf("%-6.3f %-4.2f %-4.2f %.4f±%.4f %+8.1f ", ap, eta, g, mc.diffuse_reflectance.value,
                    mc.diffuse_reflectance.standard_error, ss_dev);
        tsv << ap << '\t' << eta << '\t' << g << '\t' << mc.diffuse_reflectance.value << '\t'
            << mc.diffuse_reflectance.standard_error << '\t' << mc.single_scattering_reflectance.value << '\t'
            << mc.single_scattering_reflectance.standard_error << '\t' << ss_exact;
        std::vector<ProfileDeviation> deviations;
        for (const auto& name : models) deviations.push_back(compare_with_monte_carlo(*make_model(name), m, result));
        tsv << '\t' << deviations[0].l2_noise;  // the run's own: the same for every model
        for (const auto& d : deviations) {
          std::printf(" %+5.1f/%4.1f/%5.1f", 100 * d.total, 100 * d.near, 100 * d.far);
          tsv << '\t' << d.total << '\t' << d.l2 << '\t' << d.near << '\t' << d.far;
        }
        std::printf("   (%.1f s)\n", seconds);
        std::fflush(stdout);
        tsv << '\n';
        tsv.flush();
      }
  return 0;
}
