// Live error measurement against the exact model (model_error_vs_exact.hpp).
#include "model_error_vs_exact.hpp"

#include <cmath>

namespace bssrdf::detail {
namespace {

constexpr int kBins = 64;
constexpr double kInnerRadius = 1e-3;  // transport mfp
// Four-point Gauss-Legendre in ln r per bin: int r R dr = int r^2 R d ln r, smooth in ln r.
constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

// Bin averages of r R(r) over dr; R takes r in the edges' units.
template <class R>
std::vector<double> bin_averages(const std::vector<double>& edges, R&& reflectance) {
  std::vector<double> out;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    const double a = std::log(edges[k]), b = std::log(edges[k + 1]), half = 0.5 * (b - a);
    double s = 0;
    for (int j = 0; j < 4; ++j) {
      const double r = std::exp(a + half * (1 + kNodes[j]));
      s += kWeights[j] * r * r * reflectance(r);
    }
    out.push_back(s * half / (edges[k + 1] - edges[k]));
  }
  return out;
}

}  // namespace

ExactBins exact_bins(const ExactProfile& exact) {
  ExactBins bins;
  bins.total = exact.total();
  if (bins.total == 0) return bins;  // alpha' = 0: R = 0, no bins
  const double outer = radius_where([&](double r) { return exact.cumulative(r); }, 0.999 * bins.total, 1.0, 1e-6);
  // Log-spaced, with an edge at 1 transport mfp so no bin straddles the near / far split: the
  // bins shared between the two sides in proportion to their log ranges (at least 8 beyond).
  const double far_range = std::log(std::max(outer, 2.0)), near_range = -std::log(kInnerRadius);
  const int far_bins = std::max(8, static_cast<int>(std::lround(kBins * far_range / (far_range + near_range))));
  const int near_bins = kBins - far_bins;
  for (int k = 0; k < near_bins; ++k)
    bins.edges.push_back(kInnerRadius * std::pow(1 / kInnerRadius, double(k) / near_bins));
  for (int k = 0; k <= far_bins; ++k) bins.edges.push_back(std::pow(std::max(outer, 2.0), double(k) / far_bins));
  bins.average = bin_averages(bins.edges, [&](double r) { return exact.reflectance(r); });
  return bins;
}

ErrorVsExact error_vs_exact(const Model& model, const Reduced<double>& m, const ExactBins& exact) {
  ErrorVsExact out;
  if (exact.total == 0) {  // nothing scatters: a model is exact if it gives no light either
    const double none = model.total_reflectance(m) == 0 ? 0.0 : HUGE_VAL;
    out.total = out.near = out.far = none;
    return out;
  }
  out.total = std::abs(model.total_reflectance(m) / exact.total - 1);
  // Model lengths are physical: r_physical = r * ell, and r R is scale-free as r^2 R.
  const double ell = m.ell;
  const auto average = bin_averages(exact.edges, [&](double r) { return ell * ell * model.reflectance(m, r * ell); });
  double diff[2] = {0, 0}, norm[2] = {0, 0};
  for (std::size_t k = 0; k < average.size(); ++k) {
    const int side = exact.edges[k + 1] <= 1.0 + 1e-12 ? 0 : 1;
    const double dr = exact.edges[k + 1] - exact.edges[k], d = average[k] - exact.average[k];
    diff[side] += d * d * dr;
    norm[side] += exact.average[k] * exact.average[k] * dr;
  }
  out.near = norm[0] > 0 ? std::sqrt(diff[0] / norm[0]) : 0;
  out.far = norm[1] > 0 ? std::sqrt(diff[1] / norm[1]) : 0;
  if (!std::isfinite(out.total)) out.total = HUGE_VAL;
  if (!std::isfinite(out.near)) out.near = HUGE_VAL;
  if (!std::isfinite(out.far)) out.far = HUGE_VAL;
  return out;
}

}  // namespace bssrdf::detail
