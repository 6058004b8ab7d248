// Real-time forms fitted to a profile: a sum of Gaussians with shared variances (GPU Gems 3
// ch. 14) and Burley's d. Both minimise int r (R - fit)^2 dr on the profile's radii (trapezoid
// weights), each channel normalised by int r R^2 dr so that all channels count alike.
#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/models/normalized_diffusion.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"
#include "fit_common.hpp"

namespace bssrdf {
namespace {

// sqrt of the trapezoid weight of r_i in int r f(r)^2 dr, divided by the channel's norm.
std::vector<double> root_weights(const SampledProfile& p) {
  const std::size_t n = p.size();
  std::vector<double> w(n);
  double norm = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double left = i > 0 ? p.radius[i] - p.radius[i - 1] : 0;
    const double right = i + 1 < n ? p.radius[i + 1] - p.radius[i] : 0;
    w[i] = p.radius[i] * 0.5 * (left + right);
    norm += w[i] * p.value[i] * p.value[i];
  }
  for (auto& v : w) v = std::sqrt(v / norm);
  return w;
}

// The Gaussians G2(v_k, r_i) at one set of radii, for the variances of the last evaluation: every
// channel sampled at the same radii (a medium's table) reads them from here, so each evaluation
// takes one exponential per radius and Gaussian, not one per channel too. Ceres evaluates the
// residual blocks one after another (one thread), so the blocks may share it.
class GaussianBasis {
 public:
  GaussianBasis(const std::vector<double>& radius, int count) : radius_(radius), count_(count) {}
  bool serves(const std::vector<double>& radius) const { return radius == radius_; }
  // G2 at every radius (row) and Gaussian (column) for these log variances, computed once per set.
  const double* at(const double* log_variance) {
    if (!values_.empty() && std::equal(log_variance, log_variance + count_, log_variance_.begin())) return values_.data();
    log_variance_.assign(log_variance, log_variance + count_);
    values_.resize(radius_.size() * static_cast<std::size_t>(count_));
    for (int k = 0; k < count_; ++k) variance_[k] = std::exp(log_variance[k]);
    for (std::size_t i = 0; i < radius_.size(); ++i) {
      const double r = radius_[i];
      for (int k = 0; k < count_; ++k) {
        const double v = variance_[k];
        // exp underflows to 0 below -745.2: skip its slow path (the same value, 0).
        values_[i * count_ + k] = r * r / (2 * v) > 746 ? 0.0 : quantized_diffusion::gaussian_2d(v, r);
      }
    }
    return values_.data();
  }
  double variance(int k) const { return variance_[k]; }

 private:
  std::vector<double> radius_;
  int count_;
  std::vector<double> log_variance_, values_;
  std::array<double, 32> variance_{};  // count <= 32 (fit_gaussians)
};

// Residuals sqrt(w_i) (sum_k W_k G2(v_k, r_i) - R_i) with analytic derivatives (dG2/d ln v =
// G2 (r^2 / 2v - 1)), the Gaussians from the channel's basis.
class GaussianResidual : public ceres::CostFunction {
 public:
  GaussianResidual(const SampledProfile* profile, std::vector<double> weight, int count,
                   std::shared_ptr<GaussianBasis> basis)
      : profile_(profile), weight_(std::move(weight)), count_(count), basis_(std::move(basis)) {
    mutable_parameter_block_sizes()->assign({count, count});
    set_num_residuals(static_cast<int>(profile->size()));
  }
  bool Evaluate(double const* const* parameters, double* residual, double** jacobians) const override {
    const double* gaussians = basis_->at(parameters[0]);
    const double* w = parameters[1];  // bounded below by 0: weights may vanish exactly
    for (std::size_t i = 0; i < profile_->size(); ++i) {
      const double r = profile_->radius[i];
      double sum = 0;
      for (int k = 0; k < count_; ++k) {
        const double v = basis_->variance(k), g = gaussians[i * count_ + k];
        sum += w[k] * g;
        if (jacobians && jacobians[0]) jacobians[0][i * count_ + k] = weight_[i] * w[k] * g * (r * r / (2 * v) - 1);
        if (jacobians && jacobians[1]) jacobians[1][i * count_ + k] = weight_[i] * g;
      }
      residual[i] = weight_[i] * (sum - profile_->value[i]);
    }
    return true;
  }

 private:
  const SampledProfile* profile_;
  std::vector<double> weight_;
  int count_;
  std::shared_ptr<GaussianBasis> basis_;
};

// Parameters: [ln d, ln A]; A is fitted too, since a sampled profile's integral misses what lies
// inside its first and beyond its last radius.
// Holds a channel's weights to sum to its total: 1 % off costs as much as a 30 % L2 misfit.
struct TotalResidual {
  double total;
  int count;
  template <class T>
  bool operator()(T const* const* parameters, T* residual) const {
    T sum = T(0);
    for (int k = 0; k < count; ++k) sum += parameters[0][k];
    residual[0] = T(30.0) * (sum / T(total) - T(1));
    return true;
  }
};

struct BurleyResidual {
  const SampledProfile* profile;
  std::vector<double> weight;
  template <class T>
  bool operator()(const T* x, T* residual) const {
    using std::exp;
    for (std::size_t i = 0; i < profile->size(); ++i) {
      const double r = std::max(profile->radius[i], 1e-300);
      residual[i] = T(weight[i]) * (normalized_diffusion::profile(exp(x[1]), exp(x[0]), T(r)) - T(profile->value[i]));
    }
    return true;
  }
};

// The same with A fixed (ln A given): only ln d is a parameter.
struct BurleyShapeResidual {
  BurleyResidual full;
  double log_albedo;
  template <class T>
  bool operator()(const T* log_d, T* residual) const {
    const T x[2] = {log_d[0], T(log_albedo)};
    return full(x, residual);
  }
};

void check_profiles(const std::vector<NamedProfile>& channels) {
  if (channels.empty()) throw InvalidInput("profile: no channels to fit");
  for (const auto& c : channels) {
    try {
      c.profile.validate();
    } catch (const InvalidInput& e) {
      throw InvalidInput("channel " + c.name + ": " + e.what());
    }
    if (c.profile.size() < 8)
      throw InvalidInput("channel " + c.name + ": radii", std::to_string(c.profile.size()), ">= 8 samples");
    double peak = 0;
    for (double v : c.profile.value) peak = std::max(peak, v);
    if (!(peak > 0))
      throw InvalidInput("channel " + c.name + ": profile", "0 everywhere",
                         "a profile with some reflectance (the channel does not scatter)");
  }
}

double relative_l2(const SampledProfile& p, const std::function<double(double)>& fit) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dr = p.radius[i + 1] - p.radius[i];
    for (std::size_t j : {i, i + 1}) {
      num += 0.5 * dr * p.radius[j] * std::pow(fit(p.radius[j]) - p.value[j], 2);
      den += 0.5 * dr * p.radius[j] * p.value[j] * p.value[j];
    }
  }
  return std::sqrt(num / den);
}

}  // namespace

FitReport fit_gaussians(const std::vector<NamedProfile>& channels, int count, LengthUnit unit,
                        const std::string& source, const std::vector<double>& totals) {
  const auto start = std::chrono::steady_clock::now();
  check_profiles(channels);
  if (!totals.empty() && totals.size() != channels.size())
    throw InvalidInput("gaussians: " + std::to_string(totals.size()) + " totals for " +
                       std::to_string(channels.size()) + " channels");
  if (count < 1 || count > 32) throw InvalidInput("gaussians", std::to_string(count), "1 to 32");
  // Start: standard deviations spread geometrically over the profiles' energy range.
  double r_lo = INFINITY, r_hi = 0;
  for (const auto& c : channels) {
    r_lo = std::min(r_lo, std::max(c.profile.radius_for_fraction(0.05), c.profile.radius[1]));
    r_hi = std::max(r_hi, c.profile.radius_for_fraction(0.99));
  }
  std::vector<double> log_variance(count);
  for (int k = 0; k < count; ++k) {
    const double s = count == 1 ? std::sqrt(r_lo * r_hi) : r_lo * std::pow(r_hi / r_lo, double(k) / (count - 1));
    log_variance[k] = std::log(0.5 * s * s);
  }
  std::vector<std::vector<double>> weight(channels.size());
  ceres::Problem problem;
  std::vector<std::shared_ptr<GaussianBasis>> bases;  // one per distinct set of radii
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const double total = channels[c].profile.integrate();
    weight[c].assign(count, std::max(total, 1e-12) / count);
    const auto& radius = channels[c].profile.radius;
    auto basis = std::find_if(bases.begin(), bases.end(), [&](const auto& b) { return b->serves(radius); });
    if (basis == bases.end()) basis = bases.insert(bases.end(), std::make_shared<GaussianBasis>(radius, count));
    auto* cost = new GaussianResidual(&channels[c].profile, root_weights(channels[c].profile), count, *basis);
    problem.AddResidualBlock(cost, nullptr, log_variance.data(), weight[c].data());
    for (int k = 0; k < count; ++k) problem.SetParameterLowerBound(weight[c].data(), k, 0.0);
    if (!totals.empty()) {
      auto* conserve = new ceres::DynamicAutoDiffCostFunction<TotalResidual, 4>(new TotalResidual{totals[c], count});
      conserve->AddParameterBlock(count);
      conserve->SetNumResiduals(1);
      problem.AddResidualBlock(conserve, nullptr, weight[c].data());
    }
  }
  // Variances between (1e-3 r_lo)^2 and (1e3 r_hi)^2: far outside, a Gaussian is a spike or flat at
  // every sampled radius, and exp(log v) under- or overflows (the residuals became NaN).
  for (int k = 0; k < count; ++k) {
    problem.SetParameterLowerBound(log_variance.data(), k, std::log(0.5 * 1e-6 * r_lo * r_lo));
    problem.SetParameterUpperBound(log_variance.data(), k, std::log(0.5 * 1e6 * r_hi * r_hi));
  }
  ceres::Solver::Options options;
  // Up to 8 Gaussians the normal equations (a 4 count x 4 count Cholesky for three channels) instead of QR of the
  // whole Jacobian: 28 % fewer instructions for the 47 materials' tables at 6, every fit's relative L2 error within
  // 2.3e-13 (6) and 1e-8 (8) of QR's, relative. With more, neighbouring Gaussians' columns grow alike and squaring
  // the condition number shows (24 Gaussians, Marble: L2 0.0098 with QR, 0.0105 with the normal equations).
  options.linear_solver_type = count <= 8 ? ceres::DENSE_NORMAL_CHOLESKY : ceres::DENSE_QR;
  options.max_num_iterations = 2000;
  options.function_tolerance = 1e-12;
  options.num_threads = 1;  // the residual blocks share their GaussianBasis: evaluated one after another
  // Weights pinned at their bound 0 make monotone Levenberg-Marquardt creep (Ketchup, soy and
  // chocolate milk ran out of 2000 iterations); non-monotone steps converge in tens to hundreds.
  options.use_nonmonotonic_steps = true;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  // A Gaussian whose weight vanished in every channel is stuck in a local minimum: move it into
  // the widest gap between the others (in log variance) and solve again; keep the best solution.
  for (int round = 0; round < 2 * count; ++round) {
    double total = 0;
    std::vector<double> mass(count, 0.0);
    for (const auto& w : weight)
      for (int k = 0; k < count; ++k) mass[k] += w[k], total += w[k];
    int dead = -1;
    for (int k = 0; k < count; ++k)
      if (mass[k] < 1e-3 * total) dead = k;
    if (dead < 0 || count < 2) break;
    std::vector<double> others;
    for (int k = 0; k < count; ++k)
      if (k != dead) others.push_back(log_variance[k]);
    std::sort(others.begin(), others.end());
    double best_gap = -1, seed = others.back() + 1;
    for (std::size_t k = 0; k + 1 < others.size(); ++k)
      if (others[k + 1] - others[k] > best_gap) {
        best_gap = others[k + 1] - others[k];
        seed = 0.5 * (others[k] + others[k + 1]);
      }
    const auto saved_variance = log_variance;
    const auto saved_weight = weight;
    const double saved_cost = summary.final_cost;
    log_variance[dead] = seed;
    for (auto& w : weight) w[dead] = 0.05 * total / static_cast<double>(weight.size());
    ceres::Solver::Summary retry;
    ceres::Solve(options, &problem, &retry);
    if (retry.final_cost < saved_cost) {
      summary = retry;
    } else {
      log_variance = saved_variance;
      weight = saved_weight;
      break;
    }
  }

  FitReport report;
  report.kind = "gaussians";
  report.model = std::to_string(count) + " Gaussians, shared variances";
  report.data_source = source;
  report.iterations = static_cast<int>(summary.iterations.size()) - 1;
  report.termination = ceres::TerminationTypeToString(summary.termination_type);
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  report.solver_report = summary.FullReport();
  // Sorted by variance, as renderers list them.
  std::vector<int> order(count);
  for (int k = 0; k < count; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return log_variance[a] < log_variance[b]; });
  const std::string u(symbol(unit));
  for (int k = 0; k < count; ++k)
    report.parameters.push_back(
        {"variance_" + std::to_string(k + 1), "", std::exp(log_variance[order[k]]), NAN, u + "^2"});
  double worst = 0;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    double sum = 0;
    for (int k = 0; k < count; ++k) {
      const double w = weight[c][order[k]];
      sum += w;
      report.parameters.push_back({"weight_" + std::to_string(k + 1), channels[c].name, w, NAN, ""});
    }
    const double error = relative_l2(channels[c].profile, [&](double r) {
      double s = 0;
      for (int k = 0; k < count; ++k)
        s += weight[c][k] * quantized_diffusion::gaussian_2d(std::exp(log_variance[k]), r);
      return s;
    });
    worst = std::max(worst, error);
    report.parameters.push_back({"weight_sum", channels[c].name, sum, NAN, ""});
    report.parameters.push_back({"profile_total", channels[c].name, channels[c].profile.integrate(), NAN, ""});
    report.parameters.push_back({"relative_l2_error", channels[c].name, error, NAN, ""});
  }
  report.relative_rms = worst;
  report.residual_rms = std::sqrt(2 * summary.final_cost / channels.size());
  report.warnings.push_back(
      "uncertainties are not estimated: this is an approximation of a known profile, not a "
      "measurement; relative_l2_error is its quality");
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

FitReport fit_burley(const std::vector<NamedProfile>& channels, LengthUnit unit, const std::string& source,
                     const std::vector<double>& totals) {
  const auto start = std::chrono::steady_clock::now();
  check_profiles(channels);
  if (!totals.empty() && totals.size() != channels.size())
    throw InvalidInput("totals: " + std::to_string(totals.size()) + " values for " + std::to_string(channels.size()) +
                       " channels");
  for (double t : totals)
    if (!(t > 0 && t <= 1))
      throw InvalidInput("total reflectance", format_number(t), "0 < total <= 1 (energy is conserved)");
  FitReport report;
  report.kind = "burley";
  report.model = "normalized diffusion (Christensen & Burley 2015): d and A by least squares";
  report.data_source = source;
  report.converged = true;
  const std::string u(symbol(unit));
  double worst = 0;
  for (std::size_t k = 0; k < channels.size(); ++k) {
    const auto& c = channels[k];
    // Start from the profile's integral and half-energy radius (Burley's r_50 = 1.5436 d).
    std::array<double, 2> x = {
        std::log(c.profile.radius_for_fraction(0.5) / normalized_diffusion::inverse_cdf(1.0, 0.5)),
        std::log(totals.empty() ? c.profile.integrate() : totals[k])};
    ceres::Problem problem;
    // A given total is Burley's A itself (his surface albedo, the profile's energy): only d is
    // fitted. Free, A absorbs the misfit of the shape and can exceed 1.
    if (totals.empty())
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<BurleyResidual, ceres::DYNAMIC, 2>(
              new BurleyResidual{&c.profile, root_weights(c.profile)}, static_cast<int>(c.profile.size())),
          nullptr, x.data());
    else
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<BurleyShapeResidual, ceres::DYNAMIC, 1>(
              new BurleyShapeResidual{{&c.profile, root_weights(c.profile)}, x[1]}, static_cast<int>(c.profile.size())),
          nullptr, x.data());
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.function_tolerance = 1e-14;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    report.iterations += static_cast<int>(summary.iterations.size()) - 1;
    report.converged &= summary.termination_type == ceres::CONVERGENCE;
    const double d = std::exp(x[0]), A = std::exp(x[1]);
    const double error =
        relative_l2(c.profile, [&](double r) { return normalized_diffusion::profile(A, d, std::max(r, 1e-300)); });
    worst = std::max(worst, error);
    report.parameters.push_back({"burley_d", c.name, d, NAN, u});
    report.parameters.push_back({"surface_albedo", c.name, A, NAN, ""});
    report.parameters.push_back({"profile_total", c.name, c.profile.integrate(), NAN, ""});
    report.parameters.push_back({"relative_l2_error", c.name, error, NAN, ""});
  }
  report.termination = report.converged ? "CONVERGENCE" : "NO_CONVERGENCE";
  report.relative_rms = worst;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::vector<NamedProfile> named_profiles_in_own_unit(const MeasuredProfile& measured) {
  const double mm = millimetres_per(measured.unit);
  std::vector<NamedProfile> out;
  for (const auto& c : measured.channels) {
    NamedProfile p{c.name, {}};
    for (std::size_t i = 0; i < measured.radius.size(); ++i) {
      p.profile.radius.push_back(measured.radius[i] / mm);
      p.profile.value.push_back(c.value[i] * mm * mm);
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace bssrdf
