// Output of 'bssrdf fit slab --rxt FILE'; see rxt_output.hpp.
#include "rxt_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"

namespace bssrdf::cli {

namespace {

nlohmann::json estimate(double value, double stderr_) { return {{"value", value}, {"stderr", stderr_}}; }

}  // namespace

std::string rxt_fit_json(const RxtFit& fit) {
  const auto& f = fit.file;
  nlohmann::json doc;
  doc["tool"] = std::string("bssrdf ") + BSSRDF_VERSION;
  doc["source"] = f.name;
  doc["model"] = "adding-doubling";
  doc["unit"] = "mm";
  doc["eta"] = f.sample_n;  // with each row's mu_a, mu_s, g: a complete medium per row (materials import)
  auto sphere = [](const RxtSphere& s) {
    return nlohmann::json{{"diameter", s.diameter},
                          {"sample_port", s.sample_port},
                          {"third_port", s.third_port},
                          {"detector_port", s.detector_port},
                          {"wall_reflectance", s.wall_reflectance}};
  };
  doc["header"] = {{"sample_index", f.sample_n},
                   {"slide_index", f.slide_n},
                   {"sample_thickness", f.sample_thickness},
                   {"slide_thickness", f.slide_thickness},
                   {"beam_diameter", f.beam_diameter},
                   {"standard_reflectance", f.standard_reflectance},
                   {"spheres", f.spheres},
                   {"reflection_sphere", sphere(f.reflection)},
                   {"transmission_sphere", sphere(f.transmission)},
                   {"measurements", f.measurements},
                   {"columns", f.columns},
                   {"unscattered_in_m_r", f.unscattered_in_m_r},
                   {"unscattered_in_m_t", f.unscattered_in_m_t},
                   {"standard_transmittance", f.standard_transmittance}};
  const auto& m = fit.options.sphere;
  auto or_file = [](double v) { return std::isnan(v) ? nlohmann::json("file") : nlohmann::json(v); };
  doc["sphere_model"] = {{"baffle_reflection", m.baffle_r},
                         {"baffle_transmission", m.baffle_t},
                         {"detector_reflectance", m.detector_reflectance},
                         {"wall_first", m.wall_first},
                         {"dual_beam", m.dual_beam},
                         {"unscattered_in_m_r", or_file(m.unscattered_in_m_r)},
                         {"unscattered_in_m_t", or_file(m.unscattered_in_m_t)}};
  doc["quadrature"] =
      fit.options.quadrature == 0 ? nlohmann::json("automatic (32)") : nlohmann::json(fit.options.quadrature);
  doc["incidence_angle"] = std::isnan(fit.options.incidence_degrees) ? nlohmann::json("file (column i, else 0)")
                                                                     : nlohmann::json(fit.options.incidence_degrees);
  doc["measurement_stderr"] = {{"m_r", fit.options.reflectance_stderr},
                               {"m_t", fit.options.transmittance_stderr},
                               {"m_u", fit.options.unscattered_stderr}};
  // rows with M_U fit g, rows with a g column hold theirs; null: not given (0 held, fitted with a constraint)
  doc["g_held"] = std::isnan(fit.options.g) ? nlohmann::json(nullptr) : nlohmann::json(fit.options.g);
  const auto& k = fit.options.constraints;
  auto given = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  doc["constraints"] = {{"albedo", given(k.albedo)},
                        {"optical_thickness", given(k.optical_thickness)},
                        {"mu_a", given(k.mu_a)},
                        {"mu_s", given(k.mu_s)},
                        {"mu_s_prime", given(k.mu_s_prime)},
                        {"mu_s_power_law", std::isnan(k.power_mu_s0) ? nlohmann::json(nullptr)
                                                                     : nlohmann::json{{"lambda0", k.power_lambda0},
                                                                                      {"mu_s0", k.power_mu_s0},
                                                                                      {"gamma", k.power_gamma}}}};
  doc["lost_light_correction"] = fit.options.lost_light;
  if (fit.options.lost_light) doc["lost_light_photons"] = fit.options.lost_light_photons;
  doc["seconds"] = fit.seconds;
  doc["rows"] = nlohmann::json::array();
  for (const auto& r : fit.rows) {
    nlohmann::json row{{"line", r.row.line},
                       {"wavelength", r.row.wavelength},
                       {"mu_a", estimate(r.mu_a, r.mu_a_stderr)},
                       {"mu_s_prime", estimate(r.mu_s_prime, r.mu_s_prime_stderr)},
                       {"mu_s", estimate(r.mu_s_prime / (1 - r.g), r.mu_s_prime_stderr / (1 - r.g))},
                       {"g", estimate(r.g, r.g_stderr)},
                       {"m_r", {{"measured", r.row.m_r}, {"fitted", r.fitted_m_r}}},
                       {"m_t", {{"measured", r.row.m_t}, {"fitted", r.fitted_m_t}}},
                       {"spheres", r.row.setup.spheres},
                       {"incidence_angle", r.row.setup.incidence_degrees},
                       {"chi2", r.chi2},
                       {"converged", r.converged},
                       {"status", r.status}};
    if (!r.constraint.empty()) row["constraint"] = r.constraint;
    if (r.fitted_m_u >= 0) row["m_u"] = {{"measured", r.row.m_u}, {"fitted", r.fitted_m_u}};
    if (fit.options.lost_light) row["lost_light"] = {{"ur1", r.ur1_lost}, {"ut1", r.ut1_lost}};
    doc["rows"].push_back(row);
  }
  return doc.dump(2) + "\n";
}

std::string rxt_fit_csv(const RxtFit& fit) {
  std::ostringstream out;
  out << "wavelength,mu_a_per_mm,mu_a_stderr,mu_s_prime_per_mm,mu_s_prime_stderr,g,g_stderr,m_r,m_r_fitted,m_t,m_t_"
         "fitted,m_u,"
         "m_u_fitted,chi2,status\n";
  for (const auto& r : fit.rows) {
    out << format_number(r.row.wavelength) << ',' << format_number(r.mu_a) << ',' << format_number(r.mu_a_stderr) << ','
        << format_number(r.mu_s_prime) << ',' << format_number(r.mu_s_prime_stderr) << ',' << format_number(r.g) << ','
        << format_number(r.g_stderr) << ',' << format_number(r.row.m_r) << ',' << format_number(r.fitted_m_r) << ','
        << format_number(r.row.m_t) << ',' << format_number(r.fitted_m_t) << ',';
    if (r.fitted_m_u >= 0)
      out << format_number(r.row.m_u) << ',' << format_number(r.fitted_m_u);
    else
      out << ',';
    out << ',' << format_number(r.chi2) << ",\"" << r.status << (r.constraint.empty() ? "" : "; " + r.constraint)
        << "\"\n";
  }
  return out.str();
}

std::string rxt_fit_table(const RxtFit& fit) {
  const auto& f = fit.file;
  const auto& k = fit.options.constraints;
  std::ostringstream out;
  char line[512];
  out << "inverse adding-doubling of " << f.name << "\n";
  std::snprintf(line, sizeof line,
                "sample n %.3f, %.3f mm; slides n %.3f, %.3f mm%s; %d sphere(s); standard %.3f; g %s; %s\n", f.sample_n,
                f.sample_thickness, f.slide_n, f.slide_thickness, f.has_slides() ? "" : " (none)", f.spheres,
                f.standard_reflectance,
                f.measurements == 3         ? "fitted (M_U given)"
                : std::isnan(fit.options.g) ? (k.any() ? "fitted with the constraint, else 0" : "held at 0")
                                            : ("held at " + format_number(fit.options.g)).c_str(),
                fit.options.lost_light ? ("LOST LIGHT CORRECTED by Monte Carlo (" +
                                          std::to_string(fit.options.lost_light_photons) + " photons, pencil beam)")
                                             .c_str()
                                       : "lost light not corrected");
  out << line;
  const auto& m = fit.options.sphere;
  auto share = [](double v) { return std::isnan(v) ? std::string("file's") : format_number(v); };
  std::snprintf(line, sizeof line,
                "sphere model (iad 4): baffles %s/%s, detector reflectance %g, wall first %g, %s, unscattered in "
                "M_R %s, in M_T %s; quadrature %s\n",
                m.baffle_r ? "R" : "-", m.baffle_t ? "T" : "-", m.detector_reflectance, m.wall_first,
                m.dual_beam ? "dual beam" : "single beam", share(m.unscattered_in_m_r).c_str(),
                share(m.unscattered_in_m_t).c_str(),
                fit.options.quadrature == 0 ? "automatic (32)" : std::to_string(fit.options.quadrature).c_str());
  out << line;
  double oblique_min = 90, oblique_max = 0;
  for (const auto& r : fit.rows)
    if (r.row.setup.incidence_degrees != 0) {
      oblique_min = std::min(oblique_min, r.row.setup.incidence_degrees);
      oblique_max = std::max(oblique_max, r.row.setup.incidence_degrees);
    }
  if (oblique_max > 0)
    out << "oblique incidence (iad -i / column i): " << format_number(oblique_min)
        << (oblique_max > oblique_min ? " to " + format_number(oblique_max) : std::string())
        << " degrees, the refracted beam one of the quadrature angles\n";
  if (k.any()) {
    out << "constraints (iad's):";
    for (auto [name, v] : {std::pair{" albedo a", k.albedo},
                           {" optical thickness b", k.optical_thickness},
                           {" mu_a (1/mm)", k.mu_a},
                           {" mu_s (1/mm)", k.mu_s},
                           {" mu_s' (1/mm)", k.mu_s_prime}})
      if (!std::isnan(v)) out << name << " = " << format_number(v);
    if (!std::isnan(k.power_mu_s0))
      out << " mu_s = " << format_number(k.power_mu_s0) << " (lambda/" << format_number(k.power_lambda0) << ")^"
          << format_number(k.power_gamma);
    out << " held; the rest solved per row as iad's search\n";
  }
  out << (f.has_wavelength ? "  lambda" : "     row")
      << "   mu_a (1/mm)          mu_s' (1/mm)         g               M_R meas/fit     M_T meas/fit     status\n";
  for (const auto& r : fit.rows) {
    std::snprintf(
        line, sizeof line, "%8g  %8.4f +- %-8.2g %8.4f +- %-8.2g %6.3f +- %-5.2g %.4f/%.4f    %.4f/%.4f    %s\n",
        r.row.wavelength, r.mu_a, r.mu_a_stderr, r.mu_s_prime, r.mu_s_prime_stderr, r.g, r.g_stderr, r.row.m_r,
        r.fitted_m_r, r.row.m_t, r.fitted_m_t, (r.status + (r.constraint.empty() ? "" : "; " + r.constraint)).c_str());
    out << line;
  }
  std::snprintf(line, sizeof line, "%zu rows in %.3f s; errors: 1 sigma from M_R +- %g, M_T +- %g%s\n", fit.rows.size(),
                fit.seconds, fit.options.reflectance_stderr, fit.options.transmittance_stderr,
                f.measurements == 3 ? (", M_U +- " + format_number(fit.options.unscattered_stderr)).c_str() : "");
  out << line;
  return out.str();
}

}  // namespace bssrdf::cli
