// Monte Carlo throughput: photons/s of run_monte_carlo on the published MCML speed cases
// (reference/published_values.md), against a straightforward scalar implementation of the same
// physics run in this process: MCML 1.2.2's algorithm (one thread, double precision, analog
// Henyey-Greenstein sampling with trigonometry, implicit capture with weight roulette 1e-4/0.1,
// all-or-none Fresnel), with a 53-bit mt19937_64 generator. Medians over repetitions.
//
// Besides photons/s it prints the efficiency ratio (1/(variance x time) of R_d, the usual Monte
// Carlo figure of merit), so estimators that trace cheaper but noisier photons are not flattered.
//
//   bench_montecarlo [repetitions=5] [scale=1]      (scale multiplies the photon counts)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/montecarlo.hpp"

using namespace bssrdf;

namespace {

struct Case {
  const char* name;
  double mua, mus, g, n, thickness_mm;  // 1/mm, mm (infinite: semi-infinite)
  std::uint64_t photons;                // per repetition, ours
  std::uint64_t baseline_photons;
  double mcml_photons_per_second;       // published_values.md
};

struct BaselineResult {
  double rd_mean, rd_variance_per_photon, seconds;
};

// MCML 1.2.2's photon loop, written plainly. Single layer, ambient index 1 on both sides.
BaselineResult mcml_baseline(const Case& c, std::uint64_t photons, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  const auto rand = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  const double mut = c.mua + c.mus, d = c.thickness_mm;
  const double rsp = std::pow((c.n - 1) / (c.n + 1), 2);
  std::vector<double> r_bins(100, 0.0), t_bins(100, 0.0);
  const double dr = 0.01;
  double sum = 0, sum_sq = 0;
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t p = 0; p < photons; ++p) {
    double x = 0, y = 0, z = 0, ux = 0, uy = 0, uz = 1, w = 1 - rsp, s_left = 0;
    bool alive = true;
    while (alive) {
      // StepSizeInTissue
      double s;
      if (s_left == 0) {
        double xi;
        do xi = rand(); while (xi <= 0);
        s = -std::log(xi) / mut;
      } else {
        s = s_left / mut;
        s_left = 0;
      }
      // HitBoundary
      double db = 1e300;
      if (uz > 0) db = (d - z) / uz;
      if (uz < 0) db = -z / uz;
      if (s > db) {
        s_left = (s - db) * mut;
        s = db;
        x += s * ux;
        y += s * uy;
        z += s * uz;
        // CrossOrNot
        const double r = c.n == 1 ? 0.0 : fresnel_reflectance(std::abs(uz), c.n);
        if (rand() > r) {
          const double radius = std::sqrt(x * x + y * y);
          const auto i = static_cast<std::size_t>(radius / dr);
          if (uz < 0) {
            sum += w;
            sum_sq += w * w;
            if (i < r_bins.size()) r_bins[i] += w;
          } else if (i < t_bins.size()) {
            t_bins[i] += w;
          }
          alive = false;
        } else {
          uz = -uz;
        }
        continue;
      }
      x += s * ux;
      y += s * uy;
      z += s * uz;
      // Drop
      w -= w * c.mua / mut;
      // Spin: HG with trigonometry for the azimuth
      double cost;
      if (c.g == 0) {
        cost = 2 * rand() - 1;
      } else {
        const double t = (1 - c.g * c.g) / (1 - c.g + 2 * c.g * rand());
        cost = (1 + c.g * c.g - t * t) / (2 * c.g);
        cost = std::clamp(cost, -1.0, 1.0);
      }
      const double sint = std::sqrt(1 - cost * cost);
      const double psi = 2 * std::numbers::pi * rand();
      const double cosp = std::cos(psi), sinp = std::sin(psi);
      if (std::abs(uz) > 1 - 1e-12) {
        ux = sint * cosp;
        uy = sint * sinp;
        uz = cost * (uz > 0 ? 1 : -1);
      } else {
        const double temp = std::sqrt(1 - uz * uz);
        const double nux = sint * (ux * uz * cosp - uy * sinp) / temp + ux * cost;
        const double nuy = sint * (uy * uz * cosp + ux * sinp) / temp + uy * cost;
        uz = -sint * cosp * temp + uz * cost;
        ux = nux;
        uy = nuy;
      }
      // Roulette
      if (w < 1e-4) {
        if (rand() <= 0.1) w /= 0.1;
        else alive = false;
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double n = static_cast<double>(photons), mean = sum / n;
  return {mean, sum_sq / n - mean * mean, seconds};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const double scale = argc > 2 ? std::atof(argv[2]) : 1.0;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const double inf = kSemiInfinite;
  const Case cases[] = {
      {"mua=1 mus=100/cm g=0.9 n=1 100-mfp slab", 0.1, 10, 0.9, 1.0, 100 / 10.1, 200000, 40000, 70000},
      {"same with n=1.4", 0.1, 10, 0.9, 1.4, 100 / 10.1, 150000, 30000, 43000},
      {"mua=1 mus=10/cm g=0 n=1 semi-infinite", 0.1, 1, 0.0, 1.0, inf, 1000000, 200000, 576000},
      {"MCML Table 6.1 slab", 1.0, 9, 0.75, 1.0, 0.2, 4000000, 1000000, 4100000},
  };
  std::printf("Monte Carlo throughput, medians of %d repetitions; ours on %u threads (all cores) and on 1 thread.\n",
              repetitions, cores);
  std::printf("'baseline' = MCML's algorithm in this process (1 thread). 'efficiency' = ratio of 1/(var(R_d) x time).\n\n");
  std::printf("%-42s %-9s %12s %10s %10s %11s %11s\n", "case", "estimator", "photons/s", "x baseline", "x MCML", "efficiency",
              "R_d");
  for (const Case& c : cases) {
    std::vector<double> base_rate, base_cost;
    double base_rd = 0;
    for (int k = 0; k < repetitions; ++k) {
      const auto photons = static_cast<std::uint64_t>(static_cast<double>(c.baseline_photons) * scale);
      const auto b = mcml_baseline(c, photons, 1000 + k);
      base_rate.push_back(static_cast<double>(photons) / b.seconds);
      base_cost.push_back(b.rd_variance_per_photon * b.seconds / static_cast<double>(photons));
      base_rd = b.rd_mean;
    }
    const double base = median(base_rate), base_fom_cost = median(base_cost);
    std::printf("%-42s %-9s %12.0f %10.2f %10.2f %11.2f %11.5f\n", c.name, "baseline", base, 1.0,
                base / c.mcml_photons_per_second, 1.0, base_rd);
    for (const auto& [label, estimator, threads] :
         {std::tuple{"implicit", AbsorptionEstimator::implicit_capture, 0u},
          std::tuple{"implicit", AbsorptionEstimator::implicit_capture, 1u},
          std::tuple{"analog", AbsorptionEstimator::analog, 0u}}) {
      LayerStack stack;
      stack.channel_names = {"c0"};
      Layer layer;
      layer.sigma_a = {c.mua};
      layer.sigma_s = {c.mus};
      layer.g = {c.g};
      layer.n = c.n;
      layer.thickness = c.thickness_mm;
      stack.layers.push_back(layer);
      MonteCarloOptions o;
      o.photons = static_cast<std::uint64_t>(static_cast<double>(c.photons) * scale / (threads == 1 ? cores : 1));
      o.threads = threads;
      o.absorption = estimator;
      o.r_max = 1.0;
      std::vector<double> rate, cost;
      double rd = 0;
      for (int k = 0; k < repetitions; ++k) {
        o.seed = 1 + k;
        const auto r = run_monte_carlo(stack, o);
        const auto& e = r.channels[0].diffuse_reflectance;
        rate.push_back(r.photons_per_second);
        // variance per photon x seconds per photon
        cost.push_back(e.standard_error * e.standard_error * static_cast<double>(o.photons) * r.seconds /
                       static_cast<double>(o.photons));
        rd = e.value;
      }
      const double ours = median(rate);
      char name[32];
      std::snprintf(name, sizeof name, "%s/%ut", label, threads == 0 ? cores : threads);
      std::printf("%-42s %-9s %12.0f %10.2f %10.2f %11.2f %11.5f\n", "", name, ours, ours / base,
                  ours / c.mcml_photons_per_second, base_fom_cost / median(cost), rd);
    }
  }
  return 0;
}
