// Row-by-row inversion of an .rxt file; see include/bssrdf/fit/rxt_fit.hpp.
#include "bssrdf/fit/rxt_fit.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <vector>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/integrating_sphere.hpp"
#include "bssrdf/montecarlo.hpp"
#include "constrained_search.hpp"
#include "iad_search_edge.hpp"
#include "slab_inversion.hpp"

namespace bssrdf {

namespace {

adding_doubling::Slab slab_of(const RxtSetup& f, double sigma_a, double sigma_s, double g, double thickness) {
  adding_doubling::Slab slab;
  slab.layers = {{sigma_a, sigma_s, g, thickness}};
  slab.n = f.sample_n;
  if (f.has_slides())
    slab.above = slab.below = {{f.slide_n, f.slide_thickness, f.slide_optical_depth / f.slide_thickness}};
  return slab;
}

// The sample's totals (with its unscattered parts) for the spheres' equations.
SampleTotals sample_totals(const RxtSetup& f, const adding_doubling::Slab& slab, int points, double ur1_lost = 0,
                           double ut1_lost = 0) {
  adding_doubling::Options ad;
  ad.points = points;
  ad.incidence_cosine = f.incidence_degrees == 0 ? 1.0 : std::cos(f.incidence_degrees * M_PI / 180);
  using adding_doubling::Incidence;
  const auto both = adding_doubling::solve(
      slab, f.spheres > 0 ? std::vector{Incidence::collimated, Incidence::diffuse} : std::vector{Incidence::collimated},
      ad);
  const auto& c = both[0];
  SampleTotals t{c.specular_reflectance + c.diffuse_reflectance - ur1_lost,
                 c.total_transmittance - ut1_lost,
                 0,
                 0,
                 c.unscattered_reflectance,
                 c.unscattered_transmittance};
  if (f.spheres > 0) {
    t.uru = both[1].specular_reflectance + both[1].diffuse_reflectance;
    t.utu = both[1].total_transmittance;
  }
  return t;
}

// What the row's instrument would report for a sample with these parameters: M_R, M_T, M_U.
std::array<double, 3> predicted_measurements(const RxtSetup& f, const SphereModel& model, const SlabParameters& p,
                                             int points, double ur1_lost = 0, double ut1_lost = 0) {
  const auto t = sample_totals(f, slab_of(f, p.sigma_a, p.sigma_s_prime / (1 - p.g), p.g, f.sample_thickness), points,
                               ur1_lost, ut1_lost);
  const auto [m_r, m_t] = sphere_measurements(f, model, t);
  return {m_r, m_t, t.tu};
}

// Why iad would not solve the row (its measure_OK), or "" when it would.
std::string unreachable(const RxtRow& row, const SphereModel& model, int points) {
  const auto& f = row.setup;
  auto outside = [](const char* what, double v, const std::string& range) {
    return std::string(what) + " = " + format_number(v) + ": accepted range is " + range;
  };
  if (!(row.m_r >= 0 && row.m_r <= 1)) return outside("M_R", row.m_r, "[0, 1]");
  if (!(row.m_t >= 0 && row.m_t <= 1)) return outside("M_T", row.m_t, "[0, 1]");
  if (!(row.m_u >= 0)) return outside("M_U", row.m_u, ">= 0");
  const double C = std::isnan(model.unscattered_in_m_t) ? f.unscattered_in_m_t : model.unscattered_in_m_t;
  if (row.m_t > 0 && C * row.m_u > row.m_t)
    return outside("M_U", row.m_u, "<= M_T / C = " + format_number(row.m_t / C));
  if (f.spheres == 0 && row.m_r + row.m_t > 1)
    return outside("M_R + M_T", row.m_r + row.m_t, "<= 1 (more light out than in)");
  if (f.spheres != 2) {
    // A clear sample (no scattering, no absorption) transmits the most.
    const auto clear = sphere_measurements(f, model, sample_totals(f, slab_of(f, 0, 0, 0, f.sample_thickness), points));
    if (row.m_t > clear.second)
      return outside("M_T", row.m_t, "<= " + format_number(clear.second) + " (a clear sample's reading)");
    // A black half-space reflects the least.
    const auto black = sphere_measurements(f, model, sample_totals(f, slab_of(f, 1, 0, 0, kSemiInfinite), points));
    if (row.m_u == 0 && row.m_r < black.first)
      return outside("M_R", row.m_r, ">= " + format_number(black.first) + " (a black sample's reading)");
  }
  return "";
}

// M_R alone: a semi-infinite sample of albedo a, mu_s = 1/mm (iad's FIND_A with b = infinity).
double albedo_of_half_space(const RxtSetup& f, const SphereModel& model, double g, double m_r, int points) {
  auto reading = [&](double a) {
    return sphere_measurements(f, model, sample_totals(f, slab_of(f, 1 - a, a, g, kSemiInfinite), points)).first;
  };
  double lo = 0, hi = 1 - 1e-9;
  if (m_r >= reading(hi)) return hi;
  for (int k = 0; k < 60 && hi - lo > 1e-12; ++k) {
    const double mid = 0.5 * (lo + hi);
    (reading(mid) < m_r ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Diffuse light leaving beyond the sample ports (reflection, transmission), per incident flux,
// from the Monte Carlo reference at the parameters p (pencil beam at the port's centre).
std::pair<double, double> lost_light(const RxtSetup& f, const SlabParameters& p, std::uint64_t photons) {
  LayerStack stack;
  stack.channel_names = {"x"};
  Layer sample;
  sample.n = f.sample_n;
  sample.thickness = f.sample_thickness;
  sample.sigma_a = {p.sigma_a};
  sample.sigma_s = {p.sigma_s_prime / (1 - p.g)};
  sample.g = {p.g};
  Layer slide;
  slide.n = f.slide_n;
  slide.thickness = f.slide_thickness;
  slide.sigma_a = slide.sigma_s = slide.g = {0.0};
  if (f.has_slides()) stack.layers.push_back(slide);
  stack.layers.push_back(sample);
  if (f.has_slides()) stack.layers.push_back(slide);
  const double r_port = f.reflection.sample_port / 2, t_port = f.transmission.sample_port / 2;
  MonteCarloOptions options;
  options.photons = photons;
  options.bins = 400;
  options.r_max = std::max(r_port, t_port);
  const auto result = run_monte_carlo(stack, options);
  const auto& ch = result.channels[0];
  double r_in = 0, t_in = 0;
  for (std::size_t k = 0; k < result.bin_outer.size(); ++k) {
    const double area = M_PI * (result.bin_outer[k] * result.bin_outer[k] - result.bin_inner[k] * result.bin_inner[k]);
    if (result.bin_outer[k] <= r_port * (1 + 1e-12)) r_in += ch.reflectance[k] * area;
    if (result.bin_outer[k] <= t_port * (1 + 1e-12)) t_in += ch.transmittance[k] * area;
  }
  return {std::max(0.0, ch.diffuse_reflectance.value - r_in), std::max(0.0, ch.total_transmittance.value - t_in)};
}

}  // namespace

RxtFit fit_rxt(const RxtFile& input, const RxtFitOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RxtFile file = input;  // iad's -i sets every row's angle of incidence (over the column i)
  if (!std::isnan(options.incidence_degrees))
    for (auto& row : file.rows) row.setup.incidence_degrees = options.incidence_degrees;
  if (!std::isnan(options.g) && !(options.g > -1 && options.g < 1))
    throw InvalidInput("g", format_number(options.g), "-1 < g < 1");
  const auto& held = options.constraints;
  if (!std::isnan(held.mu_s_prime) && (!std::isnan(held.mu_s) || !std::isnan(held.power_mu_s0)))
    throw InvalidInput("--fixed-mu-s-prime with --fixed-mu-s: give one (both fix mu_s)");
  if (!std::isnan(held.power_mu_s0) && !(held.power_lambda0 > 0 && std::isfinite(held.power_gamma)))
    throw InvalidInput("--fixed-mu-s power law 'P lambda0 mu_s0 gamma'", format_number(held.power_lambda0),
                       "lambda0 > 0 and a finite gamma");
  for (double s : {options.reflectance_stderr, options.transmittance_stderr, options.unscattered_stderr})
    if (!(s > 0 && s < 1)) throw InvalidInput("measurement standard error", format_number(s), "(0, 1)");
  if (options.lost_light && file.spheres == 0)
    throw InvalidInput("lost-light correction", "on", "a file with 1 or 2 spheres (the sample port sets what is lost)");
  if (options.lost_light && !(file.reflection.sample_port > 0 && file.transmission.sample_port > 0))
    throw InvalidInput("sample port diameter", "0", "> 0 for the lost-light correction");
  if (options.lost_light && !(options.lost_light_photons >= 1000 && options.lost_light_photons <= 100'000'000))
    throw InvalidInput("lost-light photons", std::to_string(options.lost_light_photons), "1000 to 1e8");
  if (!(options.quadrature == 0 || (options.quadrature >= 4 && options.quadrature <= 256)))
    throw InvalidInput("quadrature points", std::to_string(options.quadrature), "4 to 256 (0: automatic)");
  const auto& model = options.sphere;
  for (double v : {model.wall_first, model.detector_reflectance})
    if (!(v >= 0 && v <= 1))
      throw InvalidInput("wall-first fraction / detector reflectance", format_number(v), "[0, 1]");
  for (double v : {model.unscattered_in_m_r, model.unscattered_in_m_t})
    if (!std::isnan(v) && !(v >= 0 && v <= 1)) throw InvalidInput("unscattered fraction", format_number(v), "[0, 1]");
  if (model.dual_beam && model.wall_first != 0)
    throw InvalidInput("wall-first fraction", format_number(model.wall_first), "0 with the dual-beam method (as iad)");
  // What we do not model: refused with the feature's name (docs/rxt.md lists them).
  for (const auto& row : file.rows) {
    auto refuse = [&](const std::string& what, const std::string& value, const std::string& accepted) {
      throw FileError(file.name, row.line, what + " = " + value + ": supported is " + accepted);
    };
    if (!(row.setup.incidence_degrees >= 0 && row.setup.incidence_degrees < 90))
      refuse("angle of incidence (column i or -i)", format_number(row.setup.incidence_degrees),
             "0 to below 90 degrees (grazing light does not enter)");
    if (options.lost_light && row.setup.incidence_degrees != 0)
      refuse("angle of incidence (column i) with the lost-light correction", format_number(row.setup.incidence_degrees),
             "0 degrees (the Monte Carlo beam is normal)");
    row_constraint(row, held, options.g);  // refuses two constraints at once or a power law without wavelength
  }
  RxtFit out;
  out.file = file;
  out.options = options;
  // The starting grid of invert_slab is the same for every row with the same setup and g: its
  // readings are kept across rows (iad keeps a grid too), which saves 30 solves per row.
  std::map<std::vector<double>, std::array<double, 3>> grid;
  for (const auto& row : file.rows) {
    const RxtSetup& setup = row.setup;
    const double g_given = std::isnan(row.constraints.g) ? options.g : row.constraints.g;  // NaN: not given
    const double g = std::isnan(g_given) ? 0.0 : g_given;
    const auto constraint = row_constraint(row, held, options.g);
    int points = row.constraints.quadrature > 0 ? row.constraints.quadrature : options.quadrature;
    // iad's oblique incidence (ad_cone.w RT_Cone) takes a multiple of 12 angles, at least 12.
    if (points > 0 && setup.incidence_degrees != 0) points = std::max(12, 12 * (points / 12));
    const int final_points = points > 0 ? points : 32;
    RxtRowFit fit;
    fit.row = row;
    fit.g = g;
    if (const auto why = unreachable(row, model, final_points); !why.empty()) {
      fit.status = "not solved: " + why;
      out.rows.push_back(fit);
      continue;
    }
    if (constraint && row.m_u > 0) {
      fit.status = "not solved: " + constraint->label +
                   " with M_U: M_R, M_T, M_U determine a, b, g (iad ignores the constraint then); drop one";
      out.rows.push_back(fit);
      continue;
    }
    if (!constraint && row.m_t == 0 && row.m_u == 0) {  // M_R alone
      const double a = albedo_of_half_space(setup, model, g, row.m_r, final_points);
      fit.mu_a = (1 - a) / a;
      fit.mu_s_prime = 1 - g;
      fit.fitted_m_r = row.m_r;
      fit.converged = true;
      fit.status = "M_R only: a semi-infinite sample, mu_s = 1/mm by convention (iad's); mu_a / mu_s is the result";
      out.rows.push_back(fit);
      continue;
    }
    const bool with_u = row.m_u > 0;
    const double u_stderr = options.unscattered_stderr;
    double ur1_lost = 0, ut1_lost = 0;
    auto forward_at = [&](int n) {
      return SlabForward(
          [&, n](const SlabParameters& p) { return predicted_measurements(setup, model, p, n, ur1_lost, ut1_lost); });
    };
    const SlabForward forward = forward_at(final_points);
    const SlabForward coarse_solve = forward_at(std::min(final_points, 8));
    const SlabForward coarse = [&](const SlabParameters& p) {
      const auto& r = setup.reflection;
      const auto& x = setup.transmission;
      std::vector<double> key{setup.sample_n,
                              setup.slide_n,
                              setup.sample_thickness,
                              setup.slide_thickness,
                              setup.slide_optical_depth,
                              setup.standard_reflectance,
                              setup.standard_transmittance,
                              double(setup.spheres),
                              r.diameter,
                              r.sample_port,
                              r.third_port,
                              r.detector_port,
                              r.wall_reflectance,
                              x.diameter,
                              x.sample_port,
                              x.third_port,
                              x.detector_port,
                              x.wall_reflectance,
                              setup.unscattered_in_m_r,
                              setup.unscattered_in_m_t,
                              setup.incidence_degrees,
                              ur1_lost,
                              ut1_lost,
                              p.sigma_a,
                              p.sigma_s_prime,
                              p.g,
                              double(std::min(final_points, 8))};
      const auto found = grid.find(key);
      return found != grid.end() ? found->second : grid.emplace(key, coarse_solve(p)).first->second;
    };
    // With the points fixed the search runs on the final forward itself: Ceres then differentiates
    // forwards (p + 1 solves per Jacobian instead of 2p + 1) and the polish only confirms.
    const SlabForward search = points > 0 ? forward : forward_at(16);
    const SampleReadings readings = [&](double sigma_a, double sigma_s, double g_at, double d) {
      return sphere_measurements(
          setup, model,
          sample_totals(setup, slab_of(setup, sigma_a, sigma_s, g_at, d), final_points, ur1_lost, ut1_lost));
    };
    auto invert = [&] {
      if (constraint) {
        auto solved = solve_constrained(*constraint, row.m_r, row.m_t, options.reflectance_stderr,
                                        options.transmittance_stderr, g_given, setup.sample_thickness, readings);
        fit.constraint = solved.search;
        return solved.inversion;
      }
      return invert_slab({row.m_r, row.m_t, with_u ? row.m_u : 0.0},
                         {options.reflectance_stderr, options.transmittance_stderr, u_stderr}, with_u ? 3 : 2, with_u,
                         g, setup.sample_thickness, forward, coarse, &search);
    };
    auto r = invert();
    // Losses at the estimate, refit, until they settle: a fixed-point iteration L = F(L) that
    // converges linearly (ratio ~0.65 measured), accelerated per component by extrapolating with
    // the observed ratio rho of successive changes, L + (F(L) - L)/(1 - rho) (Aitken).
    double previous_change[2] = {0, 0};
    for (int pass = 0; options.lost_light && pass < 20; ++pass) {
      const auto [r_lost, t_lost] = lost_light(setup, r.parameters, options.lost_light_photons);
      const double change[2] = {r_lost - ur1_lost, t_lost - ut1_lost};
      double* lost[2] = {&ur1_lost, &ut1_lost};
      for (int k = 0; k < 2; ++k) {
        const double rho = previous_change[k] != 0 ? change[k] / previous_change[k] : 0;
        *lost[k] += rho > 0 && rho < 0.9 ? change[k] / (1 - rho) : change[k];
        *lost[k] = std::max(0.0, *lost[k]);
        previous_change[k] = change[k];
      }
      r = invert();
      if (std::abs(change[0]) < 1e-4 && std::abs(change[1]) < 1e-4) break;
    }
    fit.mu_a = r.parameters.sigma_a;
    fit.mu_s_prime = r.parameters.sigma_s_prime;
    fit.g = r.parameters.g;
    fit.mu_a_stderr = r.standard_error[0];
    fit.mu_s_prime_stderr = r.standard_error[1];
    fit.g_stderr = with_u || constraint ? r.standard_error[2] : 0;
    fit.fitted_m_r = r.predicted[0];
    fit.fitted_m_t = r.predicted[1];
    fit.fitted_m_u = with_u ? r.predicted[2] : -1;
    fit.chi2 = r.chi2;
    fit.ur1_lost = ur1_lost;
    fit.ut1_lost = ut1_lost;
    // A solution on the boundary (no absorption or no scattering, as iad reports it): the other
    // parameter is then determined although the Jacobian in the logarithms is singular.
    const bool on_boundary =
        !r.determined && r.chi2 <= 4 && std::min(fit.mu_a, fit.mu_s_prime) < 1e-6 * std::max(fit.mu_a, fit.mu_s_prime);
    if (on_boundary) (fit.mu_a < fit.mu_s_prime ? fit.mu_a : fit.mu_s_prime) = 0;
    if (on_boundary) r.determined = true;
    fit.converged = r.converged && r.chi2 <= 4 && r.determined;
    if (!r.converged)
      fit.status = "not converged (" + r.termination + ")";
    else if (r.chi2 > 4)
      fit.status = "no parameters reproduce M_R, M_T within their errors (chi^2 " +
                   format_number(std::round(r.chi2 * 10) / 10) + ")";
    else if (!r.determined)
      fit.status = "not unique: the measurements do not separate absorption from scattering";
    else
      fit.status = constraint ? "converged" : converged_status(fit.mu_a, fit.mu_s_prime, fit.g, fit.chi2);
    out.rows.push_back(fit);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace bssrdf
