// The exact model against fresh Monte Carlo runs at random parameter points off the table's grid,
// and the bundled materials' totals against fresh runs: the accuracy table of README "The exact
// model" (output committed as tools/validation/exact_vs_montecarlo.txt).
//
//   validate_exact [points=40] [scatterings per point=4e9] [seed=7] [materials=1] [points below alpha' 0.001=10]
//                  [alpha'_min=0.001 alpha'_max=0.9999 g_max=0.99 g_min=0]   (a part of the domain only)
//                  [photons per point at most=5e7] [eta_min=1 eta_max=1.6]
//   validate_exact at SCATTERINGS MAX_PHOTONS SEED ALPHA',G,ETA [...]   (given points, e.g. again with
//                  more photons where a random point's run was too noisy to resolve the goal)
//   BSSRDF_VALIDATE_BINS=PREFIX validate_exact ...   also writes each point's bins to PREFIX_<i>.tsv (inner,
//                  outer radius, Monte Carlo R and its standard error, the model's bin average, the bin's
//                  representative radius; the run's total and photons in the header): where a miss lies in r
//   validate_exact rescore FILE.tsv [...]   the same figures from such files, the model as it is now (another
//                  table through BSSRDF_EXACT_TABLE): two tables against the very same reference runs;
//                  with BSSRDF_VALIDATE_BINS the files are written again with this model's column
//
// Each point: alpha' log-uniform in logit over [0.001, 0.9999] (1 - alpha' log-uniform where
// alpha'_min >= 0.9999: the continuation to 1), g uniform in -ln(1 - g) over [0, 0.99], eta uniform
// over [1, 1.6], drawn with a generator independent of the table's seeds; a
// Monte Carlo run in transport units (sigma_t' = 1) with 100 log bins from 1e-3 to the radius that
// holds 99.9 % of the energy, photons chosen to spend the given number of scatterings (a pilot run
// measures the cost per photon). Reported: the total's deviation (and in standard errors), and the
// relative L2 error of r R(r) over dr inside and beyond one transport mfp with the run's own noise on
// the same bins (reference_comparison.hpp). Goals (issue): total within 1 % or 3 sigma, both L2
// within 3 %.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/reference_comparison.hpp"

using namespace bssrdf;

namespace {

// Photons to spend the given scatterings, at most max_photons (a low-albedo photon costs about one).
MonteCarloResult run(const Medium& medium, const Model& model, double scatterings, std::uint64_t seed,
                     double max_photons) {
  MonteCarloOptions pilot;
  pilot.photons = 2000;
  pilot.seed = seed + 1000003;
  pilot.bins = 2;
  const auto p = run_monte_carlo(LayerStack::half_space(medium), pilot);
  double per_photon = 0;
  for (const auto& c : p.channels) per_photon = std::max(per_photon, static_cast<double>(c.interactions) / 2000.0);
  MonteCarloOptions options;
  options.photons = static_cast<std::uint64_t>(std::clamp(scatterings / std::max(per_photon, 1.0), 2e4, max_photons));
  options.seed = seed;
  options.spacing = BinSpacing::log;
  options.bins = 100;
  double r_max = 0;
  for (std::size_t c = 0; c < medium.channels(); ++c)
    r_max = std::max(r_max, model.radius_for_fraction(medium.reduced(c), 0.999));
  options.r_max = r_max;
  double ell = 1e300;
  for (std::size_t c = 0; c < medium.channels(); ++c) ell = std::min(ell, medium.reduced(c).ell);
  options.r_min = 1e-3 * ell;
  return run_monte_carlo(LayerStack::half_space(medium), options);
}

// The point's bins side by side (BSSRDF_VALIDATE_BINS).
void write_bins(const std::string& prefix, int i, const Model& model, const Medium& medium,
                const MonteCarloResult& run) {
  const std::string path = prefix + "_" + std::to_string(i) + ".tsv";
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "validate_exact: cannot write %s\n", path.c_str());
    std::exit(2);
  }
  const auto m = medium.reduced(0);
  const auto mc = run.channels[0].per_entered_flux();
  std::fprintf(f, "# alpha' %.17g g %.17g eta %.17g\n", m.albedo_prime, m.g, m.eta);
  std::fprintf(f, "# diffuse_reflectance %.17g stderr %.17g photons %llu\n", mc.diffuse_reflectance.value,
               mc.diffuse_reflectance.standard_error, static_cast<unsigned long long>(run.options.photons));
  std::fprintf(f, "# inner\touter\tmc\tmc_stderr\tmodel\tradius\n");
  for (std::size_t k = 0; k < mc.reflectance.size(); ++k) {
    const double inner = run.bin_inner[k], outer = run.bin_outer[k];
    std::fprintf(f, "%.17g\t%.17g\t%.17g\t%.17g\t%.9g\t%.17g\n", inner, outer, mc.reflectance[k],
                 mc.reflectance_stderr[k], model_bin_average(model, m, inner, outer), run.bin_radius[k]);
  }
  std::fclose(f);
}

// A run as write_bins left it (per entered flux: no specular reflection), for `rescore`.
struct StoredRun {
  Medium medium;
  MonteCarloResult run;
};
StoredRun read_bins(const char* path) {
  const auto fail = [&](const char* what) {
    std::fprintf(stderr, "validate_exact: %s: %s (expected a file written with BSSRDF_VALIDATE_BINS)\n", path, what);
    std::exit(2);
  };
  std::FILE* f = std::fopen(path, "r");
  if (!f) fail("cannot read");
  double ap = 0, g = 0, eta = 0, total = 0, total_se = 0;
  unsigned long long photons = 0;
  char columns[256];
  if (std::fscanf(f, "# alpha' %lf g %lf eta %lf\n", &ap, &g, &eta) != 3 ||
      std::fscanf(f, "# diffuse_reflectance %lf stderr %lf photons %llu\n", &total, &total_se, &photons) != 3 ||
      !std::fgets(columns, sizeof columns, f) || !(ap > 0 && ap < 1 && g >= 0 && g < 1 && eta >= 1 && total > 0))
    fail("no header of a validate_exact bins file");
  StoredRun s{Medium::single_channel(1 - ap, ap / (1 - g), g, eta), {}};
  ChannelResult c;
  c.diffuse_reflectance = {total, total_se};
  double inner = 0, outer = 0, r = 0, se = 0, model = 0, radius = 0;
  while (std::fscanf(f, "%lf %lf %lf %lf %lf %lf", &inner, &outer, &r, &se, &model, &radius) == 6) {
    s.run.bin_inner.push_back(inner);
    s.run.bin_outer.push_back(outer);
    s.run.bin_radius.push_back(radius);
    c.reflectance.push_back(r);
    c.reflectance_stderr.push_back(se);
  }
  const bool complete = std::feof(f);
  std::fclose(f);
  if (!complete || c.reflectance.empty()) fail("a bin row is not six numbers");
  s.run.channels.push_back(std::move(c));
  s.run.options.photons = photons;
  return s;
}

// The per-point rows and the section's summary: each point's deviation against its run.
class Scores {
 public:
  Scores() {
    std::printf("# %9s %6s %6s %10s %8s %7s %8s %8s %8s %8s\n", "alpha'", "g", "eta", "photons", "total%", "sigma",
                "near%", "noise%", "far%", "noise%");
  }
  void add(const Reduced<double>& m, const MonteCarloResult& mc, const ProfileDeviation& d) {
    const auto per_entered = mc.channels[0].per_entered_flux();
    const double sigma = d.total * per_entered.diffuse_reflectance.value / per_entered.diffuse_reflectance.standard_error;
    std::printf("%11.6g %6.3f %6.3f %10llu %8.3f %7.2f %8.3f %8.3f %8.3f %8.3f\n", m.albedo_prime, m.g, m.eta,
                static_cast<unsigned long long>(mc.options.photons), 100 * d.total, sigma, 100 * d.near_r,
                100 * d.near_r_noise, 100 * d.far_r, 100 * d.far_r_noise);
    std::fflush(stdout);
    ++n_;
    total_ok_ += std::abs(d.total) <= 0.01 || std::abs(sigma) <= 3;
    near_ok_ += d.near_r <= 0.03;
    far_ok_ += d.far_r <= 0.03;
    // The table's own error: what the L2 holds beyond the run's noise (they add in quadrature).
    const auto beyond_noise = [](double l2, double noise) { return std::sqrt(std::max(0.0, l2 * l2 - noise * noise)); };
    const double near_excess = beyond_noise(d.near_r, d.near_r_noise), far_excess = beyond_noise(d.far_r, d.far_r_noise);
    near_excess_ok_ += near_excess <= 0.03;
    far_excess_ok_ += far_excess <= 0.03;
    worst_total_ = std::max(worst_total_, std::abs(d.total));
    worst_near_ = std::max(worst_near_, d.near_r);
    worst_far_ = std::max(worst_far_, d.far_r);
    worst_near_excess_ = std::max(worst_near_excess_, near_excess);
    worst_far_excess_ = std::max(worst_far_excess_, far_excess);
  }
  void summary() const {
    std::printf("# points meeting the goals: total %d/%d, near L2 %d/%d, far L2 %d/%d\n", total_ok_, n_, near_ok_, n_,
                far_ok_, n_);
    std::printf(
        "# worst: total %.3f %%, near L2 %.3f %%, far L2 %.3f %% (the Monte Carlo noise is in the L2: see columns)\n",
        100 * worst_total_, 100 * worst_near_, 100 * worst_far_);
    std::printf(
        "# beyond the runs' noise (sqrt(L2^2 - noise^2)): near L2 within 3 %% at %d/%d (worst %.3f %%), far L2 at "
        "%d/%d (worst %.3f %%)\n",
        near_excess_ok_, n_, 100 * worst_near_excess_, far_excess_ok_, n_, 100 * worst_far_excess_);
  }

 private:
  int n_ = 0, total_ok_ = 0, near_ok_ = 0, far_ok_ = 0, near_excess_ok_ = 0, far_excess_ok_ = 0;
  double worst_total_ = 0, worst_near_ = 0, worst_far_ = 0, worst_near_excess_ = 0, worst_far_excess_ = 0;
};

}  // namespace

struct Point {
  double albedo_prime, g, eta;
};

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "rescore") {
    if (argc < 3) {
      std::fprintf(stderr, "usage: validate_exact rescore FILE.tsv [...]\n");
      return 2;
    }
    std::vector<StoredRun> runs;
    for (int i = 2; i < argc; ++i) runs.push_back(read_bins(argv[i]));  // every file read before any output
    const auto model = make_model("exact");
    std::printf("# exact model (table %s) vs the stored Monte Carlo runs %s ...\n",
                std::getenv("BSSRDF_EXACT_TABLE") ? std::getenv("BSSRDF_EXACT_TABLE") : "bundled", argv[2]);
    Scores scores;
    const char* prefix = std::getenv("BSSRDF_VALIDATE_BINS");  // the bins again, with this table's model column
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const StoredRun& s = runs[i];
      scores.add(s.medium.reduced(0), s.run, compare_with_monte_carlo(*model, s.medium.reduced(0), s.run));
      if (prefix) write_bins(prefix, static_cast<int>(i), *model, s.medium, s.run);
    }
    scores.summary();
    return 0;
  }
  // `validate_exact at SCATTERINGS MAX_PHOTONS SEED ALPHA',G,ETA ...`: given points again with more
  // photons (where a random point's run was too noisy to resolve the goal).
  const bool given = argc > 1 && std::string(argv[1]) == "at";
  if (given && argc < 6) {
    std::fprintf(stderr, "usage: validate_exact at SCATTERINGS MAX_PHOTONS SEED ALPHA',G,ETA [...]\n");
    return 2;
  }
  std::vector<Point> given_points;
  for (int i = 5; given && i < argc; ++i) {
    Point p{};
    if (std::sscanf(argv[i], "%lf,%lf,%lf", &p.albedo_prime, &p.g, &p.eta) != 3) {
      std::fprintf(stderr, "validate_exact: point %s: expected ALPHA',G,ETA\n", argv[i]);
      return 2;
    }
    // The exact model's domain (models/exact.hpp); alpha' = 1 has no finite Monte Carlo run.
    const ExactTable& table = bundled_exact_table();
    const auto [g_lo, g_hi] = exact_g_range(table);
    const auto [eta_lo, eta_hi] = exact_eta_range(table);
    if (!(p.albedo_prime > 0 && p.albedo_prime < 1 && p.g >= g_lo && p.g <= g_hi && p.eta >= eta_lo &&
          p.eta <= eta_hi)) {
      std::fprintf(stderr,
                   "validate_exact: point %s: accepted range is 0 < alpha' < 1, %g <= g <= %g, %g <= eta <= %g\n",
                   argv[i], g_lo, g_hi, eta_lo, eta_hi);
      return 2;
    }
    given_points.push_back(p);
  }
  // Positional arguments of the random-point mode (the `at` mode reads its own three).
  const auto arg = [&](int i, double fallback) { return !given && argc > i ? std::atof(argv[i]) : fallback; };
  const int points = given ? 0 : static_cast<int>(arg(1, 40));
  const double scatterings = std::atof(argc > 2 ? argv[2] : "4e9");
  const unsigned seed = static_cast<unsigned>(given ? std::atoi(argv[4]) : arg(3, 7));
  const bool materials = !given && arg(4, 1) != 0;
  const int low_points = static_cast<int>(arg(5, 10));
  // Optionally a part of the domain only (a region's band in the registry): alpha' and g bounds,
  // and a photon cap, to resolve a few percent where the runs are noisiest (far field at low albedo
  // and high g).
  const double ap_min = arg(6, 0.001), ap_max = arg(7, 0.9999), g_max = arg(8, 0.99), g_min = arg(9, 0.0);
  const double max_photons = given ? std::atof(argv[3]) : arg(10, 5e7);
  const double eta_min = arg(11, 1.0), eta_max = arg(12, 1.6);
  const auto model = make_model("exact");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  const double g_lo = -std::log1p(-g_min), g_hi = -std::log1p(-g_max);

  // Random points: alpha' log-uniform in logit over [ap_lo, ap_hi], g uniform in -ln(1 - g), eta uniform.
  const auto draw = [&](int n, double ap_lo, double ap_hi) {
    // Above 0.9999 (the continuation to alpha' = 1): 1 - alpha' log-uniform, down to 1e-7.
    const bool near_one = ap_lo >= 0.9999;
    const double lo = near_one ? std::log(1 - ap_lo) : std::log(ap_lo / (1 - ap_lo));
    const double hi = near_one ? std::log(std::max(1e-7, 1 - ap_hi)) : std::log(ap_hi / (1 - ap_hi));
    std::vector<Point> out;
    for (int i = 0; i < n; ++i) {
      const double u = lo + (hi - lo) * uniform(rng);
      const double ap = near_one ? 1 - std::exp(u) : 1 / (1 + std::exp(-u));
      const double g = 1 - std::exp(-(g_lo + (g_hi - g_lo) * uniform(rng)));
      const double eta = eta_min + (eta_max - eta_min) * uniform(rng);
      out.push_back({ap, g, eta});
    }
    return out;
  };
  // One section: each point against its own fresh run.
  const auto section = [&](const std::vector<Point>& list, std::uint64_t seed_offset, double max_photons) {
    Scores scores;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const auto [ap, g, eta] = list[i];
      // Transport units: sigma_t' = 1.
      const Medium medium = Medium::single_channel(1 - ap, ap / (1 - g), g, eta);
      const auto mc =
          run(medium, *model, scatterings, seed * 1000 + seed_offset + static_cast<unsigned>(i), max_photons);
      if (const char* prefix = std::getenv("BSSRDF_VALIDATE_BINS"))
        write_bins(prefix, static_cast<int>(i), *model, medium, mc);
      scores.add(medium.reduced(0), mc, compare_with_monte_carlo(*model, medium.reduced(0), mc));
    }
    scores.summary();
  };

  if (given) {
    std::printf(
        "# exact model vs fresh Monte Carlo at given points (seed %u, %.3g scatterings per point, up to %.3g "
        "photons)\n",
        seed, scatterings, max_photons);
    section(given_points, 0, max_photons);
    return 0;
  }
  if (points > 0) {
    std::printf(
        "# exact model vs fresh Monte Carlo at random off-grid points (seed %u, %.3g scatterings per point; alpha' "
        "%g-%g, g %g-%g, eta %g-%g, up to %.3g photons)\n",
        seed, scatterings, ap_min, ap_max, g_min, g_max, eta_min, eta_max, max_photons);
    section(draw(points, ap_min, ap_max), 0, max_photons);
  }
  if (low_points > 0) {
    std::printf(
        "\n# below the table's first albedo node (alpha' 1e-5 to 0.001: exact single scattering + the first two "
        "nodes' multiple scattering continued in alpha at the medium's rho), seed %u, up to 1e9 photons per point\n",
        seed);
    section(draw(low_points, 1e-5, 0.001), 500, 1e9);  // few photons reflect: many are needed
  }
  if (!materials) return 0;

  std::printf("\n# bundled materials: each channel's total, exact model vs a fresh Monte Carlo run\n");
  std::printf("# %-28s %4s %9s %6s %6s %9s %9s %8s %7s\n", "material", "ch", "alpha'", "g", "eta", "exact", "mc",
              "dev%", "sigma");
  const MaterialDatabase db = MaterialDatabase::load(default_materials_dir());
  int served = 0, channels = 0, within = 0;
  for (const auto& material : db.all()) {
    const Medium& medium = material.medium;
    for (std::size_t c = 0; c < medium.channels(); ++c) {
      ++channels;
      const auto m = medium.reduced(c);
      if (worst(model->validity(m)) == Severity::invalid) {
        std::printf("  %-28s %4zu %9.6f %6.3f %6.3f %9s (outside the table: %s)\n", material.name.c_str(), c,
                    m.albedo_prime, m.g, m.eta, "-", model->validity(m).front().message.c_str());
        continue;
      }
      ++served;
      if (m.sigma_s_prime == 0) {  // nothing scatters: no light comes back, in either
        within += model->total_reflectance(m) == 0;
        std::printf("  %-28s %4zu %9.6f %6.3f %6.3f %9.6f %9s (no scattering: R = 0)\n", material.name.c_str(), c,
                    m.albedo_prime, m.g, m.eta, model->total_reflectance(m), "0");
        continue;
      }
      const Medium one = Medium::single_channel(m.sigma_a, m.sigma_s, m.g, m.eta);
      MonteCarloOptions options;
      options.photons = 20000;
      options.seed = 99 + c;
      options.bins = 2;
      const auto pilot = run_monte_carlo(LayerStack::half_space(one), options);
      const double per_photon = static_cast<double>(pilot.channels[0].interactions) / 20000.0;
      options.photons = static_cast<std::uint64_t>(std::clamp(scatterings / 4 / std::max(per_photon, 1.0), 2e4, 2e7));
      const auto mc = run_monte_carlo(LayerStack::half_space(one), options).channels[0].per_entered_flux();
      const double exact = model->total_reflectance(m);
      const double dev = exact / mc.diffuse_reflectance.value - 1;
      const double sigma = (exact - mc.diffuse_reflectance.value) / mc.diffuse_reflectance.standard_error;
      within += std::abs(dev) <= 0.01 || std::abs(sigma) <= 3;
      std::printf("  %-28s %4zu %9.6f %6.3f %6.3f %9.6f %9.6f %8.3f %7.2f\n", material.name.c_str(), c, m.albedo_prime,
                  m.g, m.eta, exact, mc.diffuse_reflectance.value, 100 * dev, sigma);
      std::fflush(stdout);
    }
  }
  std::printf("# channels inside the domain %d/%d; their totals within 1 %% or 3 sigma: %d/%d\n", served, channels,
              within, served);
  return 0;
}
