// Adding-doubling speed (medians), with the multipole's closed-form slab totals timed in the same
// run as the baseline: forward slabs at the default tolerance and at fixed angle counts, and the
// inversions (fit slab on adding-doubling, one .rxt row with 0 and 1 sphere). Each median is
// given in wall time and in the thread's CPU time: on a shared, loaded machine the wall time
// includes waiting for a core, the CPU time does not.
//
//   bench_adding_doubling [repetitions=51] [IAD_BINARY RXT_FILE]
// With Prahl's iad and an .rxt file: each row fitted by ours (in process) and by iad (its own
// process, `iad -M 0 [-q 32]`, process start included) in the same run, per row, at iad's default
// 8 angles (ours --quadrature 8) and at 32, with the ratio.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/fit/rxt_fit.hpp"
#include "bssrdf/io/rxt.hpp"

using namespace bssrdf;

namespace {
double thread_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e6 + t.tv_nsec * 1e-3;
}
struct Timing {
  double wall_us, cpu_us;  // medians
};
double median(std::vector<double> t) {
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}
template <class F>
Timing median_us(F&& f, int repetitions) {
  std::vector<double> wall, cpu;
  for (int i = 0; i < repetitions; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_us();
    f();
    cpu.push_back(thread_cpu_us() - cpu_start);
    wall.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count());
  }
  return {median(wall), median(cpu)};
}
volatile double sink = 0;
}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 51;
  // The baseline is timed over 1000 calls at a time: one call is shorter than reading the clocks.
  Timing baseline = median_us(
      [] {
        for (int k = 0; k < 1000; ++k) sink = slab_measurables(0.1, 2.0, 0.0, 1.4, 2.0).first;
      },
      repetitions);
  baseline.wall_us /= 1000;
  baseline.cpu_us /= 1000;
  std::printf("median of %d; baseline: multipole slab totals (closed form), wall %.2f us, cpu %.2f us\n", repetitions,
              baseline.wall_us, baseline.cpu_us);
  struct Case {
    const char* name;
    double n, g, b;
    bool slides;
    int points;
  };
  const Case cases[] = {
      // the 16-angle solve first: the others are also given as multiples of it
      {"n 1.4, g 0.9, 4 mfp, 16 angles", 1.4, 0.9, 4, false, 16},
      {"n 1.0, g 0,   4 mfp, tolerance 1e-4", 1.0, 0.0, 4, false, 0},
      {"n 1.4, g 0.9, 4 mfp, tolerance 1e-4", 1.4, 0.9, 4, false, 0},
      {"n 1.4, g 0.9, 4 mfp, slides, tol 1e-4", 1.4, 0.9, 4, true, 0},
      {"n 1.4, g 0.9, semi-infinite, tol 1e-4", 1.4, 0.9, kSemiInfinite, false, 0},
      {"n 1.4, g 0.9, 4 mfp, 32 angles", 1.4, 0.9, 4, false, 32},
      {"n 1.4, g 0.9, 100 mfp, 32 angles", 1.4, 0.9, 100, false, 32},
  };
  std::printf("%-42s %10s %10s %8s %8s %s\n", "forward slab (alpha 0.99)", "wall us", "cpu us", "x base", "x 16 ang",
              "angles");
  double sixteen_cpu = 0;
  for (const auto& c : cases) {
    adding_doubling::Slab slab;
    slab.layers = {{0.01, 0.99, c.g, c.b}};
    slab.n = c.n;
    if (c.slides) slab.above = slab.below = {{1.5, 1.0, 0.0}};
    adding_doubling::Options o;
    o.points = c.points;
    int points = 0;
    const Timing t = median_us(
        [&] { points = adding_doubling::solve(slab, adding_doubling::Incidence::collimated, o).points; }, repetitions);
    if (c.points == 16) sixteen_cpu = t.cpu_us;
    char versus_sixteen[16] = "";
    if (c.points != 16) std::snprintf(versus_sixteen, sizeof versus_sixteen, "%.1f", t.cpu_us / sixteen_cpu);
    std::printf("%-42s %10.1f %10.1f %8.0f %8s %d\n", c.name, t.wall_us, t.cpu_us, t.cpu_us / baseline.cpu_us,
                versus_sixteen, points);
  }
  const int fits = std::max(3, repetitions / 5);
  const auto t =
      adding_doubling::solve({{{0.05, 2.0, 0.0, 2.0}}, 1.4, 1, 1, {}, {}}, adding_doubling::Incidence::collimated);
  const Timing fit_ad = median_us(
      [&] {
        sink = fit_slab({{"x", t.diffuse_reflectance, t.total_transmittance, 1e-3, 1e-3, 0.0}}, 2.0,
                        LengthUnit::millimetre, 1.4)
                   .iterations;
      },
      fits);
  SlabFitOptions mp;
  mp.model = "multipole";
  const Timing fit_mp = median_us(
      [&] {
        sink = fit_slab({{"x", t.diffuse_reflectance, t.total_transmittance, 1e-3, 1e-3, 0.0}}, 2.0,
                        LengthUnit::millimetre, 1.4, mp)
                   .iterations;
      },
      fits);
  std::printf(
      "inverse, one wavelength (median of %d; wall / cpu):\n  fit slab adding-doubling %.2f / %.2f ms, multipole %.2f "
      "/ %.2f ms (x %.1f cpu)\n",
      fits, fit_ad.wall_us / 1000, fit_ad.cpu_us / 1000, fit_mp.wall_us / 1000, fit_mp.cpu_us / 1000,
      fit_ad.cpu_us / fit_mp.cpu_us);
  for (int spheres : {0, 1}) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "IAD1\n1.4 1.5 1.0 1.0 5 0.98 %d\n203.2 25.4 12.7 1.0 0.96\n203.2 25.4 12.7 1.0 0.96\n2\n0.35 0.25\n",
                  spheres);
    const auto file = parse_rxt(text, "bench");
    const Timing t = median_us([&] { sink = fit_rxt(file).rows[0].mu_a; }, fits);
    std::printf("  .rxt row, %d sphere(s), slides: %.2f / %.2f ms\n", spheres, t.wall_us / 1000, t.cpu_us / 1000);
  }
  if (argc < 4) return 0;
  const auto file = read_rxt(argv[3]);
  const double rows = static_cast<double>(file.rows.size());
  for (int points : {8, 32}) {
    RxtFitOptions options;
    options.quadrature = points;
    const Timing ours = median_us([&] { sink = fit_rxt(file, options).rows[0].mu_a; }, fits);
    const std::string command = std::string(argv[2]) + " -M 0" + (points == 32 ? " -q 32" : "") + " -o /dev/null '" +
                                argv[3] + "' > /dev/null 2>&1";
    // iad's CPU time (user + system of the child process) per run, beside its wall time: on a
    // loaded machine the wall time includes waiting for a core, the CPU time does not.
    std::vector<double> iad_cpu;
    const Timing iad = median_us(
        [&] {
          rusage before{}, after{};
          getrusage(RUSAGE_CHILDREN, &before);
          sink = std::system(command.c_str());
          getrusage(RUSAGE_CHILDREN, &after);
          auto us = [](const timeval& t) { return t.tv_sec * 1e6 + t.tv_usec; };
          iad_cpu.push_back(us(after.ru_utime) + us(after.ru_stime) - us(before.ru_utime) - us(before.ru_stime));
        },
        fits);
    const double iad_cpu_us = median(iad_cpu);
    std::printf(
        "  %s, %d angles, per row: wall ours %.3f ms, iad %.3f ms (process start included): iad/ours %.1f; cpu ours "
        "%.3f ms, iad %.3f ms: iad/ours %.1f\n",
        argv[3], points, ours.wall_us / rows / 1000, iad.wall_us / rows / 1000, iad.wall_us / ours.wall_us,
        ours.cpu_us / rows / 1000, iad_cpu_us / rows / 1000, iad_cpu_us / ours.cpu_us);
  }
}
