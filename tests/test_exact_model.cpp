// The exact model: the bundled table, its interpolation, and its agreement with references it was
// not built from at these points: adding-doubling totals and fresh Monte Carlo runs at random
// parameter points off the table's grid (modest photon counts, statistical tolerances; the long run
// is tools/validation/validate_exact).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <utility>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/reference_comparison.hpp"
#include "bssrdf/single_scattering.hpp"
#include "cli_runner.hpp"

using namespace bssrdf;
using namespace bssrdf::test_cli;

namespace {

const ExactTable& table() { return bundled_exact_table(); }

double adding_doubling_total(double ap, double g, double eta, double* error_estimate = nullptr) {
  const Reduced<double> m = reduce(1 - ap, ap / (1 - g), g, eta);
  adding_doubling::Options options;
  options.tolerance = 1e-6;
  const auto t =
      adding_doubling::solve(adding_doubling::half_space(m), adding_doubling::Incidence::collimated, options);
  if (error_estimate) *error_estimate = t.error_estimate * t.entered_scale();
  return t.diffuse_reflectance * t.entered_scale();
}

// Random points off the grid: alpha' uniform in logit, g uniform in -ln(1 - g), eta uniform.
struct Point {
  double albedo_prime, g, eta;
};
std::vector<Point> random_points(int n, unsigned seed, double ap_lo = 0.001, double ap_hi = 0.9999, double g_hi = 0.99,
                                 double eta_lo = 1.0, double eta_hi = 1.6) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double lo = std::log(ap_lo / (1 - ap_lo)), hi = std::log(ap_hi / (1 - ap_hi)), gh = -std::log1p(-g_hi);
  std::vector<Point> points;
  for (int i = 0; i < n; ++i)
    points.push_back({1 / (1 + std::exp(-(lo + (hi - lo) * u(rng)))), 1 - std::exp(-gh * u(rng)),
                      eta_lo + (eta_hi - eta_lo) * u(rng)});
  return points;
}

}  // namespace

TEST(ExactTable, BundledTableCoversTheDomainAndRecordsItsProvenance) {
  const ExactTable& t = table();
  EXPECT_LE(t.albedo_prime.front(), 0.001);
  EXPECT_GE(t.albedo_prime.back(), 0.9999);
  EXPECT_LE(t.g.front(), 0.0);
  EXPECT_GE(t.g.back(), 0.99);
  EXPECT_LE(t.eta.front(), 1.0);
  EXPECT_GE(t.eta.back(), 2.0);
  EXPECT_LE(t.radius(0), 1e-3 * 1.0001);
  const auto p = nlohmann::json::parse(t.provenance);
  EXPECT_GT(p.at("photons_total").get<double>(), 1e6);
  EXPECT_TRUE(p.contains("seed"));
  EXPECT_TRUE(p.contains("source_revision"));
  // The radius holding 99.9 % of the energy lies inside the table at every node.
  EXPECT_LT(p.at("largest_radius_999").get<double>(), t.radius(t.radii - 1));
  // The shipped data (this table and the materials database) stays within 4 MB.
  std::uintmax_t shipped = std::filesystem::file_size(bundled_exact_table_path());
  if (std::filesystem::exists(bundled_exact_table_path() + ".errors"))
    shipped += std::filesystem::file_size(bundled_exact_table_path() + ".errors");
  for (const auto& f : std::filesystem::recursive_directory_iterator(default_materials_dir()))
    if (f.is_regular_file()) shipped += f.file_size();
  EXPECT_LE(shipped, 4'000'000u);
}

// The bundled table with relative errors of its own (the model's load leaves the file's unread).
const ExactTable& table_with_errors() {
  static const ExactTable t = [] {
    ExactTable copy = table();
    copy.relative_error.resize(copy.ln_y.size());
    for (std::size_t i = 0; i < copy.relative_error.size(); ++i)
      copy.relative_error[i] = static_cast<std::uint16_t>(i * 7919 % 65536);
    return copy;
  }();
  return t;
}

TEST(ExactTable, RoundTripsThroughTheFileFormatAndRefusesTruncation) {
  const auto path = temp("round_trip.bin");
  write_exact_table(table_with_errors(), path.string());
  const ExactTable back = read_exact_table(path.string(), TableErrors::read);
  EXPECT_EQ(back.ln_y, table().ln_y);
  EXPECT_EQ(back.relative_error, table_with_errors().relative_error);
  EXPECT_EQ(back.total, table().total);
  EXPECT_EQ(back.total_eta, table().total_eta);
  EXPECT_EQ(back.fine_total, table().fine_total);
  // The model's load leaves the errors (a file of their own) unread.
  EXPECT_TRUE(read_exact_table(path.string()).relative_error.empty());
  // The arrays are read straight from the file: a file cut anywhere (in the magic, the header, each
  // array), or with bytes after the totals, is refused as a whole.
  const std::string whole = test_cli::slurp(path), errors = test_cli::slurp(path.string() + ".errors");
  const std::size_t n = table().ln_y.size(),
                    header_end = whole.size() - 4 * n - 8 * table().total.size() - 8 * table().fine_total.size();
  ASSERT_EQ(errors.size(), 16 + 2 * n);
  for (const std::size_t size : {std::size_t{0}, std::size_t{7}, std::size_t{16}, header_end - 1, header_end,
                                 header_end + 4 * n - 2, header_end + 4 * n + 5, whole.size() - 8, whole.size() - 1}) {
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(whole.data(), static_cast<std::streamsize>(size));
    EXPECT_THROW(read_exact_table(path.string()), InvalidInput) << size;
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << whole << "x";
  EXPECT_THROW(read_exact_table(path.string()), InvalidInput);
  EXPECT_THROW(read_exact_table(temp("").string()), FileError);  // a directory
  // The errors beside it: cut, with a byte more, or missing, refused when they are asked for.
  std::ofstream(path, std::ios::binary | std::ios::trunc) << whole;
  for (const std::size_t size : {std::size_t{7}, std::size_t{16}, errors.size() - 1}) {
    std::ofstream(path.string() + ".errors", std::ios::binary | std::ios::trunc)
        .write(errors.data(), static_cast<std::streamsize>(size));
    EXPECT_THROW(read_exact_table(path.string(), TableErrors::read), InvalidInput) << size;
  }
  std::ofstream(path.string() + ".errors", std::ios::binary | std::ios::trunc) << errors << "x";
  EXPECT_THROW(read_exact_table(path.string(), TableErrors::read), InvalidInput);
  std::filesystem::remove(path.string() + ".errors");
  EXPECT_THROW(read_exact_table(path.string(), TableErrors::read), FileError);
  EXPECT_NO_THROW(read_exact_table(path.string()));
  // A version 2 table (the errors inline after ln_y) still loads, with or without its errors.
  std::string v2 = whole;
  const std::size_t at = v2.find("\"version\":3");
  ASSERT_NE(at, std::string::npos);
  v2[at + 10] = '2';
  v2.insert(header_end + 4 * n, errors.substr(16));
  std::ofstream(path, std::ios::binary | std::ios::trunc) << v2;
  EXPECT_EQ(read_exact_table(path.string(), TableErrors::read).relative_error, table_with_errors().relative_error);
  EXPECT_EQ(read_exact_table(path.string()).total, table().total);
  v2.resize(header_end + 4 * n + n);  // cut inside the inline errors
  std::ofstream(path, std::ios::binary | std::ios::trunc) << v2;
  EXPECT_THROW(read_exact_table(path.string()), InvalidInput);
  // A version 1 table (no fine totals) still loads, and its totals are the coarse ones.
  ExactTable v1 = table();
  v1.total_eta.clear();
  v1.fine_total.clear();
  write_exact_table(v1, path.string());
  const ExactTable old = read_exact_table(path.string());
  EXPECT_TRUE(old.total_eta.empty());
  EXPECT_NEAR(exact_total(old, old.albedo_prime[20], old.g[4], old.eta[2]), old.total[old.node(2, 4, 20)], 1e-12);
}

TEST(ExactModel, TotalsFollowTheBendJustAboveEtaOne) {
  // Total internal reflection sets in just above eta = 1 and bends the total within a few
  // hundredths of it; the coarse eta nodes (1.0, 1.05) alone missed it by up to 0.5 % at 1.02.
  // Fresh adding-doubling at random points with eta in (1, 1.05) is the reference.
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0;
  int compared = 0;
  for (int i = 0; i < 16; ++i) {
    const double ap = 1 / (1 + std::exp(-(-4.6 + 9.2 * u(rng)))), g = 0.9 * u(rng), eta = 1 + 0.05 * u(rng);
    double error_estimate = 0;
    const double reference = adding_doubling_total(ap, g, eta, &error_estimate);
    if (error_estimate > 2e-4 * reference) continue;
    ++compared;
    const double exact = exact_total(table(), ap, g, eta);
    worst = std::max(worst, std::abs(exact / reference - 1));
    EXPECT_NEAR(exact / reference, 1.0, 2e-3) << ap << " " << g << " " << eta;
  }
  EXPECT_GE(compared, 12);
  std::printf("exact totals vs adding-doubling at %d points with eta in (1, 1.05): worst %.3f %%\n", compared,
              100 * worst);
}

TEST(ExactModel, LowAlbedoForwardTotalsFollowTheBendJustAboveEtaOne) {
  // Where adding-doubling does not converge (low albedo, g near 1) the fine totals are exact single
  // scattering at each eta plus the multiple scattering interpolated; interpolating the whole total
  // from the coarse eta nodes was 1.06 % (7 sigma) above fresh Monte Carlo at this point. The
  // reference is a fresh run (cheap: about two scatterings per photon); its standard error here is
  // 0.23 %, so the former error would be 4.5 sigma.
  const Point p{0.0026, 0.98, 1.02};
  const Medium medium = Medium::single_channel(1 - p.albedo_prime, p.albedo_prime / (1 - p.g), p.g, p.eta);
  MonteCarloOptions options;
  options.photons = 150000000;
  options.seed = 41;
  options.bins = 2;
  options.r_max = 10;
  const auto mc = run_monte_carlo(LayerStack::half_space(medium), options).channels[0].per_entered_flux();
  const double exact = exact_total(table(), p.albedo_prime, p.g, p.eta);
  const double sigma = (exact - mc.diffuse_reflectance.value) / mc.diffuse_reflectance.standard_error;
  EXPECT_LE(std::abs(sigma), 3.0) << exact << " vs " << mc.diffuse_reflectance.value;
  std::printf("alpha' %g g %g eta %g: exact total %+.3f %% (%.2f sigma) from fresh Monte Carlo\n", p.albedo_prime, p.g,
              p.eta, 100 * (exact / mc.diffuse_reflectance.value - 1), sigma);
}

TEST(ExactModel, OutsideTheTableARefusalNamesTheParameter) {
  const auto refused = [](double ap, double g, double eta) -> std::string {
    try {
      ExactProfile p(table(), ap, g, eta);
    } catch (const InvalidInput& e) {
      return e.field();
    }
    return "";
  };
  EXPECT_EQ(refused(0.0005, 0.5, 1.3), "");  // below the first node: continued exactly
  EXPECT_EQ(refused(0.0, 0.5, 1.3), "");
  EXPECT_EQ(refused(-0.001, 0.5, 1.3), "albedo'");
  EXPECT_EQ(refused(0.99995, 0.5, 1.3), "");  // above the last node: continued by diffusion, to 1
  EXPECT_EQ(refused(1.0, 0.5, 1.3), "");
  EXPECT_EQ(refused(1.001, 0.5, 1.3), "albedo'");
  EXPECT_EQ(refused(0.5, 0.995, 1.3), "");  // the table's g nodes reach 0.999
  EXPECT_EQ(refused(0.5, 0.999, 1.3), "");
  EXPECT_EQ(refused(0.5, 0.9995, 1.3), "g");
  EXPECT_EQ(refused(0.5, -0.1, 1.3), "g");
  EXPECT_EQ(refused(0.5, 0.5, exact_eta_range(table()).second + 0.1), "eta");
  EXPECT_EQ(refused(0.5, 0.5, 1.3), "");
  const auto model = make_model("exact");
  const auto report = model->validity(reduce(0.0, 1.0, 0.995, 1.3));  // g 0.995 at alpha' = 1: inside
  EXPECT_NE(worst(report), Severity::invalid);
  const auto outside = model->validity(reduce(0.1, 1.0, 0.9995, 1.3));
  ASSERT_FALSE(outside.empty());
  EXPECT_EQ(worst(outside), Severity::invalid);
  EXPECT_EQ(outside.front().code, "exact_g");
}

TEST(ExactModel, TotalsMatchAddingDoublingOffTheGrid) {
  // The table stores adding-doubling totals at its nodes; between them the interpolation must stay
  // within half the 1 % goal. Fresh adding-doubling at random points is the reference, where it
  // converges (its own error estimate within 2e-4 of the total: not at g near 1 with low albedo).
  double worst = 0;
  int compared = 0;
  std::vector<Point> points = random_points(24, 11);
  for (const Point& p : random_points(12, 12, 0.001, 0.9999, 0.99, 1.6, 2.0)) points.push_back(p);  // high index
  for (const Point& p : points) {
    const double exact = exact_total(table(), p.albedo_prime, p.g, p.eta);
    double error_estimate = 0;
    const double reference = adding_doubling_total(p.albedo_prime, p.g, p.eta, &error_estimate);
    if (error_estimate > 2e-4 * reference) continue;
    ++compared;
    worst = std::max(worst, std::abs(exact / reference - 1));
    EXPECT_NEAR(exact / reference, 1.0, 5e-3) << p.albedo_prime << " " << p.g << " " << p.eta;
  }
  EXPECT_GE(compared, 18);
  RecordProperty("worst_total_vs_adding_doubling", std::to_string(worst));
  std::printf("exact totals vs fresh adding-doubling at %d random points: worst %.3f %%\n", compared, 100 * worst);
}

TEST(ExactModel, ProfileIntegratesToItsTotalAndIsPositive) {
  for (const Point& p : random_points(8, 5)) {
    const ExactProfile profile(table(), p.albedo_prime, p.g, p.eta);
    double previous = 0;
    for (double r = 1e-4; r < 1e4; r *= 1.7) {
      const double R = profile.reflectance(r), c = profile.cumulative(r);
      if (c < 0.999 * profile.total()) {
        ASSERT_GT(R, 0) << r;
      }  // far out the tail may underflow
      ASSERT_GE(R, 0) << r;
      ASSERT_GE(c, previous * (1 - 1e-12)) << r;
      previous = c;
    }
    EXPECT_NEAR(profile.cumulative(1e7) / profile.total(), 1.0, 1e-6);
    // The cumulative is the integral of R: compare one step with a fine trapezoid rule.
    const double a = 0.3, b = 0.6;
    double sum = 0;
    const int n = 2000;
    for (int i = 0; i <= n; ++i) {
      const double r = a + (b - a) * i / n;
      sum += (i == 0 || i == n ? 0.5 : 1.0) * 2 * std::numbers::pi * r * profile.reflectance(r);
    }
    EXPECT_NEAR((profile.cumulative(b) - profile.cumulative(a)) / (sum * (b - a) / n), 1.0, 1e-4);
  }
}

TEST(ExactModel, BelowTheFirstRadiusNoMoreSingularThanSingleScattering) {
  // Inside r0 = 1e-3 transport mfp, where single scattering has reached its r -> 0 form (R_ss ~ 1/r,
  // here at g 0.5), y = 2 pi r^2 R continues as a power of r no smaller than 1, so r R(r) <= r0 R(r0)
  // and the disc holds at most y(r0).
  const double r0 = table().radius(0);
  const ExactProfile profile(table(), 0.3, 0.5, 1.3);
  const double y0 = 2 * std::numbers::pi * r0 * r0 * profile.reflectance(r0);
  EXPECT_LE(profile.cumulative(r0), y0 * (1 + 1e-9));
  for (double r : {1e-4, 5e-4, 9e-4}) EXPECT_LE(r * profile.reflectance(r), r0 * profile.reflectance(r0) * (1 + 1e-9));
}

TEST(ExactModel, BelowTheFirstRadiusStronglyForwardMediaKeepTheirSingleScattering) {
  // With g near 1 the medium's mean free path is about (1 - g) transport mfp, so at r0 single
  // scattering is still attenuated, and the curve's first step continued below r0 had put R at
  // 1e-4 transport mfp 3.3x under single scattering alone (alpha' 0.9927, g 0.998, eta 1.604). Now y = y_ss,
  // exact, plus r0's multiple scattering flat in R: R(r) >= R_ss(r) within the normalisation (1 %),
  // and the disc r < r0 holds single scattering's energy there plus half r0's multiple scattering,
  // no more (at alpha' 0.1375, g 0.997 the nodes' first radii hold Monte Carlo noise, and a power
  // from the first step had put 1.77 times the fresh Monte Carlo's energy in the disc).
  const double r0 = table().radius(0);
  for (const Point& p : {Point{0.992728, 0.998, 1.604}, Point{0.555932, 0.99783, 1.545}, Point{0.137547, 0.997, 1.416},
                         Point{0.15859, 0.995, 1.45}, Point{0.9995, 0.999, 1.95}}) {
    const ExactProfile profile(table(), p.albedo_prime, p.g, p.eta);
    const Reduced<double> m = reduce(1 - p.albedo_prime, p.albedo_prime / (1 - p.g), p.g, p.eta);
    const auto y_ss = [&](double r) { return 2 * std::numbers::pi * r * r * single_scattering_reflectance(m, r, 96); };
    const auto over_ss = [&](double r) { return profile.reflectance(r) / (y_ss(r) / (2 * std::numbers::pi * r * r)); };
    for (double r : {1e-4, 1e-5, 1e-6}) EXPECT_GT(over_ss(r), 0.99) << p.g << " " << r;
    EXPECT_LT(over_ss(1e-6), 1.03) << p.g;  // there multiple scattering is ~1e-3 of it: single scattering's limit
    // That limit, R_ss -> sigma_s C / r, against the integral itself at rho = 1e-7.
    const double r_small = 1e-7 / m.sigma_t();
    EXPECT_NEAR(single_scattering_reflectance(m, r_small, 96) * r_small / m.sigma_s /
                    single_scattering_singular_coefficient(p.g, p.eta),
                1.0, 1e-5);
    // The single-scattering disc: int_0^r0 y_ss d ln r (trapezoid in ln r; y_ss ~ r below).
    double disc_ss = y_ss(r0 * std::exp(-40.0)) / 2 * 0.01;
    for (double u = 0; u < 40; u += 0.01)
      disc_ss += (y_ss(r0 * std::exp(-u)) + y_ss(r0 * std::exp(-u - 0.01))) / 2 * 0.01;
    const double ms0 = 2 * std::numbers::pi * r0 * r0 * profile.reflectance(r0) - y_ss(r0);
    EXPECT_GT(ms0, 0) << p.g;
    EXPECT_LT(profile.cumulative(r0), 1.01 * (disc_ss + ms0 / 2)) << p.albedo_prime << " " << p.g;
    EXPECT_GT(profile.cumulative(r0), 0.99 * (disc_ss + ms0 / 2)) << p.albedo_prime << " " << p.g;
  }
}

TEST(ExactModel, ContinuousFirstDerivativesAcrossTableNodes) {
  // At a node the one-sided derivatives of R(r) in each parameter agree (the interpolation is C1);
  // a linear interpolation would show a jump of the order of the slope change between cells.
  const auto R = [](double ap, double g, double eta) { return ExactProfile(table(), ap, g, eta).reflectance(0.7); };
  const double ap = table().albedo_prime[20], g = table().g[5], eta = table().eta[2];
  const double h = 1e-6;
  const auto check = [&](auto f, double x, const char* name) {
    const double left = (f(x) - f(x - h)) / h, right = (f(x + h) - f(x)) / h;
    EXPECT_NEAR(left, right, 1e-3 * std::max(1e-3, std::abs(left)) + 1e-5) << name;
  };
  check([&](double x) { return R(x, g, eta); }, ap, "albedo'");
  check([&](double x) { return R(ap, x, eta); }, g, "g");
  check([&](double x) { return R(ap, g, x); }, eta, "eta");
}

TEST(ExactModel, AlbedoInversionIsMonotoneAndRoundTrips) {
  for (const Point& p : random_points(4, 3)) {
    double previous = 0;
    for (int i = 0; i <= 400; ++i) {
      const double u = std::log(0.001 / 0.999) + (std::log(0.9999 / 0.0001) - std::log(0.001 / 0.999)) * i / 400;
      const double ap = std::clamp(1 / (1 + std::exp(-u)), 0.001, 0.9999);
      const double total = exact_total(table(), ap, p.g, p.eta);
      ASSERT_GT(total, previous) << ap;
      previous = total;
      EXPECT_NEAR(exact_albedo_prime_from_total(table(), total, p.g, p.eta) / ap, 1.0, 1e-7);
    }
  }
  EXPECT_THROW(exact_albedo_prime_from_total(table(), 1.001, 0.0, 1.3), InvalidInput);
  EXPECT_THROW(exact_albedo_prime_from_total(table(), 1e-9, 0.0, 1.3), InvalidInput);
}

namespace {

// The exact model against a fresh Monte Carlo run at p: total within 1 % or 3 standard errors,
// relative L2 of r R(r) within 3 % plus 3x the run's noise, inside and beyond one transport mfp.
void expect_agrees_with_monte_carlo(const Point& p, std::uint64_t photons, std::uint64_t seed, std::size_t bins) {
  const auto model = make_model("exact");
  const Medium medium = Medium::single_channel(1 - p.albedo_prime, p.albedo_prime / (1 - p.g), p.g, p.eta);
  const auto m = medium.reduced(0);
  MonteCarloOptions options;
  options.photons = photons;
  options.seed = seed;
  options.spacing = BinSpacing::log;
  options.bins = bins;
  options.r_max = model->radius_for_fraction(m, 0.999);
  options.r_min = 1e-3;
  const auto mc = run_monte_carlo(LayerStack::half_space(medium), options);
  const auto d = compare_with_monte_carlo(*model, m, mc);
  const auto entered = mc.channels[0].per_entered_flux();
  const double sigma = d.total * entered.diffuse_reflectance.value / entered.diffuse_reflectance.standard_error;
  EXPECT_TRUE(std::abs(d.total) <= 0.01 || std::abs(sigma) <= 3)
      << p.albedo_prime << " " << p.g << " " << p.eta << ": total " << d.total << " (" << sigma << " sigma)";
  EXPECT_LE(d.near_r, 0.03 + 3 * d.near_r_noise) << p.albedo_prime << " " << p.g << " " << p.eta;
  EXPECT_LE(d.far_r, 0.03 + 3 * d.far_r_noise) << p.albedo_prime << " " << p.g << " " << p.eta;
  std::printf("alpha' %g g %g eta %g: total %+.3f %% (%.2f sigma), near L2 %.2f %% (noise %.2f), far %.2f %% (%.2f)\n",
              p.albedo_prime, p.g, p.eta, 100 * d.total, sigma, 100 * d.near_r, 100 * d.near_r_noise, 100 * d.far_r,
              100 * d.far_r_noise);
}

}  // namespace

TEST(ExactModel, AgreesWithFreshMonteCarloOffTheGrid) {
  // Random points in the part of the domain a CI run can afford (g <= 0.9, alpha' <= 0.995).
  for (const Point& p : random_points(3, 2027, 0.05, 0.995, 0.9)) expect_agrees_with_monte_carlo(p, 100000, 31, 60);
}

TEST(ExactModel, BelowTheFirstAlbedoNodeContinuesExactly) {
  // Below alpha' 0.001: exact single scattering plus multiple scattering from the first two nodes
  // (read at the medium's rho = sigma_t r, ln(MS / alpha^2) linear in alpha). Continuous at the node,
  // zero without scattering, and equal to fresh Monte Carlo (cheap here: few scatterings per photon)
  // within its noise.
  const double a0 = table().albedo_prime.front();
  for (double g : {0.0, 0.7, 0.97}) {
    EXPECT_NEAR(exact_total(table(), a0 * (1 - 1e-9), g, 1.33) / exact_total(table(), a0, g, 1.33), 1.0, 1e-6);
    const ExactProfile below(table(), a0 * (1 - 1e-9), g, 1.33), at(table(), a0, g, 1.33);
    for (double r : {0.01, 0.3, 3.0}) EXPECT_NEAR(below.reflectance(r) / at.reflectance(r), 1.0, 1e-5) << g << " " << r;
  }
  const ExactProfile none(table(), 0.0, 0.5, 1.3);
  EXPECT_EQ(none.total(), 0.0);
  EXPECT_EQ(none.reflectance(0.5), 0.0);
  EXPECT_EQ(none.cumulative(0.5), 0.0);
  EXPECT_EQ(exact_total(table(), 0.0, 0.5, 1.3), 0.0);

  for (const Point& p : {Point{2e-4, 0.5, 1.33}, Point{6e-4, 0.95, 1.2}, Point{5e-5, 0.0, 1.0}})
    expect_agrees_with_monte_carlo(p, 20000000, 37, 40);
}

TEST(ExactModel, BelowTheFirstAlbedoNodeATotalWithoutMeasurableMultipleScatteringStaysFinite) {
  // A first albedo node low enough that its multiple scattering (~1e-4 of the total at alpha' 9e-5,
  // g 0.74: generator version 7) is below the rounding of the interpolated single scattering: here
  // every first-node total is set 0.1 % below its exact single scattering. The medium below it then
  // gets its single scattering alone (it was NaN, and radius_for_fraction's bracket failed).
  ExactTable low = table();
  const double a0 = low.albedo_prime.front();
  for (std::size_t e = 0; e < low.ln_total_eta().size(); ++e)
    for (std::size_t gi = 0; gi < low.g.size(); ++gi) {
      const double g = low.g[gi], eta = low.ln_total_eta()[e];
      const double ss = 0.999 * single_scattering_total(albedo_from_reduced(a0, g), g, eta);
      (low.total_eta.empty() ? low.total : low.fine_total)[low.node(e, gi, 0)] = ss;
    }
  low.prepare();
  for (double g : {0.2, 0.737, 0.9})
    for (double ap : {0.5 * a0, 0.1 * a0}) {
      const double t = exact_total(low, ap, g, 1.291);
      EXPECT_NEAR(t / single_scattering_total(albedo_from_reduced(ap, g), g, 1.291), 1.0, 1e-12) << g << " " << ap;
      const ExactProfile p(low, ap, g, 1.291);
      EXPECT_TRUE(std::isfinite(p.total()) && p.total() > 0) << g << " " << ap;
      EXPECT_TRUE(std::isfinite(p.cumulative(2.0)) && p.cumulative(2.0) > 0) << g << " " << ap;
    }
}

TEST(ExactModel, BelowTheFirstAlbedoNodeTheLogGridChangesNothingAgainstThePerRadiusIntegral) {
  // The medium's single scattering at all radii at once (single_scattering_ln_y, relative error < 1e-6
  // on the table's grid) instead of 96-point Gauss-Legendre radius by radius (the generator's rule,
  // ~1e-9 where R_ss is not subnormal): the profile moves by no more than that bound, the total not at
  // all. Points off the ones the rule was tuned on; radii out to 50 mfp (R_ss far from subnormal for
  // eta <= 2).
  double worst = 0;
  for (double ap : {1e-4, 5e-4, 3e-5})
    for (const auto& [g, eta] : {std::pair{0.92, 1.0}, std::pair{0.97, 1.12}, std::pair{0.999, 1.6},
                                 std::pair{0.3, 2.0}, std::pair{0.95, 1.45}}) {
      const ExactProfile fast(table(), ap, g, eta), baseline(table(), ap, g, eta, SingleScatteringRadii::per_radius);
      EXPECT_EQ(fast.total(), baseline.total());
      for (double r = 2e-4; r < 50; r *= 1.13) {
        const double change = std::abs(fast.reflectance(r) / baseline.reflectance(r) - 1);
        worst = std::max(worst, change);
        EXPECT_LT(change, 1e-6) << ap << " " << g << " " << eta << " " << r;
        EXPECT_LT(std::abs(fast.cumulative(r) / baseline.cumulative(r) - 1), 1e-6) << ap << " " << g << " " << eta;
      }
    }
  std::printf("largest change of R(r): %.2e\n", worst);
}

TEST(ExactModelCli, ProfileServesTheExactModelAndRefusesOutsideItsTable) {
  const auto ok = run("profile --sigma-a 0.01 --sigma-s 2 --g 0.9 --eta 1.4 --model exact --radii 0.1,1,10 -f json");
  ASSERT_EQ(ok.status, 0) << ok.err;
  const auto doc = nlohmann::json::parse(ok.out);
  EXPECT_NE(ok.out.find("exact"), std::string::npos);
  const auto bad = run("profile --sigma-a 0.01 --sigma-s 2 --g 0.9995 --model exact --radii 0.1,1");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("g"), std::string::npos);
  EXPECT_EQ(bad.out, "");
}

TEST(ExactModel, AboveTheLastAlbedoNodeContinuesByDiffusionToOne) {
  // alpha' in (0.9999, 1]: the last node's profile times the classical dipole's ratio, and the total
  // 1 - T = c1 s + c2 s^2 in s = sqrt(1 - alpha') through the last two nodes to T(1) = 1.
  const double a0 = table().albedo_prime.back();
  for (const Point& p : {Point{0, 0.0, 1.0}, Point{0, 0.6, 1.33}, Point{0, 0.95, 1.5}, Point{0, 0.995, 1.2}}) {
    // Continuous at the node.
    EXPECT_NEAR(exact_total(table(), a0 * (1 + 1e-12), p.g, p.eta) / exact_total(table(), a0, p.g, p.eta), 1.0, 1e-9);
    const ExactProfile above(table(), a0 + 1e-12, p.g, p.eta), at(table(), a0, p.g, p.eta);
    for (double r : {0.01, 1.0, 100.0}) EXPECT_NEAR(above.reflectance(r) / at.reflectance(r), 1.0, 1e-6) << r;
    // No absorption: a half-space returns all the light that entered.
    EXPECT_DOUBLE_EQ(exact_total(table(), 1.0, p.g, p.eta), 1.0);
    const ExactProfile one(table(), 1.0, p.g, p.eta);
    EXPECT_NEAR(one.cumulative(1e7), 1.0, 1e-6);
    // Monotone in alpha' up to 1, and the inversion returns the albedo.
    double previous = exact_total(table(), a0, p.g, p.eta);
    for (double loss : {5e-5, 1e-5, 1e-6, 1e-7, 1e-9}) {
      const double total = exact_total(table(), 1 - loss, p.g, p.eta);
      EXPECT_GT(total, previous) << loss;
      previous = total;
      EXPECT_NEAR((1 - exact_albedo_prime_from_total(table(), total, p.g, p.eta)) / loss, 1.0, 1e-6) << loss;
    }
  }
  // The totals against fresh adding-doubling, which converges here (g < 0.99): the s-law holds to
  // its second order (measured: within 3e-5 relative at eta <= 1.6, 1.5e-4 at eta 2; the goal is 1 %).
  double worst = 0;
  for (double g : {0.0, 0.5, 0.9})
    for (double eta : {1.0, 1.3, 1.6, 2.0})
      for (double loss : {5e-5, 1e-5, 1e-6}) {
        double error_estimate = 0;
        const double reference = adding_doubling_total(1 - loss, g, eta, &error_estimate);
        ASSERT_LT(error_estimate, 1e-5 * reference);  // a tenth of the tolerance below
        const double ratio = exact_total(table(), 1 - loss, g, eta) / reference;
        worst = std::max(worst, std::abs(ratio - 1));
        EXPECT_NEAR(ratio, 1.0, eta <= 1.6 ? 1e-4 : 2e-4) << g << " " << eta << " " << loss;
      }
  std::printf("totals above the last albedo node vs adding-doubling: worst %.2g relative\n", worst);
  // The profile against fresh Monte Carlo (the long run: tools/validation/exact_vs_montecarlo.txt).
  expect_agrees_with_monte_carlo({0.99995, 0.3, 1.3}, 40000, 41, 40);
}

TEST(ExactModel, BetweenTheStronglyForwardGNodesTotalsMatchAddingDoubling) {
  // g in (0.99, 0.999]: the nodes 0.995 and 0.999 (generator version 6), 0.999 the domain's end.
  EXPECT_EQ(table().g.back(), 0.999);
  // Totals against fresh adding-doubling where it converges (measured: within 0.1 %).
  int compared = 0;
  for (double g : {0.993, 0.996, 0.999})
    for (double ap : {0.3, 0.8, 0.99, 0.9995})
      for (double eta : {1.0, 1.4}) {
        double error_estimate = 0;
        const double reference = adding_doubling_total(ap, g, eta, &error_estimate);
        if (error_estimate > 2e-4 * reference) continue;
        ++compared;
        EXPECT_NEAR(exact_total(table(), ap, g, eta) / reference, 1.0, 3e-3) << ap << " " << g << " " << eta;
      }
  EXPECT_GE(compared, 16);
  expect_agrees_with_monte_carlo({0.8, 0.995, 1.33}, 20000, 43, 40);
}
