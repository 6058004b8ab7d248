// The exact table generator's fit of a noisy near field (generator version 10; data/exact/README.md).
// In a strongly forward, nearly non-absorbing medium few photons come out within 0.01 transport mfp
// of the entry (g 0.999: 2-20 of 131 072 per radius bin), so each bin is noise, while the profile
// is smooth there: y_ms ~ r^s with s near 1 (quasi-single scattering, R ~ 1/r) from 0.001 to beyond
// 0.1 transport mfp. One fit over that whole range pools its photons: ln y_ms = a cubic in ln r by
// Poisson maximum likelihood (log link), whose score equations sum_k (tally_k - fit_k) x_k^j = 0
// hold for any tally scale and for empty bins, unlike a least-squares fit of ln tally.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace bssrdf::exact_table {

constexpr int kNearFitTerms = 4;  // a cubic in ln r
using Matrix = std::array<std::array<double, kNearFitTerms>, kNearFitTerms>;

// The inverse of a symmetric positive definite matrix by Gauss-Jordan elimination (no pivoting
// needed); false when singular.
inline bool invert(Matrix a, Matrix& inv) {
  constexpr int n = kNearFitTerms;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) inv[i][j] = i == j ? 1.0 : 0.0;
  for (int c = 0; c < n; ++c) {
    const double pivot = a[c][c];
    if (!(std::abs(pivot) > 0)) return false;
    for (int j = 0; j < n; ++j) {
      a[c][j] /= pivot;
      inv[c][j] /= pivot;
    }
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      for (int j = 0; j < n; ++j) {
        a[r][j] -= f * a[c][j];
        inv[r][j] -= f * inv[c][j];
      }
    }
  }
  return true;
}

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
  constexpr int p = kNearFitTerms;  // powers of x = (k - last) d_ln_r
  NearFieldFit out;
  const std::size_t n = last + 1;
  if (n <= p + 2 || n > mean.size()) return out;
  const auto basis = [&](std::size_t k) {
    const double x = (static_cast<double>(k) - static_cast<double>(last)) * d_ln_r;
    return std::array<double, p>{1, x, x * x, x * x * x};
  };
  double sum_mean = 0, sum_var = 0, tail = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sum_mean += mean[k];
    sum_var += se[k] * se[k];
  }
  for (std::size_t k = n - 3; k < n; ++k) tail += mean[k] / 3;
  if (!(sum_mean > 0 && sum_var > 0 && tail > 0)) return out;
  std::array<double, p> c{std::log(tail), 1, 0, 0};  // start: y ~ r through the last bins
  const auto fitted = [&](const std::array<double, p>& b) {
    double ln = 0;
    for (int i = 0; i < p; ++i) ln += c[i] * b[i];
    return std::exp(ln);
  };
  Matrix h{}, inv{};  // X' diag(fit) X and its inverse
  for (int iteration = 0; iteration < 100; ++iteration) {
    std::array<double, p> grad{};
    h = {};
    for (std::size_t k = 0; k < n; ++k) {
      const auto b = basis(k);
      const double fit = fitted(b);
      for (int i = 0; i < p; ++i) {
        grad[i] += (mean[k] - fit) * b[i];
        for (int j = 0; j < p; ++j) h[i][j] += fit * b[i] * b[j];
      }
    }
    // Newton step: dc = h^-1 grad.
    if (!invert(h, inv)) return out;
    double largest = 0;
    for (int i = 0; i < p; ++i) {
      double step = 0;
      for (int j = 0; j < p; ++j) step += inv[i][j] * grad[j];
      step = std::clamp(step, -2.0, 2.0);  // a first step from far away stays finite
      c[i] += step;
      largest = std::max(largest, std::abs(step));
    }
    if (largest < 1e-12) {
      out.converged = true;
      break;
    }
  }
  if (!out.converged) return out;
  // Covariance phi (X' diag(fit) X)^-1: inv is that inverse at the solution (the last iteration's
  // step was below 1e-12).
  double fit_sum = 0;
  out.mean.resize(n);
  out.se.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = basis(k);
    out.mean[k] = fitted(b);
    fit_sum += out.mean[k];
  }
  const double phi = sum_var / fit_sum;
  double chi2 = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto b = basis(k);
    double variance = 0;  // of ln fit_k: b' cov b
    for (int i = 0; i < p; ++i)
      for (int j = 0; j < p; ++j) variance += b[i] * inv[i][j] * b[j];
    out.se[k] = out.mean[k] * std::sqrt(phi * variance);
    chi2 += (mean[k] - out.mean[k]) * (mean[k] - out.mean[k]) / (phi * out.mean[k]);
  }
  out.chi2_per_dof = chi2 / static_cast<double>(n - p);
  return out;
}

}  // namespace bssrdf::exact_table
