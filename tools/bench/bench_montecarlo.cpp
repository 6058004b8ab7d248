// Monte Carlo throughput: photons/s of run_monte_carlo on the published MCML speed cases
// (MCML 1.2.2, Wang, Jacques & Zheng 1995, timed on this machine kind), against a straightforward scalar implementation
// of the same physics run in this process: MCML 1.2.2's algorithm (one thread, double precision, analog
// Henyey-Greenstein sampling with trigonometry, implicit capture with weight roulette 1e-4/0.1,
// all-or-none Fresnel), with a 53-bit mt19937_64 generator. Medians over repetitions.
//
// Besides photons/s it prints efficiency ratios (1/(variance x time), the usual Monte Carlo figure
// of merit) of R_d and of R(r) out to 5 transport mean free paths, so estimators that trace
// cheaper but noisier photons are not flattered. Ours on 1 thread and on all hardware threads.
//
//   bench_montecarlo [repetitions=5] [scale=1] [case=all]
//   (scale multiplies the photon counts; case 0-3 runs only that case, 0 = the 100-mfp slab)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
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
  double mcml_photons_per_second;  // MCML 1.2.2 timed on this machine kind
};

// R(r) efficiency is compared on kProfileBins linear bins out to 5 transport mean free paths.
constexpr int kProfileBins = 50;

struct BaselineResult {
  double rd_mean, rd_variance_per_photon, seconds;
  std::vector<double> bin_variance_per_photon;  // R(r) bins (weights escaping at the top)
};

// MCML 1.2.2's photon loop, written plainly. Single layer, ambient index 1 on both sides.
BaselineResult mcml_baseline(const Case& c, std::uint64_t photons, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  const auto rand = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  const double mut = c.mua + c.mus, d = c.thickness_mm;
  const double rsp = std::pow((c.n - 1) / (c.n + 1), 2);
  const double ell = 1 / (c.mua + c.mus * (1 - c.g));
  std::vector<double> r_bins(kProfileBins, 0.0), r_sq(kProfileBins, 0.0), t_bins(kProfileBins, 0.0);
  const double dr = 5 * ell / kProfileBins;
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
        do xi = rand();
        while (xi <= 0);
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
            if (i < r_bins.size()) {
              r_bins[i] += w;
              r_sq[i] += w * w;
            }
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
        if (rand() <= 0.1)
          w /= 0.1;
        else
          alive = false;
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double n = static_cast<double>(photons), mean = sum / n;
  std::vector<double> bin_variance;
  for (int i = 0; i < kProfileBins; ++i) bin_variance.push_back(r_sq[i] / n - (r_bins[i] / n) * (r_bins[i] / n));
  return {mean, sum_sq / n - mean * mean, seconds, bin_variance};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

}  // namespace

// Cost of one unit of precision: variance per photon x seconds per photon (lower is better); the
// efficiency ratio is baseline cost / our cost.
struct Costs {
  double rd = 0;
  std::vector<double> bins;
};

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const double scale = argc > 2 ? std::atof(argv[2]) : 1.0;
  const int only = argc > 3 ? std::atoi(argv[3]) : -1;  // one case (0-3), or all
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const double inf = kSemiInfinite;
  const Case cases[] = {
      {"mua=1 mus=100/cm g=0.9 n=1 100-mfp slab", 0.1, 10, 0.9, 1.0, 100 / 10.1, 400000, 40000, 70000},
      {"same with n=1.4", 0.1, 10, 0.9, 1.4, 100 / 10.1, 300000, 30000, 43000},
      {"mua=1 mus=10/cm g=0 n=1 semi-infinite", 0.1, 1, 0.0, 1.0, inf, 2000000, 200000, 576000},
      {"MCML Table 6.1 slab", 1.0, 9, 0.75, 1.0, 0.2, 8000000, 1000000, 4100000},
  };
  const auto load = [] {
    std::FILE* f = std::fopen("/proc/loadavg", "r");
    char buffer[64] = "?";
    if (f) {
      if (!std::fgets(buffer, sizeof buffer, f)) buffer[0] = 0;
      std::fclose(f);
    }
    std::string s(buffer);
    return s.substr(0, s.find(' ', s.find(' ', s.find(' ') + 1) + 1));
  };
  std::string command;
  for (int i = 0; i < argc; ++i)
    command += std::string(i ? " " : "") +
               argv[i];  // not const char* + string&&: GCC 12 -Wrestrict false positive (bug 105329)
  const MonteCarloOptions defaults;
  std::printf("command: %s\n", command.c_str());
  std::printf("machine: %u hardware threads; load average (1, 5, 15 min) at start: %s\n", cores, load().c_str());
  std::printf("Medians of %d repetitions (each runs every row once, in turn), wall-clock time. 'baseline' = MCML's\n",
              repetitions);
  std::printf("algorithm in this process (1 thread).\n");
  std::printf(
      "'ours' = run_monte_carlo with its defaults (implicit capture, roulette %g/%g), 'ours mcml-rr' = the same\n",
      defaults.roulette_threshold, defaults.roulette_survival);
  std::printf(
      "with MCML's roulette (1e-4/0.1), 'analog' = analog absorption. Efficiency = ratio of 1/(variance x time)\n");
  std::printf(
      "(figure of merit) to the baseline's, of R_d and of R(r) in %d bins to 5 transport mfp (median over the bins\n",
      kProfileBins);
  std::printf("with r < 1 mfp, 'near', and 3-5 mfp, 'far').\n\n");
  std::printf("%-40s %-15s %12s %10s %8s %8s %8s %9s %9s\n", "case", "run", "photons/s", "x baseline", "x MCML",
              "eff R_d", "eff near", "eff far", "R_d");
  for (const Case& c : cases) {
    if (only >= 0 && &c != &cases[only % 4]) continue;
    const double ell = 1 / (c.mua + c.mus * (1 - c.g));
    struct Run {
      const char* label;
      AbsorptionEstimator estimator;
      double threshold, survival;
      unsigned threads;
    };
    const Run runs[] = {
        {"ours", AbsorptionEstimator::implicit_capture, defaults.roulette_threshold, defaults.roulette_survival, 1},
        {"ours", AbsorptionEstimator::implicit_capture, defaults.roulette_threshold, defaults.roulette_survival, cores},
        {"ours mcml-rr", AbsorptionEstimator::implicit_capture, 1e-4, 0.1, cores},
        {"analog", AbsorptionEstimator::analog, 0, 1, cores},
    };
    constexpr int kRuns = sizeof runs / sizeof runs[0];
    const auto stack = LayerStack::slab(Medium::single_channel(c.mua, c.mus, c.g, c.n), c.thickness_mm);

    // Repetition k runs the baseline and every configuration once, in turn, so a burst of load
    // from other processes hits one repetition of each rather than all repetitions of one.
    std::vector<double> base_rate, rate[kRuns];
    std::vector<Costs> base_costs, costs[kRuns];
    double base_rd = 0, rd[kRuns] = {};
    for (int k = 0; k < repetitions; ++k) {
      const auto photons = static_cast<std::uint64_t>(static_cast<double>(c.baseline_photons) * scale);
      const auto b = mcml_baseline(c, photons, 1000 + k);
      const double seconds_per_photon = b.seconds / static_cast<double>(photons);
      base_rate.push_back(1 / seconds_per_photon);
      Costs cost{b.rd_variance_per_photon * seconds_per_photon, {}};
      for (double v : b.bin_variance_per_photon) cost.bins.push_back(v * seconds_per_photon);
      base_costs.push_back(cost);
      base_rd = b.rd_mean;
      for (int j = 0; j < kRuns; ++j) {
        const Run& run = runs[j];
        MonteCarloOptions o;
        o.photons = static_cast<std::uint64_t>(static_cast<double>(c.photons) * scale * run.threads / cores);
        o.threads = run.threads;
        o.absorption = run.estimator;
        o.roulette_threshold = run.threshold;
        o.roulette_survival = run.survival;
        o.r_max = 5 * ell;
        o.bins = kProfileBins;
        o.seed = 1 + k;
        const auto r = run_monte_carlo(stack, o);
        const auto& ch = r.channels[0];
        const double n = static_cast<double>(o.photons), per_photon = r.seconds / n;
        rate[j].push_back(r.photons_per_second);
        // variance per photon = n se^2; per bin, the bin's R(r) stderr times its area.
        Costs ours{ch.diffuse_reflectance.standard_error * ch.diffuse_reflectance.standard_error * n * per_photon, {}};
        for (int i = 0; i < kProfileBins; ++i) {
          const double area = std::numbers::pi * (r.bin_outer[i] * r.bin_outer[i] - r.bin_inner[i] * r.bin_inner[i]);
          const double se = ch.reflectance_stderr[i] * area;
          ours.bins.push_back(se * se * n * per_photon);
        }
        costs[j].push_back(ours);
        rd[j] = ch.diffuse_reflectance.value;
      }
    }
    const double base = median(base_rate);
    // Median cost per output over the repetitions.
    const auto median_cost = [](const std::vector<Costs>& list, int bin) {
      std::vector<double> v;
      for (const auto& r : list) v.push_back(bin < 0 ? r.rd : r.bins[bin]);
      return median(v);
    };
    // Efficiency ratios: R_d, and the median over near / far bins of the per-bin ratios.
    const auto ratios = [&](const std::vector<Costs>& ours, double& eff_rd, double& near, double& far) {
      eff_rd = median_cost(base_costs, -1) / median_cost(ours, -1);
      std::vector<double> n, f;
      for (int i = 0; i < kProfileBins; ++i) {
        const double inner = 5 * ell * i / kProfileBins, outer = 5 * ell * (i + 1) / kProfileBins;
        const double ratio = median_cost(base_costs, i) / median_cost(ours, i);
        if (!std::isfinite(ratio) || ratio <= 0) continue;
        if (outer <= ell * (1 + 1e-9)) n.push_back(ratio);
        if (inner >= 3 * ell * (1 - 1e-9)) f.push_back(ratio);
      }
      near = n.empty() ? 0 : median(n);
      far = f.empty() ? 0 : median(f);
    };
    std::printf("%-40s %-15s %12.0f %10.2f %8.2f %8.2f %8.2f %9.2f %9.5f\n", c.name, "baseline/1t", base, 1.0,
                base / c.mcml_photons_per_second, 1.0, 1.0, 1.0, base_rd);
    for (int j = 0; j < kRuns; ++j) {
      const double ours = median(rate[j]);
      double eff_rd, eff_near, eff_far;
      ratios(costs[j], eff_rd, eff_near, eff_far);
      char name[40];
      std::snprintf(name, sizeof name, "%s/%ut", runs[j].label, runs[j].threads);
      std::printf("%-40s %-15s %12.0f %10.2f %8.2f %8.2f %8.2f %9.2f %9.5f\n", "", name, ours, ours / base,
                  ours / c.mcml_photons_per_second, eff_rd, eff_near, eff_far, rd[j]);
    }
    std::fflush(stdout);
  }
  std::printf("\nload average at end: %s\n", load().c_str());
  return 0;
}
