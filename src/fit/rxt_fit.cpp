// Row-by-row inversion of an .rxt file; see include/bssrdf/fit/rxt_fit.hpp.
#include "bssrdf/fit/rxt_fit.hpp"

#include <chrono>
#include <cmath>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/integrating_sphere.hpp"
#include "bssrdf/montecarlo.hpp"
#include "slab_inversion.hpp"

namespace bssrdf {

namespace {

// What the file's instrument would report for a sample with these parameters.
std::array<double, 3> predicted_measurements(const RxtFile& f, const SlabParameters& p, int points, double ur1_lost = 0,
                                             double ut1_lost = 0) {
  adding_doubling::Slab slab;
  slab.layers = {{p.sigma_a, p.sigma_s_prime / (1 - p.g), p.g, f.sample_thickness}};
  slab.n = f.sample_n;
  if (f.has_slides()) slab.above = slab.below = {{f.slide_n, f.slide_thickness, 0.0}};
  adding_doubling::Options ad;
  ad.points = points;
  using adding_doubling::Incidence;
  const auto both = adding_doubling::solve(
      slab, f.spheres > 0 ? std::vector{Incidence::collimated, Incidence::diffuse} : std::vector{Incidence::collimated},
      ad);
  const auto& c = both[0];
  SampleTotals t{c.specular_reflectance + c.diffuse_reflectance - ur1_lost, c.total_transmittance - ut1_lost, 0, 0};
  if (f.spheres > 0) {
    t.uru = both[1].specular_reflectance + both[1].diffuse_reflectance;
    t.utu = both[1].total_transmittance;
  }
  const auto [m_r, m_t] = sphere_measurements(f, t);
  return {m_r, m_t, c.unscattered_transmittance};
}

// Diffuse light leaving beyond the sample ports (reflection, transmission), per incident flux,
// from the Monte Carlo reference at the parameters p (pencil beam at the port's centre).
std::pair<double, double> lost_light(const RxtFile& f, const SlabParameters& p, std::uint64_t photons) {
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

RxtFit fit_rxt(const RxtFile& file, const RxtFitOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.g > -1 && options.g < 1)) throw InvalidInput("g", format_number(options.g), "-1 < g < 1");
  for (double s : {options.reflectance_stderr, options.transmittance_stderr, options.unscattered_stderr})
    if (!(s > 0 && s < 1)) throw InvalidInput("measurement standard error", format_number(s), "(0, 1)");
  if (options.lost_light && file.spheres == 0)
    throw InvalidInput("lost-light correction", "on", "a file with 1 or 2 spheres (the sample port sets what is lost)");
  if (options.lost_light && !(file.reflection.sample_port > 0 && file.transmission.sample_port > 0))
    throw InvalidInput("sample port diameter", "0", "> 0 for the lost-light correction");
  if (options.lost_light && !(options.lost_light_photons >= 1000 && options.lost_light_photons <= 100'000'000))
    throw InvalidInput("lost-light photons", std::to_string(options.lost_light_photons), "1000 to 1e8");
  RxtFit out;
  out.file = file;
  out.options = options;
  const bool with_u = file.measurements == 3;
  for (const auto& row : file.rows) {
    double ur1_lost = 0, ut1_lost = 0;
    const SlabForward forward = [&](const SlabParameters& p) {
      return predicted_measurements(file, p, 32, ur1_lost, ut1_lost);
    };
    const SlabForward coarse = [&](const SlabParameters& p) {
      return predicted_measurements(file, p, 8, ur1_lost, ut1_lost);
    };
    const SlabForward search = [&](const SlabParameters& p) {
      return predicted_measurements(file, p, 16, ur1_lost, ut1_lost);
    };
    auto invert = [&] {
      return invert_slab({row.m_r, row.m_t, with_u ? row.m_u : 0.0},
                         {options.reflectance_stderr, options.transmittance_stderr, options.unscattered_stderr},
                         with_u ? 3 : 2, with_u, options.g, file.sample_thickness, forward, coarse, &search);
    };
    auto r = invert();
    // Losses at the estimate, refit, until they settle: a fixed-point iteration L = F(L) that
    // converges linearly (ratio ~0.65 measured), accelerated per component by extrapolating with
    // the observed ratio rho of successive changes, L + (F(L) - L)/(1 - rho) (Aitken).
    double previous_change[2] = {0, 0};
    for (int pass = 0; options.lost_light && pass < 20; ++pass) {
      const auto [r_lost, t_lost] = lost_light(file, r.parameters, options.lost_light_photons);
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
    RxtRowFit fit;
    fit.row = row;
    fit.mu_a = r.parameters.sigma_a;
    fit.mu_s_prime = r.parameters.sigma_s_prime;
    fit.g = r.parameters.g;
    fit.mu_a_stderr = r.standard_error[0];
    fit.mu_s_prime_stderr = r.standard_error[1];
    fit.g_stderr = with_u ? r.standard_error[2] : 0;
    fit.fitted_m_r = r.predicted[0];
    fit.fitted_m_t = r.predicted[1];
    fit.fitted_m_u = with_u ? r.predicted[2] : -1;
    fit.chi2 = r.chi2;
    fit.ur1_lost = ur1_lost;
    fit.ut1_lost = ut1_lost;
    fit.converged = r.converged && r.chi2 <= 4 && r.determined;
    if (!r.converged)
      fit.status = "not converged (" + r.termination + ")";
    else if (r.chi2 > 4)
      fit.status = "no parameters reproduce M_R, M_T within their errors (chi^2 " +
                   format_number(std::round(r.chi2 * 10) / 10) + ")";
    else if (!r.determined)
      fit.status = "not unique: the measurements do not separate absorption from scattering";
    else
      fit.status = "converged";
    out.rows.push_back(fit);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace bssrdf
