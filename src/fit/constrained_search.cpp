// iad's constrained inversions; see constrained_search.hpp.
#include "constrained_search.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/root_finding.hpp"

namespace bssrdf {

bool RxtConstraintOptions::any() const {
  return !std::isnan(albedo) || !std::isnan(optical_thickness) || !std::isnan(mu_a) || !std::isnan(mu_s) ||
         !std::isnan(mu_s_prime) || !std::isnan(power_mu_s0);
}

std::optional<RowConstraint> row_constraint(const RxtRow& row, const RxtConstraintOptions& o, double g_option) {
  using Kind = RowConstraint::Kind;
  const auto& k = row.constraints;
  // -F as a power law and -j resolve to mu_s (iad_main.w); the option wins over the row's column.
  double mu_s = o.mu_s;
  std::string mu_s_source = "iad -F";
  if (!std::isnan(o.power_mu_s0)) {
    if (!row.has_wavelength)
      throw InvalidInput("--fixed-mu-s power law", "row " + std::to_string(row.line) + " without a wavelength",
                         "a file with wavelengths (column L or the first value > 1)");
    mu_s = o.power_mu_s0 * std::pow(row.wavelength / o.power_lambda0, o.power_gamma);
    mu_s_source = "iad -F 'P " + format_number(o.power_lambda0) + " " + format_number(o.power_mu_s0) + " " +
                  format_number(o.power_gamma) + "'";
  }
  if (!std::isnan(o.mu_s_prime)) {
    mu_s = std::isnan(g_option) ? o.mu_s_prime : o.mu_s_prime / (1 - g_option);
    mu_s_source = "iad -j";
  }
  struct Candidate {
    Kind kind;
    double option, column;
    const char *name, *option_source, *column_source;
  };
  const Candidate candidates[] = {
      {Kind::albedo, o.albedo, k.albedo, "a", "iad -a", "column a"},
      {Kind::optical_thickness, o.optical_thickness, k.optical_thickness, "b", "iad -b", "column b"},
      {Kind::mu_a, o.mu_a, k.mu_a, "mu_a", "iad -A", "column A"},
      {Kind::mu_s, mu_s, k.mu_s, "mu_s", "", "column F"},
  };
  std::optional<RowConstraint> found;
  for (const auto& c : candidates) {
    const bool from_option = !std::isnan(c.option);
    const double v = from_option ? c.option : c.column;
    if (std::isnan(v)) continue;
    const std::string source = from_option ? (c.kind == Kind::mu_s ? mu_s_source : c.option_source) : c.column_source;
    if (found)
      throw InvalidInput("constraints " + found->label + " and " + c.name + " (" + source + ") on row " +
                         std::to_string(row.line) + ": supported is one of a, b, mu_a, mu_s per row");
    const bool ok = c.kind == Kind::albedo ? v >= 0 && v <= 1 : v >= 0 && std::isfinite(v);
    if (!ok)
      throw InvalidInput(std::string("constraint ") + c.name + " (" + source + ")", format_number(v),
                         c.kind == Kind::albedo ? "[0, 1]" : "a finite number >= 0");
    found = RowConstraint{c.kind, v, std::string(c.name) + " = " + format_number(v) + " (" + source + ")"};
  }
  return found;
}

namespace {

enum class Unknown { albedo, optical_thickness, sigma_a, sigma_s, g };

const char* name_of(Unknown u) {
  static const char* const names[] = {"a", "b", "mu_a", "mu_s", "g"};
  return names[static_cast<int>(u)];
}

// The search variable x of each unknown and its bounds: a = 1/(1 + e^-x), b, mu = e^x, g = tanh x.
std::pair<double, double> bounds_of(Unknown u) {
  switch (u) {
    case Unknown::albedo:
      return {-30, 30};
    case Unknown::optical_thickness:
      return {std::log(1e-6), std::log(1e6)};
    case Unknown::g:
      return {-3.8, 3.8};  // |g| < 0.999
    default:
      return {-25, 12};  // 1e-11 to 1.6e5 per mm
  }
}

double value_of(Unknown u, double x) {
  switch (u) {
    case Unknown::albedo:
      return 1 / (1 + std::exp(-x));
    case Unknown::g:
      return std::tanh(x);
    default:
      return std::exp(x);
  }
}

// Starting values of the two-unknown grid (optical depths per thickness for the coefficients).
std::vector<double> grid_of(Unknown u, double d) {
  std::vector<double> x;
  switch (u) {
    case Unknown::albedo:
      for (double a : {0.3, 0.7, 0.9, 0.97, 0.99, 0.997}) x.push_back(std::log(a / (1 - a)));
      break;
    case Unknown::optical_thickness:
      for (double b : {0.1, 0.3, 1.0, 3.0, 10.0, 30.0}) x.push_back(std::log(b));
      break;
    case Unknown::g:
      for (double g : {-0.3, 0.0, 0.3, 0.6, 0.8, 0.9}) x.push_back(std::atanh(g));
      break;
    default:
      for (double b : {0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0}) x.push_back(std::log(b / d));
  }
  return x;
}

// A sample the search tries: what the forward sees and what is reported (they differ for a
// semi-infinite sample, whose coefficients follow iad's Calculate_Mua_Musp conventions).
struct Sample {
  double sigma_a, sigma_s, g, d;
  double mu_a, mu_s;
};

struct Search {
  RowConstraint constraint;
  std::vector<Unknown> free;
  bool semi_infinite = false, use_r = false, use_t = false;
  double g = 0, d = 1;

  Sample at(const double* x) const {
    double a = NAN, b = NAN, sa = NAN, ss = NAN, g_at = g;
    double* held[] = {&a, &b, &sa, &ss};
    *held[static_cast<int>(constraint.kind)] = constraint.value;
    for (std::size_t k = 0; k < free.size(); ++k) {
      const double v = value_of(free[k], x[k]);
      if (free[k] == Unknown::g)
        g_at = v;
      else
        *held[static_cast<int>(free[k])] = v;
    }
    if (semi_infinite) {
      Sample s{1 - a, a, g_at, kSemiInfinite, (1 - a) / a, 1.0};
      if (a <= 1e-5) {
        s.mu_a = 1;
        s.mu_s = 0;
      } else if (constraint.kind == RowConstraint::Kind::mu_s) {
        s.mu_s = constraint.value;
        s.mu_a = constraint.value / a - constraint.value;
      } else if (constraint.kind == RowConstraint::Kind::mu_a) {
        s.mu_a = constraint.value;
        s.mu_s = constraint.value / (1 - a) - constraint.value;
      }
      return s;
    }
    if (!std::isnan(b)) {
      sa = (1 - a) * b / d;
      ss = a * b / d;
    }
    return {sa, ss, g_at, d, sa, ss};
  }
};

// iad's determine_search for one constraint.
Search plan(const RowConstraint& c, double m_r, double m_t, double g_held, double d) {
  using Kind = RowConstraint::Kind;
  Search s{c, {}, false, false, false, std::isnan(g_held) ? 0.0 : g_held, d};
  const Unknown other = c.kind == Kind::albedo              ? Unknown::optical_thickness
                        : c.kind == Kind::optical_thickness ? Unknown::albedo
                        : c.kind == Kind::mu_a              ? Unknown::sigma_s
                                                            : Unknown::sigma_a;
  const bool R = m_r > 0, T = m_t > 0;
  if (R && T) {
    s.use_t = true;
    s.free = {other};
    if (!(c.kind == Kind::albedo && c.value == 0) && std::isnan(g_held)) {
      s.free.push_back(Unknown::g);
      s.use_r = true;
    }
  } else if (T) {
    s.use_t = true;
    s.free = {other};
  } else {
    s.use_r = true;
    if (c.kind == Kind::optical_thickness) {
      s.free = {Unknown::albedo};
    } else if (c.kind != Kind::albedo) {
      s.free = {Unknown::albedo};
      s.semi_infinite = true;
    } else if (c.value == 0 || c.value == 1) {
      s.free = {Unknown::optical_thickness};
    } else {
      s.free = {Unknown::g};
      s.semi_infinite = true;
    }
  }
  return s;
}

struct Residuals {
  const Search* search;
  const SampleReadings* readings;
  double m_r, m_t, r_stderr, t_stderr;
  // Weighted residuals of the matched measurements (M_R first); returns the readings too.
  std::pair<double, double> operator()(const double* x, double* residual) const {
    const Sample s = search->at(x);
    const auto readings_at = (*readings)(s.sigma_a, s.sigma_s, s.g, s.d);
    int m = 0;
    if (search->use_r) residual[m++] = (readings_at.first - m_r) / r_stderr;
    if (search->use_t) residual[m++] = (readings_at.second - m_t) / t_stderr;
    return readings_at;
  }
  bool operator()(double const* const* x, double* residual) const {
    (*this)(x[0], residual);
    return true;
  }
};

}  // namespace

ConstrainedSolution solve_constrained(const RowConstraint& constraint, double m_r, double m_t, double r_stderr,
                                      double t_stderr, double g_held, double thickness,
                                      const SampleReadings& readings) {
  const Search search = plan(constraint, m_r, m_t, g_held, thickness);
  const int p = static_cast<int>(search.free.size());
  const int count = int(search.use_r) + int(search.use_t);
  const Residuals residuals{&search, &readings, m_r, m_t, r_stderr, t_stderr};
  ConstrainedSolution out;
  out.search = constraint.label + " held; ";
  for (int k = 0; k < p; ++k) out.search += std::string(k ? ", " : "") + name_of(search.free[k]);
  out.search += std::string(" from ") + (search.use_r && search.use_t ? "M_R, M_T" : search.use_r ? "M_R" : "M_T");
  if (search.semi_infinite) out.search += " (semi-infinite sample, as iad)";
  auto& inv = out.inversion;

  std::array<double, 2> x{};
  if (p == 1) {
    // The bracketing interval of a sign change on a grid of the range, then TOMS 748.
    const auto [lo, hi] = bounds_of(search.free[0]);
    auto f = [&](double at) {
      double r[2];
      residuals(&at, r);
      return r[0];
    };
    constexpr int kGrid = 24;
    std::array<double, kGrid + 1> xs{}, fs{};
    int best = 0, bracket = -1;
    for (int k = 0; k <= kGrid; ++k) {
      xs[k] = lo + (hi - lo) * k / kGrid;
      fs[k] = f(xs[k]);
      if (std::abs(fs[k]) < std::abs(fs[best])) best = k;
      if (k > 0 && bracket < 0 && (fs[k - 1] <= 0) != (fs[k] <= 0)) bracket = k - 1;
    }
    if (bracket >= 0) {
      // Stops at a bracket 2^-44 of its size (iad's tolerance is far looser).
      const BracketedRoot root =
          illinois_root(f, xs[bracket], xs[bracket + 1], fs[bracket], fs[bracket + 1], 0.0, 0x1p-44);
      x[0] = root.x;
      inv.converged = true;
      inv.termination = "CONVERGENCE";
      inv.iterations = root.steps;
    } else {
      x[0] = xs[best];
      inv.termination = std::string("NO_CONVERGENCE (no ") + name_of(search.free[0]) + " reproduces " +
                        (search.use_r ? "M_R" : "M_T") + ")";
    }
  } else {
    // The best point of a grid of both unknowns, then Levenberg-Marquardt.
    double best_cost = INFINITY;
    for (double x0 : grid_of(search.free[0], thickness))
      for (double x1 : grid_of(search.free[1], thickness)) {
        const double at[2] = {x0, x1};
        double r[2];
        residuals(at, r);
        const double cost = r[0] * r[0] + r[1] * r[1];
        if (cost < best_cost) {
          best_cost = cost;
          x = {x0, x1};
        }
      }
    auto* cost = new ceres::DynamicNumericDiffCostFunction<Residuals, ceres::CENTRAL>(new Residuals(residuals));
    cost->AddParameterBlock(p);
    cost->SetNumResiduals(count);
    ceres::Problem problem;
    problem.AddResidualBlock(cost, nullptr, x.data());
    for (int k = 0; k < p; ++k) {
      problem.SetParameterLowerBound(x.data(), k, bounds_of(search.free[k]).first);
      problem.SetParameterUpperBound(x.data(), k, bounds_of(search.free[k]).second);
    }
    ceres::Solver::Summary summary;
    ceres::Solve(slab_solver_options(), &problem, &summary);
    inv.converged = summary.termination_type == ceres::CONVERGENCE;
    inv.termination = ceres::TerminationTypeToString(summary.termination_type);
    inv.iterations = static_cast<int>(summary.iterations.size()) - 1;
  }

  // The solution, its readings and chi^2 over the matched measurements.
  double r[2];
  const auto readings_at = residuals(x.data(), r);
  inv.predicted = {readings_at.first, readings_at.second, 0};
  for (int m = 0; m < count; ++m) inv.chi2 += r[m] * r[m];
  auto reported = [&](const std::array<double, 2>& at) {
    const Sample s = search.at(at.data());
    return Eigen::Vector3d(s.mu_a, s.mu_s * (1 - s.g), s.g);  // mu_a, mu_s', g as iad prints them
  };
  const Eigen::Vector3d q = reported(x);
  inv.parameters = {q(0), q(1), q(2)};

  // Errors: the Jacobian J of the weighted residuals in x and G of the reported values in x
  // (central differences); Cov(q) = G (J^T J)^+ G^T, singular values floored as in invert_slab.
  Eigen::MatrixXd J(count, p), G(3, p);
  const double h = 1e-5;
  for (int j = 0; j < p; ++j) {
    auto xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    double rp[2], rm[2];
    residuals(xp.data(), rp);
    residuals(xm.data(), rm);
    for (int m = 0; m < count; ++m) J(m, j) = (rp[m] - rm[m]) / (2 * h);
    G.col(j) = (reported(xp) - reported(xm)) / (2 * h);
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto s = svd.singularValues();
  inv.determined = s.size() == p && s(p - 1) > 1e-9 * s(0);
  Eigen::VectorXd inverse(s.size());
  for (int k = 0; k < s.size(); ++k) inverse(k) = 1 / std::max(s(k), std::max(1e-9 * s(0), 1e-100));
  const Eigen::MatrixXd K = G * svd.matrixV() * inverse.asDiagonal() * svd.matrixU().transpose();  // 3 x count
  for (int j = 0; j < 3; ++j) inv.standard_error[j] = K.row(j).norm();
  return out;
}

}  // namespace bssrdf
