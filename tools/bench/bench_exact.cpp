// The exact model's speed goals (issue 12 §4), each against a baseline measured in the same run:
//   one R(r) evaluation      <= 100 ns   (baseline: pbd, the best analytic model)
//   one profile build        (ExactProfile at new coefficients; exact's per-medium cost)
//   one profile build below the first albedo node   <= 10 us   (baseline: the per-radius single-scattering path)
//   a radial LUT, Skin1      <= 2 ms     (baseline: the same LUT through pbd)
//   a 3-channel profile fit  <= 20 ms    (baseline: the same fit through pbd)
//   1000 albedo inversions   <= 5 ms     (baseline: pbd's inversion, 100 of the values x 10)
//   choose_model(Skin1, 0.1) <= 200 ms   (`--model auto`: every candidate measured live against
//                                         exact; baseline: exact's radial LUT of Skin1)
// Medians over `repetitions` runs.
//
//   bench_exact [repetitions=7]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "bssrdf/fit/profile_fit.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/profile.hpp"
#include "median_timing.hpp"

using namespace bssrdf;
using bssrdf::bench::median_ns_per_call;

namespace {

volatile double sink;

// Median wall time of f() in ms over `repetitions` runs.
double median_ms(const std::function<double()>& f, int repetitions) {
  std::vector<double> t;
  for (int k = 0; k < repetitions; ++k) {
    const auto start = std::chrono::steady_clock::now();
    sink = f();
    t.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(t.begin(), t.begin() + repetitions / 2, t.end());
  return t[repetitions / 2];
}

void row(const char* what, double exact, double baseline, const char* unit, double goal) {
  std::printf("  %-28s exact %10.3f %s   pbd %10.3f %s   exact/pbd %6.3f   goal <= %g %s: %s\n", what, exact, unit,
              baseline, unit, exact / baseline, goal, unit, exact <= goal ? "met" : "MISSED");
}

MeasuredProfile three_channel_profile(const Model& model, const Medium& medium) {
  MeasuredProfile data;
  data.radius = log_spaced(0.01, 20.0, 40);
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    MeasuredProfile::Channel ch{medium.channel_names[c], {}, {}};
    for (double r : data.radius) ch.value.push_back(model.reflectance(medium.reduced(c), r));
    data.channels.push_back(ch);
  }
  return data;
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  const auto exact = make_model("exact"), pbd = make_model("pbd");
  const auto skin = MaterialDatabase::load(default_materials_dir()).find("Skin1").medium;
  std::printf("Exact model speed, medians of %d runs; baseline pbd in the same run\n", repetitions);

  // One evaluation: alpha' 0.9, g 0, eta 1.3, 64 radii in [0.01, 20] ell (as bench_models).
  std::vector<double> radii;
  for (int i = 0; i < 64; ++i) radii.push_back(0.01 * std::pow(2000.0, i / 63.0));
  const auto m = reduce(0.1, 0.9, 0.0, 1.3);
  exact->reflectance(m, 1.0);
  pbd->reflectance(m, 1.0);
  row("one R(r) evaluation", median_ns_per_call([&](double r) { return exact->reflectance(m, r); }, radii, repetitions),
      median_ns_per_call([&](double r) { return pbd->reflectance(m, r); }, radii, repetitions), "ns", 100);

  // One profile build at new coefficients (each a different alpha').
  const ExactTable& table = bundled_exact_table();
  const double build_ms = median_ms(
      [&] {
        double s = 0;
        for (int k = 0; k < 1000; ++k) s += ExactProfile(table, 0.5 + 0.0004 * k, 0.3, 1.35).total();
        return s;
      },
      repetitions);
  std::printf("  %-28s exact %10.3f us   (1000 builds at distinct alpha', per build)\n", "one profile build", build_ms);
  // Below the table's first albedo node the build integrates the node's single scattering at every
  // radius: at all radii at once (log_grid) against 96-point Gauss-Legendre at each radius
  // (per_radius, the previous path), alternated in one loop; each build at its own alpha' below the
  // first node (8.9e-5 since the version-7 nodes; 0.001 before), g in [0.9, 0.999) and eta in [1, 2)
  // (no per-medium cache can help).
  const auto low_albedo = [&](SingleScatteringRadii how, int builds) {
    double s = 0;
    for (int k = 0; k < builds; ++k) {
      const double u = (k + 0.5) / builds;
      s += ExactProfile(table, table.albedo_prime.front() * (0.1 + 0.8 * u), 0.9 + 0.099 * u, 1 + u, how).total();
    }
    return s;
  };
  std::vector<double> log_grid_us, per_radius_us;
  for (int rep = 0; rep < repetitions; ++rep) {
    log_grid_us.push_back(1e3 * median_ms([&] { return low_albedo(SingleScatteringRadii::log_grid, 1000); }, 1));
    per_radius_us.push_back(1e3 * median_ms([&] { return low_albedo(SingleScatteringRadii::per_radius, 20); }, 1) / 20);
  }
  std::nth_element(log_grid_us.begin(), log_grid_us.begin() + repetitions / 2, log_grid_us.end());
  std::nth_element(per_radius_us.begin(), per_radius_us.begin() + repetitions / 2, per_radius_us.end());
  const double low_us = log_grid_us[repetitions / 2] / 1000, low_before_us = per_radius_us[repetitions / 2];
  std::printf("  %-28s exact %10.3f us   per-radius %10.3f us   ratio %6.3f   goal <= 10 us: %s\n",
              "one profile build, low alpha'", low_us, low_before_us, low_us / low_before_us,
              low_us <= 10 ? "met" : "MISSED");
  // The continued parts of the domain: above the last albedo node (the dipole ratio at every radius),
  // beyond the last g node (four g rows), and an eta between the last two nodes.
  const auto per_build_us = [&](auto make) {
    return median_ms(
        [&] {
          double s = 0;
          for (int k = 0; k < 1000; ++k) s += make(k).total();
          return s;
        },
        repetitions);
  };
  std::printf("  %-28s exact %10.3f us   (1000 builds at distinct alpha' in (0.9999, 1), per build)\n",
              "one profile build, alpha'>.9999",
              per_build_us([&](int k) { return ExactProfile(table, 1 - 9e-5 * (k + 1) / 1001.0, 0.3, 1.35); }));
  std::printf("  %-28s exact %10.3f us   (1000 builds at distinct g in (0.99, 0.999), per build)\n",
              "one profile build, g > 0.99",
              per_build_us([&](int k) { return ExactProfile(table, 0.7, 0.99 + 9e-6 * (k + 1), 1.35); }));
  const double eta_high = exact_eta_range(table).second;
  std::printf("  %-28s exact %10.3f us   (1000 builds at distinct eta near the largest, per build)\n",
              "one profile build, high eta",
              per_build_us([&](int k) { return ExactProfile(table, 0.7, 0.5, eta_high - 1e-4 * (k + 1)); }));
  const auto above = reduce(1e-5, 0.99999, 0.3, 1.35), forward = reduce(0.3, 70.0, 0.995, 1.35);
  row("one R(r), alpha' 0.99999",
      median_ns_per_call([&](double r) { return exact->reflectance(above, r); }, radii, repetitions),
      median_ns_per_call([&](double r) { return pbd->reflectance(above, r); }, radii, repetitions), "ns", 100);
  row("one R(r), g 0.995",
      median_ns_per_call([&](double r) { return exact->reflectance(forward, r); }, radii, repetitions),
      median_ns_per_call([&](double r) { return pbd->reflectance(forward, r); }, radii, repetitions), "ns", 100);

  // A radial LUT for one material (3 channels, default tolerance).
  RadialTableOptions lut;
  row("radial LUT, Skin1", median_ms([&] { return build_radial_table(skin, *exact, lut).max_error; }, repetitions),
      median_ms([&] { return build_radial_table(skin, *pbd, lut).max_error; }, repetitions), "ms", 2);

  const auto coke = MaterialDatabase::load(default_materials_dir()).find("Coke").medium;  // alpha' < 0.001, and 0
  row("radial LUT, Coke", median_ms([&] { return build_radial_table(coke, *exact, lut).max_error; }, repetitions),
      median_ms([&] { return build_radial_table(coke, *pbd, lut).max_error; }, repetitions), "ms", 2);

  // A 3-channel profile fit on a profile the model itself generated (40 radii, Skin1's g and eta).
  const auto fit_ms = [&](const Model& model) {
    const auto data = three_channel_profile(model, skin);
    ProfileFitOptions options;
    options.model = model.name();
    options.eta = skin.eta;
    options.g = skin.g;
    return median_ms([&] { return fit_profile(data, options).relative_rms; }, repetitions);
  };
  row("3-channel profile fit", fit_ms(*exact), fit_ms(*pbd), "ms", 20);

  // 1000 albedo inversions: totals spread over what both models reach at eta 1.3.
  std::vector<double> totals;
  for (int k = 0; k < 1000; ++k) totals.push_back(0.01 + 0.5 * k / 999.0);
  row("1000 albedo inversions",
      median_ms(
          [&] {
            double s = 0;
            for (double t : totals) s += exact_albedo_prime_from_total(table, t, 0.0, 1.3);
            return s;
          },
          repetitions),
      // pbd's generic root finding costs ~16 ms per value: every 10th value, times 10.
      10 * median_ms(
               [&] {
                 double s = 0;
                 for (std::size_t k = 0; k < totals.size(); k += 10)
                   s += pbd->albedo_prime_from_total(totals[k], 1.3, 0.0);
                 return s;
               },
               std::min(repetitions, 3)),
      "ms", 5);

  // `--model auto` on one material: the live measurement of every candidate against exact.
  const double lut_ms = median_ms([&] { return build_radial_table(skin, *exact, lut).max_error; }, repetitions);
  const double choose_ms =
      median_ms([&] { return static_cast<double>(choose_model(skin, 0.1).estimates.size()); }, repetitions);
  std::printf("  %-28s %10.3f ms   exact radial LUT %8.3f ms   ratio %6.1f   goal <= 200 ms: %s\n",
              "choose_model(Skin1, 0.1)", choose_ms, lut_ms, choose_ms / lut_ms, choose_ms <= 200 ? "met" : "MISSED");
  return 0;
}
