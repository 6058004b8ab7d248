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

// The reduced albedo whose total reflectance under `model` is `total`, for a medium with
// anisotropy g and index eta (the total of models with single scattering depends on g). Exact
// root finding (bracketing + secant), no table. Throws InvalidInput when no alpha' in [0, 1]
// reaches `total`.
double albedo_prime_for_total(const Model& model, double total, double eta, double g);

}  // namespace bssrdf
