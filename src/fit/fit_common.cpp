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

double albedo_prime_for_total(const Model& model, double total, double eta, double g) {
  if (const auto* entry = find_model_entry(model.name()); entry && entry->albedo_prime_for_total)
    return entry->albedo_prime_for_total(total, g, eta);
  const auto total_at = [&](double a) { return model.total_reflectance(reduced_optical(a, g, eta)); };
  double lo = 0, hi = 1;
  double f_lo = total_at(lo) - total, f_hi = total_at(hi) - total;
  if (!(f_lo <= 0 && f_hi >= 0) || !std::isfinite(total))
    throw InvalidInput("total reflectance", format_number(total),
                       "[" + format_number(f_lo + total) + ", " + format_number(f_hi + total) + "] for the " +
                           model.name() + " model at eta = " + format_number(eta) + ", g = " + format_number(g));
  // Illinois regula falsi: superlinear, never leaves the bracket.
  int side = 0;
  for (int iter = 0; iter < 100 && hi - lo > 1e-15; ++iter) {
    const double a = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const double f = total_at(a) - total;
    if (f == 0) return a;
    if ((f > 0) == (f_hi > 0)) {
      hi = a;
      f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    } else {
      lo = a;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
    if (std::abs(f) < 1e-15 * std::max(total, 1e-300)) return a;
  }
  return 0.5 * (lo + hi);
}

}  // namespace bssrdf
