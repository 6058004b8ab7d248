#include "bssrdf/lut/albedo_radius_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fresnel.hpp"
#include "bssrdf/lut/interpolation.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/models/photon_beam_diffusion.hpp"
#include "bssrdf/parallel.hpp"
#include "bssrdf/scalar_math.hpp"
#include "bssrdf/single_scattering.hpp"
#include "bssrdf/transport_total.hpp"

namespace bssrdf {
namespace {

// Integral of the Catmull-Rom spline through (x_j, f_j): per interval h (f0 + f1)/2 + h^2 (d0 - d1)/12
// with the spline's slopes d (centred differences, one-sided at the ends). cumulative[j] at x_j.
std::vector<double> catmull_rom_cumulative(const std::vector<double>& x, const double* f) {
  const std::size_t n = x.size();
  BSSRDF_CHECK(n >= 2);  // layouts have at least 4 radii
  const auto slope = [&](std::size_t j) {
    if (j == 0) return (f[1] - f[0]) / (x[1] - x[0]);
    if (j + 1 == n) return (f[n - 1] - f[n - 2]) / (x[n - 1] - x[n - 2]);
    return (f[j + 1] - f[j - 1]) / (x[j + 1] - x[j - 1]);
  };
  std::vector<double> cum(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double h = x[j + 1] - x[j];
    cum[j + 1] = cum[j] + h * (f[j] + f[j + 1]) / 2 + h * h * (slope(j) - slope(j + 1)) / 12;
  }
  return cum;
}

}  // namespace

AlbedoRadiusLayout AlbedoRadiusLayout::pbrt() {
  AlbedoRadiusLayout l;
  for (int i = 0; i < 100; ++i) l.albedo.push_back((1 - std::exp(-8.0 * i / 99.0)) / (1 - std::exp(-8.0)));
  l.radius.push_back(0);
  l.radius.push_back(0.0025);
  for (int j = 2; j < 64; ++j) l.radius.push_back(l.radius.back() * 1.2);
  return l;
}

AlbedoRadiusLayout AlbedoRadiusLayout::family(std::size_t albedos, std::size_t radii, double r_max) {
  if (albedos < 4 || radii < 4)
    throw InvalidInput("table size", std::to_string(albedos) + " x " + std::to_string(radii), ">= 4 x 4");
  AlbedoRadiusLayout l;
  const double a = static_cast<double>(albedos - 1);
  for (std::size_t i = 0; i < albedos; ++i) l.albedo.push_back((1 - std::exp(-8.0 * i / a)) / (1 - std::exp(-8.0)));
  const double ratio = std::pow(r_max / 0.0025, 1.0 / static_cast<double>(radii - 2));
  l.radius.push_back(0);
  l.radius.push_back(0.0025);
  for (std::size_t j = 2; j < radii; ++j) l.radius.push_back(l.radius.back() * ratio);
  return l;
}

AlbedoRadiusTable build_albedo_radius_table(const AlbedoRadiusLayout& layout, double g, double eta,
                                            const AlbedoRadiusOptions& options) {
  if (!(options.tolerance > 0 && options.tolerance < 1))
    throw InvalidInput("tolerance", format_number(options.tolerance), "0 < tolerance < 1");
  if (!(g > -1 && g < 1)) throw InvalidInput("g", format_number(g), "-1 < g < 1");
  if (!(eta > 0) || !std::isfinite(eta)) throw InvalidInput("eta", format_number(eta), "> 0 and finite");
  const auto start = std::chrono::steady_clock::now();
  AlbedoRadiusTable t;
  t.tolerance = options.tolerance;
  t.g = g;
  t.eta = eta;
  t.layout = layout;
  const std::size_t rows = t.rows(), cols = t.columns();
  const auto b = improved_boundary(eta);

  // One quadrature order for the table: the largest any of a few albedos needs (optical units).
  for (double rho : {0.3, 0.9, 0.99, 0.999})
    t.quadrature_order = std::max(t.quadrature_order, photon_beam_diffusion::samples_for_tolerance(
                                                          reduced_albedo(rho, g), g, eta, options.tolerance));

  // Single scattering with sigma_t = 1 is rho * S(r): one integral per column.
  const auto unit_scattering = reduce(0.0, 1.0, g, eta);
  std::vector<double> single(cols, 0.0);
  for (std::size_t j = 0; j < cols; ++j)
    if (layout.radius[j] > 0)
      single[j] = kTwoPi * layout.radius[j] *
                  single_scattering_reflectance(unit_scattering, layout.radius[j], t.quadrature_order);

  BSSRDF_CHECK(rows >= 1 && cols >= 2 && std::is_sorted(layout.radius.begin(), layout.radius.end()));
  const double single_integral = catmull_rom_cumulative(layout.radius, single.data()).back();
  t.profile.assign(rows * cols, 0.0);
  t.cdf.assign(rows * cols, 0.0);
  t.effective_albedo.assign(rows, 0.0);
  t.energy = options.energy;
  std::vector<double> scale(rows, std::numeric_limits<double>::quiet_NaN());  // NaN: row not scaled
  std::vector<char> at_model_energy(rows, 0), exact_row(rows, 0);
  t.shape = options.shape;
  const auto exact = make_exact_model();
  const ExactTable& exact_table = bundled_exact_table();
  parallel_for(rows, options.threads, [&](std::size_t i) {
    const double rho = layout.albedo[i];
    const auto m = reduced_unit_extinction(rho, g, eta);
    double* row = &t.profile[i * cols];
    exact_row[i] =
        options.shape == RowShape::exact && rho > 0 && exact_domain(exact_table, m.albedo_prime, m.g, m.eta).empty();
    for (std::size_t j = 0; j < cols && exact_row[i]; ++j) {
      const double r = layout.radius[j];
      row[j] = r > 0 ? kTwoPi * r * exact->reflectance(m, r) : 0.0;  // 2 pi r R -> 2 pi r R_ss, finite
    }
    for (std::size_t j = 0; j < cols && !exact_row[i]; ++j) {
      const double r = layout.radius[j];
      // 2 pi r R vanishes at r = 0 (R_ms is finite there; R_ss ~ 1/r is handled by the column factor).
      row[j] = rho * single[j] +
               (r > 0 && rho > 0 ? kTwoPi * r * photon_beam_diffusion::multiple_scattering(m, b, r, t.quadrature_order)
                                 : 0.0);
    }
    auto cum = catmull_rom_cumulative(layout.radius, row);
    if (options.energy == RowEnergy::transport && cum.back() > 0) {
      const auto total = transport_total(m);
      // pbd's single scattering is exact: only its multiple scattering is scaled (which also keeps
      // the rows linear in rho near rho = 0, where single scattering dominates, so they
      // interpolate as well as before). Exact rows are scaled whole (by ~1).
      const double single_energy = exact_row[i] ? 0.0 : rho * single_integral;
      const double multiple_energy = cum.back() - single_energy;
      if (total.reliable() && multiple_energy > 0 && total.value > single_energy) {
        scale[i] = (total.value - single_energy) / multiple_energy;
        for (std::size_t j = 0; j < cols; ++j) {
          const double single_part = exact_row[i] ? 0.0 : rho * single[j];
          row[j] = single_part + scale[i] * (row[j] - single_part);
        }
        cum = catmull_rom_cumulative(layout.radius, row);
        cum.back() = total.value;  // equal up to rounding: exactly the total (never above 1)
      } else {
        at_model_energy[i] = 1;
      }
    }
    t.effective_albedo[i] = cum.back();
    for (std::size_t j = 0; j < cols; ++j) t.cdf[i * cols + j] = cum.back() > 0 ? cum[j] / cum.back() : 0.0;
  });
  if (options.energy == RowEnergy::transport) {
    std::vector<double> applied;
    for (double f : scale)
      if (std::isfinite(f)) applied.push_back(f);
    if (!applied.empty()) {
      t.smallest_scale = *std::min_element(applied.begin(), applied.end());
      t.largest_scale = *std::max_element(applied.begin(), applied.end());
    }
    t.rows_at_model_energy = static_cast<std::size_t>(std::count(at_model_energy.begin(), at_model_energy.end(), 1));
  }
  t.exact_rows = static_cast<std::size_t>(std::count(exact_row.begin(), exact_row.end(), 1));
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

namespace {

// Worst |interpolated - direct| / row peak at the given (albedo, radius) points, where `direct` is a
// table built at exactly those points (rows = albedos, columns = radii).
double midpoint_error(const AlbedoRadiusTable& table, const AlbedoRadiusTable& direct) {
  double worst = 0;
  for (std::size_t i = 0; i < direct.rows(); ++i) {
    double peak = 0;
    for (std::size_t j = 0; j < direct.columns(); ++j) peak = std::max(peak, direct.profile[i * direct.columns() + j]);
    if (!(peak > 0)) continue;
    for (std::size_t j = 0; j < direct.columns(); ++j) {
      const double interpolated = table.interpolate(direct.layout.albedo[i], direct.layout.radius[j]);
      worst = std::max(worst, std::abs(interpolated - direct.profile[i * direct.columns() + j]) / peak);
    }
  }
  return worst;
}

// Midpoints of the intervals; geometric ones for radii, skipping the first interval [0, r_1]
// (pbrt's r = 0 column, which carries no energy: 2 pi r R vanishes there).
std::vector<double> midpoints(const std::vector<double>& x, bool geometric) {
  std::vector<double> m;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    if (geometric && x[i] == 0) continue;
    m.push_back(geometric ? std::sqrt(x[i] * x[i + 1]) : 0.5 * (x[i] + x[i + 1]));
  }
  return m;
}

}  // namespace

AdaptiveAlbedoRadiusLayout adaptive_albedo_radius_layout(double g, double eta, double tolerance,
                                                         const AlbedoRadiusOptions& options) {
  if (!(tolerance > 0 && tolerance < 1))
    throw InvalidInput("table tolerance", format_number(tolerance), "0 < tolerance < 1");
  const auto grow = [](std::size_t n) { return n + std::max<std::size_t>(1, n / 4); };
  constexpr std::size_t kLargest = 2048;
  AdaptiveAlbedoRadiusLayout out;
  // Each axis's midpoint error is held to a third of the tolerance: errors off the grid in both
  // axes add, and the midpoint is not always the worst point of an interval (measured: 2x).
  const double target = tolerance / 3;
  AlbedoRadiusOptions table_options = options;
  table_options.progress = nullptr;
  constexpr std::uint64_t kMostSteps = 48;  // 12 * 1.25^24 > 2048 on each axis
  std::uint64_t step = 0;
  const auto stepped = [&] {
    if (options.progress) options.progress(std::min(++step, kMostSteps), kMostSteps);
  };
  // Radii first, on a few albedo rows spread over the range.
  const auto probe_rows = AlbedoRadiusLayout::family(9, 4).albedo;
  std::size_t radii = 12;
  for (;; radii = grow(radii)) {
    AlbedoRadiusLayout grid = AlbedoRadiusLayout::family(4, radii);
    grid.albedo = probe_rows;
    AlbedoRadiusLayout mid = grid;
    mid.radius = midpoints(grid.radius, true);
    out.radius_error = midpoint_error(build_albedo_radius_table(grid, g, eta, table_options),
                                      build_albedo_radius_table(mid, g, eta, table_options));
    stepped();
    if (out.radius_error <= target || radii >= kLargest) break;
  }
  // Then albedos, on the chosen radii.
  std::size_t albedos = 12;
  for (;; albedos = grow(albedos)) {
    AlbedoRadiusLayout grid = AlbedoRadiusLayout::family(albedos, radii);
    AlbedoRadiusLayout mid = grid;
    mid.albedo = midpoints(grid.albedo, false);
    out.albedo_error = midpoint_error(build_albedo_radius_table(grid, g, eta, table_options),
                                      build_albedo_radius_table(mid, g, eta, table_options));
    stepped();
    if (out.albedo_error <= target || albedos >= kLargest) break;
  }
  if (options.progress) options.progress(kMostSteps, kMostSteps);
  out.layout = AlbedoRadiusLayout::family(albedos, radii);
  return out;
}

double AlbedoRadiusTable::interpolate(double albedo, double r) const {
  const auto wa = catmull_rom_weights(layout.albedo, albedo);
  const auto wr = catmull_rom_weights(layout.radius, r);
  double sum = 0;
  for (int a = 0; a < 4; ++a) {
    const int i = wa.offset + a;
    if (i < 0 || i >= static_cast<int>(rows()) || wa.weight[a] == 0) continue;
    for (int k = 0; k < 4; ++k) {
      const int j = wr.offset + k;
      if (j < 0 || j >= static_cast<int>(columns()) || wr.weight[k] == 0) continue;
      sum +=
          wa.weight[a] * wr.weight[k] * profile[static_cast<std::size_t>(i) * columns() + static_cast<std::size_t>(j)];
    }
  }
  return sum;
}

double AlbedoRadiusTable::albedo_from_effective_albedo(double rho_eff) const {
  const auto at = [&](double a) { return bssrdf::interpolate(layout.albedo, effective_albedo, a); };
  double lo = layout.albedo.front(), hi = layout.albedo.back();
  if (rho_eff <= at(lo)) return lo;
  if (rho_eff >= at(hi)) return hi;
  for (int k = 0; k < 100 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    (at(mid) < rho_eff ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

std::string shape_text(const AlbedoRadiusTable& t) {
  if (t.shape == RowShape::pbd) return "photon beam diffusion";
  return "the exact model (radiative transfer) in " + std::to_string(t.exact_rows) + " of " + std::to_string(t.rows()) +
         " rows, photon beam diffusion outside its domain";
}

std::string energy_text(const AlbedoRadiusTable& t) {
  if (t.energy == RowEnergy::model) return "the model's own row integral (pbrt's construction)";
  return "the radiative-transfer total (exact model inside its domain, adding-doubling outside); rows scaled by " +
         format_number(std::round(t.smallest_scale * 1e4) / 1e4) + " to " +
         format_number(std::round(t.largest_scale * 1e4) / 1e4) + " from the model's integral" +
         (t.rows_at_model_energy
              ? "; " + std::to_string(t.rows_at_model_energy) + (t.rows_at_model_energy == 1 ? " row" : " rows") +
                    " at the model's integral (adding-doubling not converged)"
              : "");
}

}  // namespace

LookupTable to_lookup_table(const AlbedoRadiusTable& t, const TableContext& context, const std::string& layout_name) {
  LookupTable out;
  out.kind = "albedo-radius";
  out.width = t.columns();
  out.height = t.rows();
  describe(out, context);
  out.set("bssrdf:g", t.g);
  out.set("bssrdf:eta", t.eta);
  out.set("bssrdf:unit", std::string("mean free path 1/sigma_t (optical units, sigma_t = 1)"));
  out.set("bssrdf:distance",
          std::string("radius r on the surface from the point of incidence, in mean free paths 1/sigma_t (unreduced)"));
  out.set("bssrdf:normalization",
          std::string("per_entered_flux; profile = 2 pi r R(r) (multiple + single scattering)"));
  out.set("bssrdf:layout", layout_name);
  out.set("bssrdf:grid", layout_name == "pbrt"
                             ? std::string("rows: rho_i = (1 - exp(-8 i / 99)) / (1 - exp(-8)), i = 0..99; columns: "
                                           "r_0 = 0, r_1 = 0.0025, r_j = 1.2 r_{j-1}, j < 64")
                             : std::string("rows: rho_i = (1 - exp(-8 i / (n - 1))) / (1 - exp(-8)); columns: r_0 = 0, "
                                           "r_1 = 0.0025, geometric to r_max; see the albedo and radius channels"));
  out.set("bssrdf:interpolation", std::string("catmull-rom in albedo and in radius (pbrt's CatmullRomWeights)"));
  out.set("bssrdf:quadrature_order", t.quadrature_order);
  out.set("bssrdf:cdf",
          std::string("per row: Catmull-Rom integral of the profile from 0 to r_j over effective_albedo"));
  out.set("bssrdf:effective_albedo", energy_text(t));
  out.set("bssrdf:profile", shape_text(t));
  std::vector<double> radius, albedo, rho_eff;
  for (std::size_t i = 0; i < t.rows(); ++i)
    for (std::size_t j = 0; j < t.columns(); ++j) {
      radius.push_back(t.layout.radius[j]);
      albedo.push_back(t.layout.albedo[i]);
      rho_eff.push_back(t.effective_albedo[i]);
    }
  out.add_channel("profile", "2 pi r R(r) at (albedo row, radius column), per mean free path", t.profile);
  out.add_channel("cdf", "row CDF of the profile", t.cdf);
  out.add_channel("radius", "r, mean free paths (same in every row)", radius);
  out.add_channel("albedo", "single-scattering albedo rho = sigma_s / sigma_t of the row", albedo);
  out.add_channel("effective_albedo", "rho_eff = int 2 pi r R dr of the row (the albedo inversion table)", rho_eff);
  return out;
}

std::string summary(const AlbedoRadiusTable& t, const std::string& layout_name) {
  std::ostringstream s;
  s << "albedo-radius table (" << layout_name << " layout): " << t.rows() << " albedos x " << t.columns()
    << " radii, g = " << format_number(t.g) << ", eta = " << format_number(t.eta) << ", " << shape_text(t)
    << " (pbd: " << t.quadrature_order << "-point Gauss-Legendre, tolerance " << format_number(t.tolerance)
    << "); table in " << format_number(std::round(t.seconds * 1e5) / 100)
    << " ms\n  effective albedo: " << format_number(t.effective_albedo.front()) << " (rho = 0) to "
    << format_number(t.effective_albedo.back()) << " (rho = 1): " << energy_text(t) << "\n";
  if (t.shape == RowShape::pbd && t.energy == RowEnergy::transport &&
      (t.largest_scale > 1.5 || t.smallest_scale < 0.67))
    s << "  pbd's multiple scattering is off by more than 1.5x in some rows here: --model exact tabulates the "
         "radiative-transfer profile\n";
  return s.str();
}

std::string summary(const AdaptiveAlbedoRadiusLayout& layout, double table_tolerance) {
  return "adaptive layout for interpolation tolerance " + format_number(table_tolerance) + ": worst midpoint error " +
         format_number(std::round(layout.albedo_error * 1e6) / 1e6) + " (albedo), " +
         format_number(std::round(layout.radius_error * 1e6) / 1e6) + " (radius), relative to each row's peak";
}

}  // namespace bssrdf
