#include "bssrdf/reference_comparison.hpp"

#include <cmath>
#include <numbers>

namespace bssrdf {

double model_bin_average(const Model& model, const Reduced<double>& m, double inner, double outer) {
  const double area = std::numbers::pi * (outer * outer - inner * inner);
  return (model.cumulative_reflectance(m, outer) - model.cumulative_reflectance(m, inner)) / area;
}

ProfileDeviation compare_with_monte_carlo(const Model& model, const Reduced<double>& m, const MonteCarloResult& run,
                                          std::size_t channel) {
  const auto mc = run.channels.at(channel).per_entered_flux();
  // [all, near, far] sums of area * (difference^2, tally^2, stderr^2)
  double diff[3] = {0, 0, 0}, norm[3] = {0, 0, 0}, noise[3] = {0, 0, 0};
  double r_diff[3] = {0, 0, 0}, r_norm[3] = {0, 0, 0}, r_noise[3] = {0, 0, 0};  // r R(r) over dr
  for (std::size_t i = 0; i < mc.reflectance.size(); ++i) {
    const double inner = run.bin_inner[i], outer = run.bin_outer[i];
    const double area = std::numbers::pi * (outer * outer - inner * inner);
    const double average = model_bin_average(model, m, inner, outer);
    for (int part : {0, outer <= m.ell ? 1 : 2}) {
      diff[part] += area * std::pow(average - mc.reflectance[i], 2);
      norm[part] += area * std::pow(mc.reflectance[i], 2);
      noise[part] += area * std::pow(mc.reflectance_stderr[i], 2);
      const double weight = (outer - inner) * run.bin_radius[i] * run.bin_radius[i];
      r_diff[part] += weight * std::pow(average - mc.reflectance[i], 2);
      r_norm[part] += weight * std::pow(mc.reflectance[i], 2);
      r_noise[part] += weight * std::pow(mc.reflectance_stderr[i], 2);
    }
  }
  ProfileDeviation d;
  d.total = model.total_reflectance(m) / mc.diffuse_reflectance.value - 1;
  d.l2 = std::sqrt(diff[0] / norm[0]), d.near = std::sqrt(diff[1] / norm[1]), d.far = std::sqrt(diff[2] / norm[2]);
  d.l2_noise = std::sqrt(noise[0] / norm[0]), d.near_noise = std::sqrt(noise[1] / norm[1]),
  d.far_noise = std::sqrt(noise[2] / norm[2]);
  d.near_r = std::sqrt(r_diff[1] / r_norm[1]), d.far_r = std::sqrt(r_diff[2] / r_norm[2]);
  d.near_r_noise = std::sqrt(r_noise[1] / r_norm[1]), d.far_r_noise = std::sqrt(r_noise[2] / r_norm[2]);
  return d;
}

}  // namespace bssrdf
