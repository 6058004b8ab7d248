// The inversion shared by 'fit slab' and the integrating-sphere files: measured (R, T[, U]) with
// standard errors -> sigma_a, sigma_s' [, g] by weighted least squares (Ceres, numeric
// differences through the forward solver), with the covariance, the share of each measurement
// in each parameter's variance, and chi^2.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <string>

namespace bssrdf {

struct SlabParameters {
  double sigma_a, sigma_s_prime, g;  // 1/mm
};

// Predicted measurements for the parameters (the same quantities as measured, in the same order).
using SlabForward = std::function<std::array<double, 3>(const SlabParameters&)>;

struct SlabInversion {
  SlabParameters parameters{};
  std::array<double, 3> standard_error{};        // of sigma_a, sigma_s' (1/mm) and g; finite always
  double albedo_prime_stderr = 0;                // of sigma_s'/(sigma_a + sigma_s')
  std::array<std::array<double, 3>, 3> share{};  // share[p][m]: fraction of parameter p's variance from measurement m
  bool determined = true;                        // false: the Jacobian was (numerically) singular
  std::array<double, 3> predicted{};
  double chi2 = 0;
  int iterations = 0;
  bool converged = false;
  std::string termination;
};

// The least-squares settings of the slab inversions (tolerances ~1e-10 in the parameters' logarithms).
ceres::Solver::Options slab_solver_options();

// `count` measurements (2: R, T; 3: R, T, U). With fit_g, g is a parameter (start `g`), else held.
// `forward` is evaluated at fixed accuracy; `coarse` (a cheaper forward) picks the starting point
// on a grid and, when `search` is given, a first least-squares solve runs on it (cheaper still)
// before the final one on `forward` polishes the result.
SlabInversion invert_slab(const std::array<double, 3>& measured, const std::array<double, 3>& stderr_, int count,
                          bool fit_g, double g, double thickness_mm, const SlabForward& forward,
                          const SlabForward& coarse, const SlabForward* search = nullptr);

}  // namespace bssrdf
