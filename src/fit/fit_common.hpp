// Helpers shared by the fits (private to src/fit).
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "bssrdf/model.hpp"

namespace bssrdf {

// The covariance of the given parameter blocks (in order, all entries), or nothing when Ceres
// finds the Jacobian rank-deficient.
std::optional<Eigen::MatrixXd> parameter_covariance(ceres::Problem& problem, const std::vector<const double*>& blocks);


}  // namespace bssrdf
