// The exact table generator's fit of a noisy near field (generator version 10; data/exact/README.md).
// In a strongly forward, nearly non-absorbing medium few photons come out within 0.01 transport mfp
// of the entry (g 0.999: 2-20 of 131 072 per radius bin), so each bin is noise, while the profile
// is smooth there: y_ms ~ r^s with s near 1 (quasi-single scattering, R ~ 1/r) from 0.001 to beyond
// 0.1 transport mfp. One fit over that whole range pools its photons: ln y_ms = a cubic in ln r by
// Poisson maximum likelihood (log link), whose score equations sum_k (tally_k - fit_k) x_k^j = 0
// hold for any tally scale and for empty bins, unlike a least-squares fit of ln tally.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace bssrdf::exact_table {

struct NearFieldFit {
  std::vector<double> mean, se;  // the fit's bin means and standard errors at bins 0 .. last
  double chi2_per_dof = 0;       // Pearson's, with the variance phi * fit from the run's own errors
  bool converged = false;
};

// Fits bins 0 .. last of `mean` (bin means of y_ms, one per radius, spaced d_ln_r in ln r) with
// standard errors `se`. The variance is modelled as phi * fit_k (a compound Poisson tally: photons
// of similar weight), phi = sum se^2 / sum mean over the range, so a bin's own noisy error never
// weights it.
inline NearFieldFit fit_near_field(const std::vector<double>& mean, const std::vector<double>& se, std::size_t last,
                                   double d_ln_r) {
  using Vector = Eigen::Vector4d;  // a cubic in x = (k - last) d_ln_r
  NearFieldFit out;
  const std::size_t n = last + 1;
  if (n <= 6 || n > mean.size()) return out;  // a cubic through 6 bins would follow the noise
  const auto basis = [&](std::size_t k) {
    const double x = (static_cast<double>(k) - static_cast<double>(last)) * d_ln_r;
    return Vector(1, x, x * x, x * x * x);
  };
  double sum_mean = 0, sum_var = 0, tail = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sum_mean += mean[k];
    sum_var += se[k] * se[k];
  }
  for (std::size_t k = n - 3; k < n; ++k) tail += mean[k] / 3;
  if (!(sum_mean > 0 && sum_var > 0 && tail > 0)) return out;
  Vector c(std::log(tail), 1, 0, 0);        // start: y ~ r through the last bins
  Eigen::LLT<Eigen::Matrix4d> information;  // of X' diag(fit) X, symmetric positive definite
  for (int iteration = 0; iteration < 100 && !out.converged; ++iteration) {
    Vector gradient = Vector::Zero();
    Eigen::Matrix4d h = Eigen::Matrix4d::Zero();
    for (std::size_t k = 0; k < n; ++k) {
      const Vector b = basis(k);
      const double fit = std::exp(c.dot(b));
      gradient += (mean[k] - fit) * b;
      h += fit * b * b.transpose();
    }
    information.compute(h);
    if (information.info() != Eigen::Success) return out;
    // Newton's step, each component bounded so a first step from far away stays finite.
    const Vector step = information.solve(gradient).cwiseMax(-2.0).cwiseMin(2.0);
    c += step;
    out.converged = step.cwiseAbs().maxCoeff() < 1e-12;
  }
  if (!out.converged) return out;
  // Covariance phi (X' diag(fit) X)^-1, from the last iteration's factor (its step was below 1e-12).
  out.mean.resize(n);
  out.se.resize(n);
  for (std::size_t k = 0; k < n; ++k) out.mean[k] = std::exp(c.dot(basis(k)));
  double fit_sum = 0;
  for (double v : out.mean) fit_sum += v;
  const double phi = sum_var / fit_sum;
  double chi2 = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vector b = basis(k);
    const double ln_variance = b.dot(information.solve(b));  // of ln fit_k
    out.se[k] = out.mean[k] * std::sqrt(phi * ln_variance);
    chi2 += (mean[k] - out.mean[k]) * (mean[k] - out.mean[k]) / (phi * out.mean[k]);
  }
  out.chi2_per_dof = chi2 / static_cast<double>(n - 4);
  return out;
}

}  // namespace bssrdf::exact_table
