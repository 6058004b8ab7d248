#include "fit_common.hpp"

#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/model_registry.hpp"

namespace bssrdf {

std::optional<Eigen::MatrixXd> parameter_covariance(ceres::Problem& problem, const std::vector<const double*>& blocks) {
  // Eigen's SVD does not survive an infinite or NaN Jacobian (it crashed on data of 1e308): such a
  // fit has no covariance.
  double cost = 0;
  ceres::CRSMatrix jacobian;
  if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, &jacobian) || !std::isfinite(cost))
    return std::nullopt;
  for (const double v : jacobian.values)
    if (!std::isfinite(v)) return std::nullopt;
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.null_space_rank = -1;  // refuse rank-deficient problems instead of pseudo-inverting them
  ceres::Covariance covariance(options);
  std::vector<std::pair<const double*, const double*>> pairs;
  for (auto* a : blocks)
    for (auto* b : blocks) pairs.emplace_back(a, b);
  if (!covariance.Compute(pairs, &problem)) return std::nullopt;
  std::vector<int> size, offset;
  int total = 0;
  for (auto* b : blocks) {
    size.push_back(problem.ParameterBlockTangentSize(b));
    offset.push_back(total);
    total += size.back();
  }
  Eigen::MatrixXd out(total, total);
  for (std::size_t i = 0; i < blocks.size(); ++i)
    for (std::size_t j = 0; j < blocks.size(); ++j) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(size[i], size[j]);
      covariance.GetCovarianceBlockInTangentSpace(blocks[i], blocks[j], block.data());
      out.block(offset[i], offset[j], size[i], size[j]) = block;
    }
  return out;
}

}  // namespace bssrdf
