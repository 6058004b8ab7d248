#include "bssrdf/quadrature.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <queue>

namespace bssrdf {

const GaussLegendreRule& gauss_legendre(std::size_t n) {
  static std::mutex mutex;
  static std::map<std::size_t, GaussLegendreRule> cache;
  std::lock_guard lock(mutex);
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  GaussLegendreRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  // Newton iteration on P_n from the Chebyshev-like initial guesses; converges to machine precision.
  for (std::size_t i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1, p1 = x;
      for (std::size_t k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 1 ? x : p1, pn1 = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pn1) / (x * x - 1);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2 / ((1 - x * x) * dp * dp);
    rule.nodes[i] = -x;
    rule.nodes[n - 1 - i] = x;
    rule.weights[i] = rule.weights[n - 1 - i] = w;
  }
  return cache.emplace(n, std::move(rule)).first->second;
}

namespace {

// Gauss-Kronrod 7/15 nodes and weights on [-1, 1].
constexpr std::array<double, 8> kKronrodNodes = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851, 0.864864423359769072789712788640926,
    0.741531185599394439863864773280788, 0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kKronrodWeights = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204, 0.104790010322250183839876322541518,
    0.140653259715525918745189590510238, 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kGaussWeights = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780, 0.381830050505118944950369775488975,
    0.417959183673469387755102040816327};

struct Interval {
  double a, b, value, error;
  bool operator<(const Interval& other) const { return error < other.error; }
};

Interval gauss_kronrod(const std::function<double(double)>& f, double a, double b) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  const double fc = f(mid);
  double kronrod = fc * kKronrodWeights[7], gauss = fc * kGaussWeights[3];
  for (int j = 0; j < 7; ++j) {
    const double dx = half * kKronrodNodes[j];
    const double sum = f(mid - dx) + f(mid + dx);
    kronrod += kKronrodWeights[j] * sum;
    if (j % 2 == 1) gauss += kGaussWeights[j / 2] * sum;
  }
  return {a, b, kronrod * half, std::abs((kronrod - gauss) * half)};
}

}  // namespace

QuadratureResult integrate_adaptive(const std::function<double(double)>& f, double a, double b, double rel_tol,
                                    double abs_tol, int max_intervals, int initial_pieces) {
  QuadratureResult result;
  if (a == b) {
    result.converged = true;
    return result;
  }
  std::priority_queue<Interval> heap;
  // Start from a few sub-intervals so that narrow features are not missed by the first estimate.
  const int kStart = std::max(1, initial_pieces);
  double value = 0, error = 0;
  for (int i = 0; i < kStart; ++i) {
    const Interval piece = gauss_kronrod(f, a + (b - a) * i / kStart, a + (b - a) * (i + 1) / kStart);
    value += piece.value;
    error += piece.error;
    heap.push(piece);
  }
  result.evaluations = 15 * kStart;
  while (error > std::max(abs_tol, rel_tol * std::abs(value)) && static_cast<int>(heap.size()) < max_intervals) {
    const Interval worst = heap.top();
    heap.pop();
    const double mid = 0.5 * (worst.a + worst.b);
    const Interval left = gauss_kronrod(f, worst.a, mid), right = gauss_kronrod(f, mid, worst.b);
    result.evaluations += 30;
    value += left.value + right.value - worst.value;
    error += left.error + right.error - worst.error;
    heap.push(left);
    heap.push(right);
  }
  // Re-sum to remove the round-off accumulated by the running updates.
  value = 0;
  error = 0;
  while (!heap.empty()) {
    value += heap.top().value;
    error += heap.top().error;
    heap.pop();
  }
  result.value = value;
  result.error_estimate = error;
  result.converged = error <= std::max(abs_tol, rel_tol * std::abs(value));
  return result;
}

QuadratureResult integrate_radial(const std::function<double(double)>& R, double r0, double r1, double scale,
                                  double rel_tol) {
  const double lo = std::log(r0 > 0 ? r0 : scale * 1e-12);
  const double hi = std::log(std::isfinite(r1) ? r1 : scale * 1e9);
  if (!(hi > lo)) return {0, 0, 0, true};
  // Start with one piece per decade so the adaptive rule sees the profile's structure at once.
  const int pieces = std::max(1, static_cast<int>((hi - lo) / std::log(10.0)));
  const auto integrand = [&R](double u) {
    const double r = std::exp(u);
    return 2 * std::numbers::pi * r * r * R(r);
  };
  return integrate_adaptive(integrand, lo, hi, rel_tol, 0.0, 4000, pieces);
}

}  // namespace bssrdf
