#include "bssrdf/fit/profile_fit.hpp"

#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/profile.hpp"
#include "fit_common.hpp"

namespace bssrdf {
namespace {

// The model's forward form (model_registry.hpp) and, for a numeric form, the runtime model.
struct ForwardModel {
  FitForm form;
  bool singular_at_origin = false;
  std::shared_ptr<const Model> runtime;
};

// One channel's data points (radius, value, sigma) and where the model is evaluated for each: point i
// is sum_k weight[i n + k] R(node[i n + k]), n = nodes_per_point: R at the radius itself (n = 1), or
// R averaged over the point's bin (n = 4, Gauss-Legendre in r of 2 pi r R over the annulus) where the
// file gives bins: the 1/r of single scattering near the entry point makes R at a bin's centre differ
// from its average (a factor 2 in the fitted sigma_a of a Monte Carlo profile with 0.2 mm bins).
struct ChannelData {
  std::vector<double> radius, value, sigma;
  std::vector<double> node, weight;
  std::size_t nodes_per_point = 1;
  double g = 0;
  template <class T>
  T model_value(const T* at_nodes, std::size_t i) const {
    T v(0);
    for (std::size_t k = 0; k < nodes_per_point; ++k)
      v += T(weight[i * nodes_per_point + k]) * at_nodes[i * nodes_per_point + k];
    return v;
  }
};

// Parameter blocks: [ln sigma_a, ln sigma_s'] per channel, [eta], [ln scale].
struct AutoResidual {
  const ChannelData* data;
  const ForwardModel* forward;
  template <class T>
  bool operator()(const T* channel, const T* eta, const T* log_scale, T* residual) const {
    using std::exp;
    const T sigma_a = exp(channel[0]), sigma_s_prime = exp(channel[1]);
    const auto m = reduce(sigma_a, sigma_s_prime / T(1 - data->g), T(data->g), eta[0]);
    std::vector<T> at(data->node.size());
    evaluate(forward->form, m, data->node, at.data());
    const T scale = exp(log_scale[0]);
    for (std::size_t i = 0; i < data->value.size(); ++i)
      residual[i] = (scale * data->model_value(at.data(), i) - T(data->value[i])) / T(data->sigma[i]);
    return true;
  }
};

struct NumericResidual {
  const ChannelData* data;
  const ForwardModel* forward;
  bool operator()(const double* channel, const double* eta, const double* log_scale, double* residual) const {
    const auto m = reduce(std::exp(channel[0]), std::exp(channel[1]) / (1 - data->g), data->g, eta[0]);
    const double scale = std::exp(log_scale[0]);
    std::vector<double> at(data->node.size());
    for (std::size_t k = 0; k < at.size(); ++k) at[k] = forward->runtime->reflectance(m, data->node[k]);
    for (std::size_t i = 0; i < data->value.size(); ++i)
      residual[i] = (scale * data->model_value(at.data(), i) - data->value[i]) / data->sigma[i];
    return true;
  }
};

ForwardModel forward_for(const std::string& name) {
  const auto& entry = model_entry(name);
  return {entry.fit_form, entry.singular_at_origin, entry.make()};
}

}  // namespace

void ProfileFitOptions::validate(std::size_t channels) const {
  if (!model.empty()) make_model(model);
  if (!(eta > 0) || !std::isfinite(eta)) throw InvalidInput("eta", format_number(eta), "> 0");
  if (fit_eta && !(eta_min < eta_max && eta >= eta_min && eta <= eta_max))
    throw InvalidInput("eta", format_number(eta),
                       "[" + format_number(eta_min) + ", " + format_number(eta_max) + "] when fitting eta");
  if (!g.empty() && g.size() != 1 && g.size() != channels)
    throw InvalidInput("g: " + std::to_string(g.size()) + " values for " + std::to_string(channels) + " channels");
  for (double v : g)
    if (!(v > -1 && v < 1)) throw InvalidInput("g", format_number(v), "-1 < g < 1");
  if (loss != "none" && loss != "huber" && loss != "cauchy")
    throw InvalidInput("loss", "'" + loss + "'", "none, huber or cauchy");
  if (!(loss_scale > 0)) throw InvalidInput("loss scale", format_number(loss_scale), "> 0");
}

FitReport fit_profile(const MeasuredProfile& data, const ProfileFitOptions& given) {
  const auto start = std::chrono::steady_clock::now();
  given.validate(data.channels.size());
  ProfileFitOptions options = given;
  DefaultModel chosen{given.model, ""};
  if (options.model.empty()) {
    chosen = default_model_over_albedos(options.g, options.fit_eta ? options.eta_min : options.eta,
                                        options.fit_eta ? options.eta_max : options.eta);
    options.model = chosen.name;
  }
  ForwardModel forward = forward_for(options.model);
  const double mm = millimetres_per(data.unit);

  // Data per channel; relative residuals where no standard errors are given.
  std::vector<ChannelData> channels(data.channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    auto& ch = channels[c];
    const auto& in = data.channels[c];
    double peak = 0;
    for (double v : in.value) peak = std::max(peak, v);
    if (!(peak > 0)) throw InvalidInput("channel " + in.name + ": every value is 0; nothing to fit");
    ch.g = options.g.empty() ? 0.0 : options.g.size() == 1 ? options.g[0] : options.g[c];
    const bool bins = !data.radius_inner.empty() && data.radius_inner.size() == data.radius.size();
    ch.nodes_per_point = bins ? 4 : 1;
    for (std::size_t i = 0; i < data.radius.size(); ++i) {
      if (!bins && data.radius[i] <= 0 && forward.singular_at_origin) continue;
      ch.radius.push_back(data.radius[i]);
      ch.value.push_back(in.value[i]);
      ch.sigma.push_back(in.standard_error.empty() ? std::max(in.value[i], 1e-9 * peak) : in.standard_error[i]);
      if (!bins) {
        ch.node.push_back(data.radius[i]);
        ch.weight.push_back(1);
        continue;
      }
      // The annulus average (1 / (pi (b^2 - a^2))) int_a^b 2 pi r R dr, four-point Gauss-Legendre.
      static constexpr double kX[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                       0.8611363115940526};
      static constexpr double kW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
      const double a = data.radius_inner[i], b = data.radius_outer[i];
      for (int k = 0; k < 4; ++k) {
        const double r = 0.5 * (a + b) + 0.5 * (b - a) * kX[k];
        ch.node.push_back(r);
        ch.weight.push_back(kW[k] * 0.5 * (b - a) * 2 * r / (b * b - a * a));
      }
    }
  }

  // Starting point: alpha' from the measured total, sigma_t' from the half-energy radius.
  const auto model = make_model(options.model);
  std::vector<std::array<double, 2>> x(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    SampledProfile p;
    p.radius = channels[c].radius;
    p.value = channels[c].value;
    const double total = std::clamp(p.integrate(), 1e-3, 0.95);
    double a = 0.9;
    try {
      a = std::clamp(model->albedo_prime_from_total(total, options.eta, channels[c].g), 0.05, 0.999);
    } catch (const InvalidInput&) {
    }
    const auto unit_medium = reduced_optical(a, channels[c].g, options.eta);
    const double r_model = model->radius_for_fraction(unit_medium, 0.5), r_data = p.radius_for_fraction(0.5);
    const double sigma_t_prime = std::isfinite(r_model) && r_data > 0 ? r_model / r_data : 1.0;
    x[c] = {std::log((1 - a) * sigma_t_prime), std::log(a * sigma_t_prime)};
  }
  double eta = options.eta, log_scale = 0;
  prepare(forward.form, options.eta);  // the same discretisation as the runtime model at this eta

  ceres::Problem problem;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const int n = static_cast<int>(channels[c].value.size());
    ceres::CostFunction* cost;
    if (forward.form.numeric()) {
      cost = new ceres::NumericDiffCostFunction<NumericResidual, ceres::CENTRAL, ceres::DYNAMIC, 2, 1, 1>(
          new NumericResidual{&channels[c], &forward}, ceres::TAKE_OWNERSHIP, n);
    } else {
      cost = new ceres::AutoDiffCostFunction<AutoResidual, ceres::DYNAMIC, 2, 1, 1>(
          new AutoResidual{&channels[c], &forward}, n);
    }
    ceres::LossFunction* loss = options.loss == "huber"
                                    ? static_cast<ceres::LossFunction*>(new ceres::HuberLoss(options.loss_scale))
                                : options.loss == "cauchy" ? new ceres::CauchyLoss(options.loss_scale)
                                                           : nullptr;
    problem.AddResidualBlock(cost, loss, x[c].data(), &eta, &log_scale);
    for (int i = 0; i < 2; ++i) {  // coefficients between 1e-11 and 1e11 per length unit
      problem.SetParameterLowerBound(x[c].data(), i, -25);
      problem.SetParameterUpperBound(x[c].data(), i, 25);
    }
  }
  if (!options.fit_eta)
    problem.SetParameterBlockConstant(&eta);
  else {
    problem.SetParameterLowerBound(&eta, 0, options.eta_min);
    problem.SetParameterUpperBound(&eta, 0, options.eta_max);
  }
  if (!options.fit_scale) problem.SetParameterBlockConstant(&log_scale);

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-14;
  solver.gradient_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-12;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  FitReport report;
  report.kind = "profile";
  report.model = options.model;
  report.model_choice = chosen.reason;
  report.data_source = data.file;
  report.iterations = static_cast<int>(summary.iterations.size()) - 1;
  report.termination = ceres::TerminationTypeToString(summary.termination_type);
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  report.solver_report = summary.FullReport();
  report.eta = eta;
  for (const auto& ch : channels) report.g.push_back(ch.g);
  report.length_unit = symbol(data.unit);

  // Covariance of the free parameters; scaled by the reduced chi-square without standard errors.
  std::vector<const double*> blocks;
  for (auto& b : x) blocks.push_back(b.data());
  if (options.fit_eta) blocks.push_back(&eta);
  if (options.fit_scale) blocks.push_back(&log_scale);
  std::size_t points = 0;
  for (const auto& ch : channels) points += ch.radius.size();
  const std::size_t free = 2 * channels.size() + options.fit_eta + options.fit_scale;
  const bool have_errors = !data.channels.empty() && !data.channels[0].standard_error.empty();
  const double chi2_dof = points > free ? 2 * summary.final_cost / static_cast<double>(points - free) : NAN;
  // With standard errors, a chi^2/dof above 1 means the model cannot explain the data within them:
  // the 1-sigma are widened by sqrt(chi^2/dof) (the Particle Data Group's scale factor), never
  // narrowed. Without standard errors, the residual scatter is the only noise estimate.
  const double variance_scale = have_errors ? std::max(1.0, chi2_dof) : chi2_dof;
  const auto covariance = parameter_covariance(problem, blocks);

  const std::string per_unit = "1/" + std::string(symbol(data.unit));
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::string& name = data.channels[c].name;
    const double sa = std::exp(x[c][0]), ssp = std::exp(x[c][1]);
    double se_a = NAN, se_s = NAN, se_albedo = NAN, rho = NAN;
    if (covariance) {
      const auto& cov = *covariance;
      se_a = sa * std::sqrt(cov(2 * c, 2 * c) * variance_scale);
      se_s = ssp * std::sqrt(cov(2 * c + 1, 2 * c + 1) * variance_scale);
      rho = cov(2 * c, 2 * c + 1) / std::sqrt(cov(2 * c, 2 * c) * cov(2 * c + 1, 2 * c + 1));
      // alpha' = s / (a + s) in the fitted logs: d alpha' / d ln s = -d alpha' / d ln a = a s / (a + s)^2.
      const double slope = sa * ssp / ((sa + ssp) * (sa + ssp));
      se_albedo =
          slope * std::sqrt(std::max(0.0, cov(2 * c, 2 * c) + cov(2 * c + 1, 2 * c + 1) - 2 * cov(2 * c, 2 * c + 1)) *
                            variance_scale);
    }
    report.parameters.push_back({"sigma_a", name, sa * mm, se_a * mm, per_unit});
    report.parameters.push_back({"sigma_s_prime", name, ssp * mm, se_s * mm, per_unit});
    report.parameters.push_back({"albedo_prime", name, ssp / (sa + ssp), se_albedo, ""});
    // The 1-sigma are statistical: a diffusion model's own error against radiative transfer biases
    // the estimates beyond them (PBD on a Monte Carlo profile: sigma_a 7.6 % high, 12 sigma). Say
    // how large that error is here, measured against Monte Carlo (model_choice.hpp).
    if (const auto e = estimate_model_error(options.model, reduce(sa, ssp / (1 - channels[c].g), channels[c].g, eta)))
      if (e->profile_error > 0.01)
        report.warnings.push_back("channel " + name + ": the 1-sigma are statistical only; " + e->model +
                                  " itself differs from radiative transfer by " +
                                  format_number(std::round(e->profile_error * 1000) / 10) + " % in R(r) (L2) and " +
                                  format_number(std::round(e->total_error * 1000) / 10) +
                                  " % in the total at these coefficients (measured against Monte Carlo), which biases "
                                  "the fitted coefficients beyond them");
    if (std::abs(rho) > 0.99)
      report.warnings.push_back("channel " + name + ": sigma_a and sigma_s' are strongly correlated (rho = " +
                                format_number(std::round(rho * 1000) / 1000) +
                                "): the profile determines mainly one combination of them");
  }
  std::size_t k = 2 * channels.size();
  if (options.fit_eta) {
    report.parameters.push_back(
        {"eta", "", eta, covariance ? std::sqrt((*covariance)(k, k) * variance_scale) : NAN, ""});
    ++k;
  }
  if (options.fit_scale) {
    const double s = std::exp(log_scale);
    report.parameters.push_back(
        {"scale", "", s, covariance ? s * std::sqrt((*covariance)(k, k) * variance_scale) : NAN, ""});
  }
  if (!covariance)
    report.warnings.push_back(
        "the covariance could not be computed (rank-deficient Jacobian): the parameters are not "
        "all identifiable from these data");
  if (have_errors && chi2_dof > 1)
    report.warnings.push_back(
        "chi-square per degree of freedom " + format_number(std::round(chi2_dof * 100) / 100) +
        (chi2_dof > 4 ? ": the model does not explain the data within their standard errors" : "") +
        "; the 1-sigma are widened by sqrt(chi^2/dof) = " + format_number(std::round(std::sqrt(chi2_dof) * 100) / 100));
  if (!report.converged) report.warnings.push_back("the solver did not converge: " + summary.message);

  // Residuals per point.
  double sum_w = 0, sum_rel = 0;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const auto& ch = channels[c];
    std::vector<double> r(ch.radius.size());
    const double lscale = log_scale;
    if (forward.form.numeric())
      NumericResidual{&ch, &forward}(x[c].data(), &eta, &lscale, r.data());
    else
      AutoResidual{&ch, &forward}(x[c].data(), &eta, &lscale, r.data());
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double model_value = ch.value[i] + r[i] * ch.sigma[i];
      report.residuals.push_back(
          {data.channels[c].name, ch.radius[i] / mm, ch.value[i] * mm * mm, model_value * mm * mm, r[i]});
      sum_w += r[i] * r[i];
      if (ch.value[i] > 0) sum_rel += std::pow(model_value / ch.value[i] - 1, 2);
    }
  }
  report.residual_rms = std::sqrt(sum_w / std::max<std::size_t>(1, points));
  report.relative_rms = std::sqrt(sum_rel / std::max<std::size_t>(1, points));
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace bssrdf
