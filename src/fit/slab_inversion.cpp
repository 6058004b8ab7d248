// Weighted least-squares inversion of slab measurements; see slab_inversion.hpp.
#include "slab_inversion.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>

namespace bssrdf {

namespace {

// x = (ln sigma_a, ln sigma_s' [, atanh g]): positive coefficients and |g| < 1 without bounds.
SlabParameters from_x(const double* x, bool fit_g, double g) {
  return {std::exp(x[0]), std::exp(x[1]), fit_g ? std::tanh(x[2]) : g};
}

struct Residual {
  const SlabForward* forward;
  std::array<double, 3> measured, sigma;
  int count;
  bool fit_g;
  double g;
  bool operator()(double const* const* x, double* residual) const {
    const auto predicted = (*forward)(from_x(x[0], fit_g, g));
    for (int m = 0; m < count; ++m) residual[m] = (predicted[m] - measured[m]) / sigma[m];
    return true;
  }
};

template <ceres::NumericDiffMethodType method>
ceres::CostFunction* numeric_cost(const Residual& residual, int parameters, int residuals) {
  auto* cost = new ceres::DynamicNumericDiffCostFunction<Residual, method>(new Residual(residual));
  cost->AddParameterBlock(parameters);
  cost->SetNumResiduals(residuals);
  return cost;
}

}  // namespace

ceres::Solver::Options slab_solver_options() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
  options.gradient_tolerance = 1e-14;
  // Ceres refines every step of a bounded problem by a projected line search; with cubic
  // interpolation (the default) each trial costs a Jacobian, with quadratic only a solve.
  options.line_search_interpolation_type = ceres::QUADRATIC;
  return options;
}

SlabInversion invert_slab(const std::array<double, 3>& measured, const std::array<double, 3>& stderr_, int count,
                          bool fit_g, double g, double d, const SlabForward& forward, const SlabForward& coarse,
                          const SlabForward* search) {
  const int p = fit_g ? 3 : 2;
  // Starting point: the best of a coarse grid of reduced albedo and reduced optical thickness.
  double best_cost = INFINITY;
  std::array<double, 3> x{0, 0, fit_g ? std::atanh(g) : 0};
  for (double a : {0.3, 0.7, 0.9, 0.97, 0.99, 0.997})
    for (double optical : {0.3, 1.0, 3.0, 10.0, 30.0}) {
      const SlabParameters trial{(1 - a) * optical / d, a * optical / d, g};
      const auto predicted = coarse(trial);
      double cost = 0;
      for (int m = 0; m < count; ++m) cost += std::pow((predicted[m] - measured[m]) / stderr_[m], 2);
      if (cost < best_cost) {
        best_cost = cost;
        x[0] = std::log(trial.sigma_a);
        x[1] = std::log(trial.sigma_s_prime);
      }
    }
  // Least squares on the search forward (or the final one when there is none), by Ceres.
  ceres::Solver::Summary summary;
  {
    Residual stage_residual{search ? search : &forward, measured, stderr_, count, fit_g, g};
    // Forward differences when a polish follows (they cost p solves per Jacobian instead of 2p,
    // and the search only has to come close); central ones when this is the final solve.
    auto* cost = search ? numeric_cost<ceres::FORWARD>(stage_residual, p, count)
                        : numeric_cost<ceres::CENTRAL>(stage_residual, p, count);
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, x.data());
    for (int i = 0; i < 2; ++i) {  // 1e-11 to 1e11 per mm
      problem.SetParameterLowerBound(x.data(), i, -25);
      problem.SetParameterUpperBound(x.data(), i, 25);
    }
    if (fit_g) {
      problem.SetParameterLowerBound(x.data(), 2, -3.8);  // |g| < 0.999
      problem.SetParameterUpperBound(x.data(), 2, 3.8);
    }
    // Without g, no projected line search after each trust-region step (Ceres does one on bounded
    // problems): the bounds on ln sigma are never near a solution's, and the searches cost a solve
    // per step (basic_B at 8 angles: 117.6 M instructions instead of 145.8 M, same results to
    // 5e-12 on rows solved exactly). With g fitted the line search is kept: without it basic_C
    // (M_U) ends in other minima (g 0.90 -> 1.00 on row 4).
    auto solver = slab_solver_options();
    if (!fit_g) solver.max_num_line_search_step_size_iterations = 0;
    ceres::Solve(solver, &problem, &summary);
  }
  int polish_steps = 0;

  // The Jacobian of the weighted residuals in x (central differences) and the residuals.
  auto jacobian = [&](const Residual& res, const std::array<double, 3>& at, Eigen::VectorXd& r) {
    Eigen::MatrixXd J(count, p);
    double residual_plus[3], residual_minus[3], centre[3];
    const double* b = at.data();
    res(&b, centre);
    r = Eigen::Map<Eigen::VectorXd>(centre, count);
    for (int j = 0; j < p; ++j) {
      std::array<double, 3> xp = at, xm = at;
      const double h = 1e-5;
      xp[j] += h;
      xm[j] -= h;
      const double* bp = xp.data();
      const double* bm = xm.data();
      res(&bp, residual_plus);
      res(&bm, residual_minus);
      for (int m = 0; m < count; ++m) J(m, j) = (residual_plus[m] - residual_minus[m]) / (2 * h);
    }
    return J;
  };
  // With a cheaper search, Gauss-Newton steps on the final forward polish the result (its
  // optimum is within the search forward's error of the start: one or two steps). The Jacobian
  // is the search forward's: the two differ by the search's angular error (~1e-4 in R and T),
  // so a step leaves ~1e-3 of the remaining error, and only the residuals cost a final solve.
  const Residual search_residual{search ? search : &forward, measured, stderr_, count, fit_g, g};
  Eigen::VectorXd r;
  Eigen::MatrixXd J = jacobian(search_residual, x, r);
  std::array<double, 3> predicted{};
  auto final_residual = [&](const std::array<double, 3>& at) {
    predicted = forward(from_x(at.data(), fit_g, g));
    Eigen::VectorXd residuals(count);
    for (int m = 0; m < count; ++m) residuals(m) = (predicted[m] - measured[m]) / stderr_[m];
    return residuals;
  };
  if (search) r = final_residual(x);
  while (search && polish_steps < 4) {
    const Eigen::VectorXd step = J.completeOrthogonalDecomposition().solve(-r);
    const auto previous_x = x;
    const auto previous_predicted = predicted;
    for (int j = 0; j < p; ++j) x[j] = std::clamp(x[j] + step(j), j < 2 ? -25.0 : -3.8, j < 2 ? 25.0 : 3.8);
    const Eigen::VectorXd previous_r = r;
    r = final_residual(x);
    // A step that raises chi^2 (a near-singular Jacobian far from any optimum, e.g. data out of
    // the model's reach) is not taken: the polish never leaves a worse point than it started from.
    if (r.squaredNorm() > previous_r.squaredNorm()) {
      x = previous_x;
      r = previous_r;
      predicted = previous_predicted;
      break;
    }
    ++polish_steps;
    // A step below 1e-3 (0.1 % in the coefficients) leaves O(1e-6) to go, and the Jacobian at
    // the previous point serves the covariance to 0.2 %.
    if (step.cwiseAbs().maxCoeff() < 1e-3) break;
    Eigen::VectorXd search_r;
    J = jacobian(search_residual, x, search_r);
  }

  SlabInversion out;
  out.parameters = from_x(x.data(), fit_g, g);
  out.predicted = search ? predicted : forward(out.parameters);
  for (int m = 0; m < count; ++m) out.chi2 += std::pow((out.predicted[m] - measured[m]) / stderr_[m], 2);
  out.iterations = static_cast<int>(summary.iterations.size()) - 1 + polish_steps;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.termination = ceres::TerminationTypeToString(summary.termination_type);

  // Linear propagation: with J the Jacobian of the weighted residuals in x, the parameters move by
  // K = (J^T J)^-1 J^T per unit of weighted measurement error, so Cov(x) = K K^T and row p of K
  // says how much each measurement contributes to parameter p's variance.
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto s = svd.singularValues();
  out.determined = s.size() == p && s(p - 1) > 1e-9 * s(0);
  // Pseudo-inverse with singular values floored at 1e-9 of the largest: an undetermined
  // combination gets a huge (finite) error instead of NaN, and the report says so. The absolute
  // floor 1e-100 keeps the squared errors finite where the data do not move at all (a Jacobian
  // of zeros, e.g. everything absorbed).
  Eigen::VectorXd inverse(s.size());
  for (int k = 0; k < s.size(); ++k) inverse(k) = 1 / std::max(s(k), std::max(1e-9 * s(0), 1e-100));
  const Eigen::MatrixXd K = svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();  // p x count
  for (int j = 0; j < p; ++j) {
    const double variance = K.row(j).squaredNorm();
    const double scale = j == 0   ? out.parameters.sigma_a
                         : j == 1 ? out.parameters.sigma_s_prime
                                  : 1 - out.parameters.g * out.parameters.g;
    out.standard_error[j] = scale * std::sqrt(variance);  // d exp(x) = exp(x) dx, d tanh(x) = (1 - tanh^2) dx
    for (int m = 0; m < count; ++m) out.share[j][m] = variance > 0 ? K(j, m) * K(j, m) / variance : 0;
  }
  const double a = out.parameters.sigma_a, sp = out.parameters.sigma_s_prime;
  const double slope = a * sp / ((a + sp) * (a + sp));  // d alpha'/d ln sigma_s' = -d alpha'/d ln sigma_a
  out.albedo_prime_stderr = slope * (K.row(1) - K.row(0)).norm();
  return out;
}

}  // namespace bssrdf
