// Integrating-sphere inversion: (R, T[, U]) of a slab -> sigma_a, sigma_s' [, g], through
// adding-doubling (exact at any thickness, glass slides) or the multipole (for comparison).
#include <chrono>
#include <cmath>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/models/multipole.hpp"
#include "slab_inversion.hpp"

namespace bssrdf {

namespace {

// The infinite multipole series in closed form (no pair counting), plus the ballistic beam with
// its multiple reflections between the faces.
std::pair<double, double> multipole_measurables(double sigma_a, double sigma_s_prime, double g, double eta, double d) {
  const auto m = reduce(sigma_a, sigma_s_prime / (1 - g), g, eta);
  const auto slab = multipole::make_slab(d, eta, eta);
  const double rsp = std::pow((eta - 1) / (eta + 1), 2);
  const double e = std::exp(-m.sigma_t() * d);
  const double bounce = 1 - rsp * rsp * e * e;
  const double ballistic_t = (1 - rsp) * (1 - rsp) * e / bounce;
  const double ballistic_r = (1 - rsp) * (1 - rsp) * rsp * e * e / bounce;
  return {(1 - rsp) * multipole::total_reflectance(m, slab) + ballistic_r,
          (1 - rsp) * multipole::total_transmittance(m, slab) + ballistic_t};
}

adding_doubling::Slab ad_slab(const SlabParameters& p, double eta, double d, const SlabFitOptions& options, double mm) {
  adding_doubling::Slab slab;
  slab.layers = {{p.sigma_a, p.sigma_s_prime / (1 - p.g), p.g, d}};
  slab.n = eta;
  if (options.slide_n > 0) slab.above = slab.below = {{options.slide_n, options.slide_thickness * mm, 0.0}};
  return slab;
}

}  // namespace

std::pair<double, double> slab_measurables(double sigma_a, double sigma_s_prime, double g, double eta, double d) {
  return multipole_measurables(sigma_a, sigma_s_prime, g, eta, d);
}

FitReport fit_slab(const std::vector<SlabMeasurement>& channels, double thickness, LengthUnit unit, double eta,
                   const SlabFitOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(thickness > 0) || !std::isfinite(thickness)) throw InvalidInput("thickness", format_number(thickness), "> 0");
  if (!(eta > 0 && std::isfinite(eta))) throw InvalidInput("eta", format_number(eta), "> 0");
  const bool multipole = options.model == "multipole";
  if (!multipole && options.model != "adding-doubling")
    throw InvalidInput("model", options.model, "adding-doubling or multipole");
  if (options.slide_n != 0) {
    if (multipole)
      throw InvalidInput("slides", format_number(options.slide_n), "none with the multipole (use adding-doubling)");
    if (!(options.slide_n >= 1 && options.slide_n <= 4))
      throw InvalidInput("slide index", format_number(options.slide_n), "1 to 4");
    if (!(options.slide_thickness > 0 && std::isfinite(options.slide_thickness)))
      throw InvalidInput("slide thickness", format_number(options.slide_thickness), "> 0 and finite");
  }
  const double mm = millimetres_per(unit);
  const double d = to_mm(thickness, unit);
  FitReport report;
  report.kind = "slab";
  report.model = options.model;
  report.data_source =
      "slab of " + format_number(thickness) + " " + std::string(symbol(unit)) + ", eta " + format_number(eta) +
      (options.slide_n > 0 ? ", slides n " + format_number(options.slide_n) + " x " +
                                 format_number(options.slide_thickness) + " " + std::string(symbol(unit))
                           : std::string());
  report.converged = true;
  report.eta = eta;  // g is a parameter of every channel, fitted or held
  report.length_unit = symbol(unit);
  const std::string per_unit = "1/" + std::string(symbol(unit));
  const char* const measurement_names[] = {"R", "T", "U"};
  for (const auto& c : channels) {
    const std::string where = "channel " + c.name + ": ";
    if (!(c.reflectance >= 0 && c.reflectance <= 1))
      throw InvalidInput(where + "reflectance", format_number(c.reflectance), "[0, 1]");
    if (!(c.transmittance >= 0 && c.transmittance <= 1))
      throw InvalidInput(where + "transmittance", format_number(c.transmittance), "[0, 1]");
    if (c.reflectance + c.transmittance > 1)
      throw InvalidInput(where + "reflectance + transmittance", format_number(c.reflectance + c.transmittance),
                         "<= 1 (more light out than in: an impossible measurement)");
    if (!(c.reflectance_stderr > 0 && c.transmittance_stderr > 0 && std::isfinite(c.reflectance_stderr) &&
          std::isfinite(c.transmittance_stderr)))
      throw InvalidInput(where + "standard errors must be > 0 and finite");
    if (!(c.g > -1 && c.g < 1)) throw InvalidInput(where + "g", format_number(c.g), "-1 < g < 1");
    const bool with_u = c.unscattered >= 0;
    if (with_u) {
      if (multipole)
        throw InvalidInput(where + "unscattered transmittance", format_number(c.unscattered),
                           "not used by the multipole");
      if (!(c.unscattered <= c.transmittance))
        throw InvalidInput(where + "unscattered transmittance", format_number(c.unscattered),
                           "<= total transmittance " + format_number(c.transmittance));
      if (!(c.unscattered_stderr > 0 && std::isfinite(c.unscattered_stderr)))
        throw InvalidInput(where + "unscattered standard error", format_number(c.unscattered_stderr), "> 0 and finite");
    }
    const int count = with_u ? 3 : 2;
    SlabForward forward, coarse, search;
    if (multipole) {
      forward = coarse = [&](const SlabParameters& p) -> std::array<double, 3> {
        const auto [R, T] = multipole_measurables(p.sigma_a, p.sigma_s_prime, p.g, eta, d);
        return {R, T, 0};
      };
    } else {
      // Fixed angles during the fit, so the residuals are smooth in the parameters: 32 keeps R and
      // T within 3e-5 of 128 angles over the tested range (test_ad_slab); 8 for the starting grid,
      // 16 for the search that the final solve on 32 polishes.
      auto with_points = [&, d](int points) {
        return [&, d, points](const SlabParameters& p) -> std::array<double, 3> {
          adding_doubling::Options ad;
          ad.points = points;
          const auto t =
              adding_doubling::solve(ad_slab(p, eta, d, options, mm), adding_doubling::Incidence::collimated, ad);
          return {t.diffuse_reflectance, t.total_transmittance, t.unscattered_transmittance};
        };
      };
      forward = with_points(32);
      coarse = with_points(8);
      search = with_points(16);
    }
    const auto result = invert_slab({c.reflectance, c.transmittance, with_u ? c.unscattered : 0.0},
                                    {c.reflectance_stderr, c.transmittance_stderr, with_u ? c.unscattered_stderr : 1.0},
                                    count, with_u, c.g, d, forward, coarse, search ? &search : nullptr);
    const auto& p = result.parameters;
    report.parameters.push_back({"sigma_a", c.name, p.sigma_a * mm, result.standard_error[0] * mm, per_unit});
    report.parameters.push_back(
        {"sigma_s_prime", c.name, p.sigma_s_prime * mm, result.standard_error[1] * mm, per_unit});
    report.parameters.push_back({"g", c.name, p.g, with_u ? result.standard_error[2] : 0.0, ""});
    report.parameters.push_back(
        {"albedo_prime", c.name, p.sigma_s_prime / (p.sigma_a + p.sigma_s_prime), result.albedo_prime_stderr, ""});
    const double measured[] = {c.reflectance, c.transmittance, c.unscattered};
    const double sigma[] = {c.reflectance_stderr, c.transmittance_stderr, c.unscattered_stderr};
    for (int m = 0; m < count; ++m)
      report.residuals.push_back(
          {c.name, double(m), measured[m], result.predicted[m], (result.predicted[m] - measured[m]) / sigma[m]});
    report.iterations += result.iterations;
    report.converged &= result.converged;
    // Which measurement constrains which parameter: each one's share of the parameter's variance.
    std::string shares;
    const char* const parameter_names[] = {"sigma_a", "sigma_s'", "g"};
    for (int j = 0; j < (with_u ? 3 : 2); ++j) {
      if (j) shares.append("; ");
      shares.append(parameter_names[j]).append(":");
      for (int m = 0; m < count; ++m)
        shares.append(" ")
            .append(measurement_names[m])
            .append(" ")
            .append(std::to_string(std::lround(100 * result.share[j][m])))
            .append("%");
    }
    report.warnings.push_back(where + "note: share of each parameter's variance from each measurement: " + shares);
    report.warnings.push_back(where + "note: chi^2 = " + format_number(std::round(result.chi2 * 1000) / 1000) +
                              " for " + std::to_string(count) + " measurements and " + std::to_string(with_u ? 3 : 2) +
                              " parameters" +
                              (result.chi2 <= 4 ? " (the data are explained within their errors)" : ""));
    if (result.chi2 > 4)
      report.warnings.push_back(where + "no sigma_a, sigma_s'" + (with_u ? ", g" : "") + " of " + options.model +
                                " reproduce the data within their errors " + "(closest R, T = " +
                                format_number(result.predicted[0]) + ", " + format_number(result.predicted[1]) +
                                ", chi^2 = " + format_number(result.chi2) + "): the data are out of the model's reach");
    if (!result.determined)
      report.warnings.push_back(where +
                                "the solution is not unique here (singular Jacobian): the measurements do not separate "
                                "absorption from scattering; the standard errors are floored pseudo-inverse values");
    if (!result.converged)
      report.warnings.push_back(where + "the solver did not converge (" + result.termination + ")");
    if (multipole) {
      const multipole::Model slab(d);
      for (const auto& note : slab.validity(reduce(p.sigma_a, p.sigma_s_prime / (1 - c.g), c.g, eta)))
        if (note.severity != Severity::note) report.warnings.push_back(where + note.message);
    }
  }
  double sum = 0;
  for (const auto& r : report.residuals) sum += r.weighted * r.weighted;
  report.residual_rms = std::sqrt(sum / std::max<std::size_t>(1, report.residuals.size()));
  report.termination = report.converged ? "CONVERGENCE" : "NO_CONVERGENCE";
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace bssrdf
