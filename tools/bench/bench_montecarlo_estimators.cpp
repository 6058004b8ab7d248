// Monte Carlo estimator settings compared by efficiency (figure of merit 1 / (variance x time)) on
// every output, so the defaults are chosen on all of them and not on R_d alone: R_d, T_t, the
// absorbed fraction, R(r) in bins out to 5 transport mean free paths (near: r < 1 ell, far:
// 3 to 5 ell) and the absorption by depth (top fifth and bottom half of the slab). Everything is
// relative to the first setting (MCML's roulette, 1e-4 / 0.1), measured in the same process,
// medians over repetitions with different seeds. One thread, so the times are comparable.
//
//   bench_montecarlo_estimators [repetitions=5] [photons=200000] [case=0] [absolute=0]
//   case 0: mua = 1/cm, mus = 100/cm, g = 0.9, n = 1, 100-mfp slab (the MCML speed case)
//   case 1: the same with n = 1.4;  case 2: mua = 1/cm, mus = 10/cm, g = 0, n = 1 semi-infinite
//   case 3: half-space albedo' = 0.99, eta = 1.3, g = 0 (the models' validation medium)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "bssrdf/montecarlo.hpp"

using namespace bssrdf;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

struct Setting {
  std::string label;
  AbsorptionEstimator estimator;
  double threshold, survival;
};

// Figures of merit 1/(se^2 t) of every output of one run (groups of bins: the median over bins).
struct Merits {
  double rd, t, absorbed, r_near, r_far, a_top, a_deep, seconds, interactions_per_photon, rd_value, rd_se;
};

// t: seconds of CPU time of the run (one thread): less disturbed than wall-clock time by other
// processes on a shared machine.
Merits merits(const MonteCarloResult& r, double ell, double t) {
  const auto& c = r.channels[0];
  const auto fom = [t](double se) { return se > 0 ? 1 / (se * se * t) : 0.0; };
  std::vector<double> near, far, top, deep;
  for (std::size_t i = 0; i < r.bin_radius.size(); ++i) {
    if (r.bin_outer[i] <= ell) near.push_back(fom(c.reflectance_stderr[i]));
    if (r.bin_inner[i] >= 3 * ell && r.bin_outer[i] <= 5 * ell * (1 + 1e-9))
      far.push_back(fom(c.reflectance_stderr[i]));
  }
  const std::size_t nz = r.depth_inner.size();
  for (std::size_t i = 0; i < nz; ++i) {
    if (i < nz / 5) top.push_back(fom(c.absorbed_by_depth_stderr[i]));
    if (i >= nz / 2) deep.push_back(fom(c.absorbed_by_depth_stderr[i]));
  }
  return {fom(c.diffuse_reflectance.standard_error),
          fom(c.total_transmittance.standard_error),
          fom(c.absorbed.standard_error),
          near.empty() ? 0 : median(near),
          far.empty() ? 0 : median(far),
          top.empty() ? 0 : median(top),
          deep.empty() ? 0 : median(deep),
          t,
          static_cast<double>(c.interactions) / static_cast<double>(r.options.photons),
          c.diffuse_reflectance.value,
          c.diffuse_reflectance.standard_error};
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const auto photons = static_cast<std::uint64_t>(argc > 2 ? std::atof(argv[2]) : 200000);
  const int which = argc > 3 ? std::atoi(argv[3]) : 0;
  // absolute = 1: print the figures of merit themselves (1/s), to compare builds across processes.
  const bool absolute = argc > 4 && std::atoi(argv[4]) != 0;

  struct Case {
    const char* name;
    double mua, mus, g, n, thickness;
  };
  const double a99 = 0.99;  // case 3: albedo' = 0.99, g = 0: sigma_t = 1/mm
  const Case cases[] = {
      {"mua=1 mus=100/cm g=0.9 n=1 100-mfp slab", 0.1, 10, 0.9, 1.0, 100 / 10.1},
      {"mua=1 mus=100/cm g=0.9 n=1.4 100-mfp slab", 0.1, 10, 0.9, 1.4, 100 / 10.1},
      {"mua=1 mus=10/cm g=0 n=1 semi-infinite", 0.1, 1, 0.0, 1.0, kSemiInfinite},
      {"albedo'=0.99 eta=1.3 g=0 half-space", 1 - a99, a99, 0.0, 1.3, kSemiInfinite},
  };
  const Case& c = cases[std::clamp(which, 0, 3)];
  const auto stack = LayerStack::slab(Medium::single_channel(c.mua, c.mus, c.g, c.n), c.thickness);
  const double ell = 1 / (c.mua + c.mus * (1 - c.g));

  const std::vector<Setting> settings = {
      {"implicit 1e-4/0.1 (MCML)", AbsorptionEstimator::implicit_capture, 1e-4, 0.1},
      {"implicit 1e-3/0.1", AbsorptionEstimator::implicit_capture, 1e-3, 0.1},
      {"implicit 1e-2/0.1", AbsorptionEstimator::implicit_capture, 1e-2, 0.1},
      {"implicit 0.05/0.2", AbsorptionEstimator::implicit_capture, 0.05, 0.2},
      {"implicit 0.1/0.5", AbsorptionEstimator::implicit_capture, 0.1, 0.5},
      {"implicit 0.2/0.5", AbsorptionEstimator::implicit_capture, 0.2, 0.5},
      {"implicit 0.3/0.5", AbsorptionEstimator::implicit_capture, 0.3, 0.5},
      {"implicit 0.5/0.5", AbsorptionEstimator::implicit_capture, 0.5, 0.5},
      {"implicit 0.02/0.5", AbsorptionEstimator::implicit_capture, 0.02, 0.5},
      {"implicit 0.05/0.5", AbsorptionEstimator::implicit_capture, 0.05, 0.5},
      {"implicit 0.1/0.3", AbsorptionEstimator::implicit_capture, 0.1, 0.3},
      {"implicit 0.3/0.3", AbsorptionEstimator::implicit_capture, 0.3, 0.3},
      {"analog", AbsorptionEstimator::analog, 0, 1},
  };

  std::printf("Estimator efficiency, %s; %llu photons x %d repetitions, 1 thread; medians.\n", c.name,
              static_cast<unsigned long long>(photons), repetitions);
  std::printf("Figures of merit 1/(se^2 t) relative to the first row (measured in this process, same seeds;\n");
  std::printf("t = CPU seconds of the one thread, photons/s per CPU second).\n");
  std::printf("R(r): linear bins of ell/10 to 5 ell (ell = %.3f mm); near r < ell, far 3-5 ell (median over bins).\n",
              ell);
  std::printf("Absorption by depth: 20 bins over %s; top = first 4 bins, deep = bottom half (median over bins).\n\n",
              c.thickness == kSemiInfinite ? "10 ell" : "the slab");
  std::printf("%-26s %9s %8s %8s %7s %7s %7s %7s %7s %7s %7s %8s\n", "setting", "photons/s", "int/ph", "R_d", "R_d",
              "T_t", "A", "R near", "R far", "A top", "A deep", "R_d se");
  std::vector<Merits> reference;
  for (const Setting& s : settings) {
    std::vector<Merits> runs;
    for (int k = 0; k < repetitions; ++k) {
      MonteCarloOptions o;
      o.photons = photons;
      o.seed = 100 + k;
      o.threads = 1;
      o.batch_size = 1024;
      o.absorption = s.estimator;
      o.roulette_threshold = s.threshold;
      o.roulette_survival = s.survival;
      o.r_max = 5 * ell;
      o.bins = 50;
      o.depth_bins = 20;
      const std::clock_t start = std::clock();
      const auto result = run_monte_carlo(stack, o);
      const double cpu = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
      runs.push_back(merits(result, ell, cpu));
    }
    if (reference.empty()) reference = runs;
    // Ratios per repetition (same seed index), then medians.
    const auto ratio = [&](double Merits::*field) {
      std::vector<double> v;
      for (int k = 0; k < repetitions; ++k) v.push_back(runs[k].*field / (absolute ? 1.0 : reference[k].*field));
      const double m = median(v);
      return std::isfinite(m) ? m : 0.0;  // 0: no such output (T_t of a half-space)
    };
    std::vector<double> rate, inter, rd, se;
    for (const auto& m : runs) {
      rate.push_back(static_cast<double>(photons) / m.seconds);
      inter.push_back(m.interactions_per_photon);
      rd.push_back(m.rd_value);
      se.push_back(m.rd_se);
    }
    std::printf(absolute ? "%-26s %9.0f %8.1f %8.5f %7.3g %7.3g %7.3g %7.3g %7.3g %7.3g %7.3g %8.6f\n"
                         : "%-26s %9.0f %8.1f %8.5f %7.2f %7.2f %7.2f %7.2f %7.2f %7.2f %7.2f %8.6f\n",
                s.label.c_str(), median(rate), median(inter), median(rd), ratio(&Merits::rd), ratio(&Merits::t),
                ratio(&Merits::absorbed), ratio(&Merits::r_near), ratio(&Merits::r_far), ratio(&Merits::a_top),
                ratio(&Merits::a_deep), median(se));
  }
  return 0;
}
