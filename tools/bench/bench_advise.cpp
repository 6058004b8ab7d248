// Costs behind `bssrdf advise` (advise/advise.hpp), medians, with ratios against the dipole's
// R(r) measured in the same run (bench_models' baseline):
//  - one lookup of a 16-radius table (radial_table: a log, a floor, a lerp and an exp), one sum of
//    K Gaussians (K = 1, 2, 4, 8), one separable-kernel tap: the per-evaluation costs the candidates
//    assume;
//  - advise() for Skin1 at 0.01 to 10 mm with the Monte Carlo reference (200 000 photons) and with
//    a model as the reference (PBD: what plugging in an exact model costs), and the whole database
//    (materials in parallel, as `advise --all`) with --reference auto against the model reference.
//
//   bench_advise [repetitions=5]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "bssrdf/advise/advise.hpp"
#include "bssrdf/advise/auto_reference.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/parallel.hpp"
#include "median_timing.hpp"

using namespace bssrdf;
using bssrdf::bench::median_ns_per_call;

namespace {

template <class F>
double median_seconds(F&& f, int repetitions) {
  std::vector<double> s;
  for (int rep = 0; rep < repetitions; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    f();
    s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(s.begin(), s.begin() + repetitions / 2, s.end());
  return s[repetitions / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::vector<double> radii;
  for (int i = 0; i < 64; ++i) radii.push_back(0.01 * std::pow(2000.0, i / 63.0));
  const auto m = reduce(0.1, 0.9, 0.0, 1.3);
  const auto dipole = make_model("dipole");
  const double base = median_ns_per_call([&](double r) { return dipole->reflectance(m, r); }, radii, repetitions);
  std::printf("per evaluation, median of %d (alpha' 0.9, eta 1.3, 64 radii over 0.01-20 ell); ratio to the dipole\n",
              repetitions);
  std::printf("  %-22s %8.2f ns  1.00\n", "dipole (baseline)", base);
  const auto table = radial_table(*make_model("pbd"), m, 16);
  const double lookup = median_ns_per_call(table, radii, repetitions);
  std::printf("  %-22s %8.2f ns  %.2f   (assumed kTableLookupNs = %g)\n", "radial table lookup", lookup, lookup / base,
              kTableLookupNs);
  for (int k : {1, 2, 4, 8}) {
    std::vector<double> w(static_cast<std::size_t>(k), 0.1), v;
    for (int j = 0; j < k; ++j) v.push_back(0.1 * std::pow(4.0, j));
    const double ns = median_ns_per_call(
        [&](double r) {
          double R = 0;
          for (std::size_t j = 0; j < w.size(); ++j)
            R += w[j] * std::exp(-r * r / (2 * v[j])) / (2 * std::numbers::pi * v[j]);
          return R;
        },
        radii, repetitions);
    std::printf("  %d Gaussian%-12s %8.2f ns  %.2f   (assumed %g)\n", k, k > 1 ? "s" : "", ns, ns / base,
                k * kGaussianTermNs);
  }
  {
    // One separable-kernel tap: an RGB irradiance row read between two texels (a bilinear fetch
    // along the pass) and a multiply-add per channel; the "radius" argument is the sample position.
    std::vector<float> row(3 * 4096);
    for (std::size_t i = 0; i < row.size(); ++i) row[i] = static_cast<float>(i % 97) / 97.0f;
    const float weight[3] = {0.3f, 0.2f, 0.1f};
    const double ns = median_ns_per_call(
        [&](double r) {
          const double x = r * 100;
          const auto i = static_cast<std::size_t>(x);
          const float t = static_cast<float>(x - static_cast<double>(i));
          float acc = 0;
          for (int c = 0; c < 3; ++c) acc += weight[c] * ((1 - t) * row[3 * i + c] + t * row[3 * i + 3 + c]);
          return static_cast<double>(acc);
        },
        radii, repetitions);
    std::printf("  %-22s %8.2f ns  %.2f   (assumed kKernelTapNs = %g)\n", "separable kernel tap", ns, ns / base,
                kKernelTapNs);
  }

  const auto database = MaterialDatabase::load_with_user("");
  const Medium& skin = database.find("Skin1").medium;
  const MonteCarloReference mc({200'000, 1, 0});
  const ModelReference model_reference(make_model("pbd"));
  std::printf("\nadvise(Skin1), wall seconds, median of %d\n", repetitions);
  for (double pixel : {0.01, 0.1, 1.0, 10.0}) {
    AdviseOptions o;
    o.pixel = pixel;
    const double with_mc = median_seconds([&] { advise(skin, mc, o); }, repetitions);
    const double with_model = median_seconds([&] { advise(skin, model_reference, o); }, repetitions);
    std::printf("  %5g mm  Monte Carlo reference %.3f s   model reference %.3f s   ratio %.1f\n", pixel, with_mc,
                with_model, with_mc / with_model);
  }
  // The whole database as `advise --all` runs it: materials in parallel on every core. The baseline is
  // the model reference (PBD, no band: the cost of the candidates alone); `auto` is what the command
  // uses by default (auto_reference.hpp: exact, adding-doubling + a shape, or Monte Carlo per channel).
  AdviseOptions o;
  o.pixel = 1;
  const AutoReference automatic({200'000, 1, 0});
  const auto& materials = database.all();
  const auto database_seconds = [&](const ReferenceProfile& reference) {
    return median_seconds(
        [&] { parallel_for(materials.size(), 0, [&](std::size_t i) { advise(materials[i].medium, reference, o); }); },
        repetitions);
  };
  const double baseline = database_seconds(model_reference);
  const double with_auto = database_seconds(automatic);
  std::printf("\nthe database (%zu materials) at 1 mm, all cores, median of %d:\n", materials.size(), repetitions);
  std::printf("  model reference (baseline)  %.2f s (%.3f s a material)\n", baseline,
              baseline / static_cast<double>(materials.size()));
  std::printf("  --reference auto            %.2f s (%.3f s a material)   ratio %.2f   goal < 10 s\n", with_auto,
              with_auto / static_cast<double>(materials.size()), with_auto / baseline);
}
