// Row-by-row inversion of an .rxt file; see include/bssrdf/fit/rxt_fit.hpp.
#include "bssrdf/fit/rxt_fit.hpp"

#include <chrono>
#include <cmath>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/integrating_sphere.hpp"
#include "slab_inversion.hpp"

namespace bssrdf {

namespace {

// What the file's instrument would report for a sample with these parameters.
std::array<double, 3> predicted_measurements(const RxtFile& f, const SlabParameters& p, int points) {
  adding_doubling::Slab slab;
  slab.layers = {{p.sigma_a, p.sigma_s_prime / (1 - p.g), p.g, f.sample_thickness}};
  slab.n = f.sample_n;
  if (f.has_slides()) slab.above = slab.below = {{f.slide_n, f.slide_thickness, 0.0}};
  adding_doubling::Options ad;
  ad.points = points;
  using adding_doubling::Incidence;
  const auto both = adding_doubling::solve(
      slab, f.spheres > 0 ? std::vector{Incidence::collimated, Incidence::diffuse} : std::vector{Incidence::collimated}, ad);
  const auto& c = both[0];
  SampleTotals t{c.specular_reflectance + c.diffuse_reflectance, c.total_transmittance, 0, 0};
  if (f.spheres > 0) {
    t.uru = both[1].specular_reflectance + both[1].diffuse_reflectance;
    t.utu = both[1].total_transmittance;
  }
  const auto [m_r, m_t] = sphere_measurements(f, t);
  return {m_r, m_t, c.unscattered_transmittance};
}

}  // namespace

RxtFit fit_rxt(const RxtFile& file, const RxtFitOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.g > -1 && options.g < 1)) throw InvalidInput("g", format_number(options.g), "-1 < g < 1");
  for (double s : {options.reflectance_stderr, options.transmittance_stderr, options.unscattered_stderr})
    if (!(s > 0 && s < 1)) throw InvalidInput("measurement standard error", format_number(s), "(0, 1)");
  RxtFit out;
  out.file = file;
  out.options = options;
  const bool with_u = file.measurements == 3;
  for (const auto& row : file.rows) {
    const SlabForward forward = [&](const SlabParameters& p) { return predicted_measurements(file, p, 32); };
    const SlabForward coarse = [&](const SlabParameters& p) { return predicted_measurements(file, p, 8); };
    const SlabForward search = [&](const SlabParameters& p) { return predicted_measurements(file, p, 16); };
    const auto r = invert_slab({row.m_r, row.m_t, with_u ? row.m_u : 0.0},
                               {options.reflectance_stderr, options.transmittance_stderr, options.unscattered_stderr}, with_u ? 3 : 2,
                               with_u, options.g, file.sample_thickness, forward, coarse, &search);
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
    fit.converged = r.converged && r.chi2 <= 4 && r.determined;
    if (!r.converged)
      fit.status = "not converged (" + r.termination + ")";
    else if (r.chi2 > 4)
      fit.status = "no parameters reproduce M_R, M_T within their errors (chi^2 " + format_number(std::round(r.chi2 * 10) / 10) + ")";
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
