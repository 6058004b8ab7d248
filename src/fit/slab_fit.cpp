// Integrating-sphere inversion through the multipole: (M_R, M_T) of a slab -> sigma_a, sigma_s'.
#include <ceres/ceres.h>

#include <chrono>
#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/models/multipole.hpp"
#include "fit_common.hpp"

namespace bssrdf {

namespace {

// The infinite multipole series in closed form (no pair counting), plus the ballistic beam with
// its multiple reflections between the faces; templated for automatic differentiation.
template <class T>
std::pair<T, T> measurables(T sigma_a, T sigma_s_prime, double g, double eta, double d) {
  using std::exp;
  const auto m = reduce(sigma_a, sigma_s_prime / T(1 - g), T(g), T(eta));
  const auto slab = multipole::make_slab(T(d), T(eta), T(eta));
  const double rsp = std::pow((eta - 1) / (eta + 1), 2);
  const T e = exp(-m.sigma_t() * T(d));
  const T bounce = T(1) - T(rsp * rsp) * e * e;
  const T ballistic_t = T((1 - rsp) * (1 - rsp)) * e / bounce;
  const T ballistic_r = T((1 - rsp) * (1 - rsp) * rsp) * e * e / bounce;
  return {T(1 - rsp) * multipole::total_reflectance(m, slab) + ballistic_r,
          T(1 - rsp) * multipole::total_transmittance(m, slab) + ballistic_t};
}

}  // namespace

std::pair<double, double> slab_measurables(double sigma_a, double sigma_s_prime, double g, double eta, double d) {
  return measurables(sigma_a, sigma_s_prime, g, eta, d);
}

namespace {

struct SlabResidual {
  const SlabMeasurement* data;
  double eta, thickness;
  template <class T>
  bool operator()(const T* x, T* residual) const {
    using std::exp;
    const auto [R, Tt] = measurables(exp(x[0]), exp(x[1]), data->g, eta, thickness);
    residual[0] = (R - T(data->reflectance)) / T(data->reflectance_stderr);
    residual[1] = (Tt - T(data->transmittance)) / T(data->transmittance_stderr);
    return true;
  }
};

}  // namespace

FitReport fit_slab(const std::vector<SlabMeasurement>& channels, double thickness, LengthUnit unit, double eta) {
  const auto start = std::chrono::steady_clock::now();
  const double d = to_mm(thickness, unit);
  if (!(thickness > 0) || !std::isfinite(thickness)) throw InvalidInput("thickness", format_number(thickness), "> 0");
  if (!(eta > 0)) throw InvalidInput("eta", format_number(eta), "> 0");
  FitReport report;
  report.kind = "slab";
  report.model = "multipole";
  report.data_source = "slab of " + format_number(thickness) + " " + std::string(symbol(unit)) + ", eta " + format_number(eta);
  report.converged = true;
  const std::string per_unit = "1/" + std::string(symbol(unit));
  const double mm = millimetres_per(unit);
  for (const auto& c : channels) {
    const std::string where = "channel " + c.name + ": ";
    if (!(c.reflectance >= 0 && c.reflectance <= 1)) throw InvalidInput(where + "reflectance", format_number(c.reflectance), "[0, 1]");
    if (!(c.transmittance >= 0 && c.transmittance <= 1))
      throw InvalidInput(where + "transmittance", format_number(c.transmittance), "[0, 1]");
    if (c.reflectance + c.transmittance > 1)
      throw InvalidInput(where + "reflectance + transmittance", format_number(c.reflectance + c.transmittance),
                         "<= 1 (more light out than in: an impossible measurement)");
    if (!(c.reflectance_stderr > 0 && c.transmittance_stderr > 0))
      throw InvalidInput(where + "standard errors must be > 0");
    // Multi-start: the map (sigma_a, sigma_s') -> (R, T) folds for thin slabs; keep the best fit.
    double best_cost = INFINITY;
    std::array<double, 2> best{};
    ceres::Solver::Summary best_summary;
    for (double a : {0.5, 0.9, 0.99})
      for (double optical : {2.0, 6.0, 20.0}) {
        std::array<double, 2> x = {std::log((1 - a) * optical / d), std::log(a * optical / d)};
        ceres::Problem problem;
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SlabResidual, 2, 2>(
                                     new SlabResidual{&c, eta, d}),
                                 nullptr, x.data());
        for (int i = 0; i < 2; ++i) {  // keep the search in the physical range (1e-11 to 1e11 per mm)
          problem.SetParameterLowerBound(x.data(), i, -25);
          problem.SetParameterUpperBound(x.data(), i, 25);
        }
        ceres::Solver::Options options;
        options.linear_solver_type = ceres::DENSE_QR;
        options.max_num_iterations = 100;
        options.function_tolerance = 1e-16;
        options.parameter_tolerance = 1e-14;
        ceres::Solver::Summary summary;
        ceres::Solve(options, &problem, &summary);
        if (summary.final_cost < best_cost) {
          best_cost = summary.final_cost;
          best = x;
          best_summary = summary;
        }
      }
    // Uncertainty: the covariance of the weighted least-squares problem at the solution, i.e. the
    // measurement errors propagated through the inverse Jacobian.
    ceres::Problem problem;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SlabResidual, 2, 2>(new SlabResidual{&c, eta, d}),
                             nullptr, best.data());
    const auto covariance = parameter_covariance(problem, {best.data()});
    const double sa = std::exp(best[0]), ssp = std::exp(best[1]);
    const double se_a = covariance ? sa * std::sqrt((*covariance)(0, 0)) : NAN;
    const double se_s = covariance ? ssp * std::sqrt((*covariance)(1, 1)) : NAN;
    report.parameters.push_back({"sigma_a", c.name, sa * mm, se_a * mm, per_unit});
    report.parameters.push_back({"sigma_s_prime", c.name, ssp * mm, se_s * mm, per_unit});
    report.parameters.push_back({"albedo_prime", c.name, ssp / (sa + ssp), NAN, ""});
    const auto [R, T] = slab_measurables(sa, ssp, c.g, eta, d);
    report.residuals.push_back({c.name, 0, c.reflectance, R, (R - c.reflectance) / c.reflectance_stderr});
    report.residuals.push_back({c.name, 1, c.transmittance, T, (T - c.transmittance) / c.transmittance_stderr});
    report.iterations += static_cast<int>(best_summary.iterations.size()) - 1;
    if (std::sqrt(2 * best_cost) > 2)
      report.warnings.push_back(where + "no sigma_a, sigma_s' of the multipole reproduce (R, T) = (" + format_number(c.reflectance) +
                                ", " + format_number(c.transmittance) + ") within their errors (closest: " + format_number(R) +
                                ", " + format_number(T) + "): the data are out of the model's reach");
    if (!covariance)
      report.warnings.push_back(where + "the solution is not unique here (singular Jacobian): R and T do not separate "
                                "absorption from scattering");
    const multipole::Model slab(d);
    for (const auto& note : slab.validity(reduce(sa, ssp / (1 - c.g), c.g, eta)))
      if (note.severity != Severity::note) report.warnings.push_back(where + note.message);
  }
  double sum = 0;
  for (const auto& r : report.residuals) sum += r.weighted * r.weighted;
  report.residual_rms = std::sqrt(sum / std::max<std::size_t>(1, report.residuals.size()));
  report.termination = "CONVERGENCE";
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace bssrdf
