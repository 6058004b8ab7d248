// Gauss and Radau angles for adding-doubling (see angles.hpp).
#include "angles.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bssrdf/quadrature.hpp"

namespace bssrdf::adding_doubling {

namespace {

// P_{n-1}(x) and P_n(x) by the three-term recurrence.
std::pair<double, double> legendre_pair(int n, double x) {
  double previous = 1, current = x;
  if (n == 0) return {0, 1};
  for (int k = 2; k <= n; ++k) {
    const double next = ((2 * k - 1) * x * current - (k - 1) * previous) / k;
    previous = current;
    current = next;
  }
  return {previous, current};
}

}  // namespace

void gauss_radau_right(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  // With the fixed node at -1 the free nodes are the roots of (P_{n-1} + P_n)/(1 + x) and the
  // weights (1 - x)/(n^2 P_{n-1}(x)^2), 2/n^2 at -1 (Abramowitz & Stegun 25.4.31); mirrored here.
  nodes.assign(1, -1.0);
  weights.assign(1, 2.0 / (n * n));
  for (int k = 1; k < n; ++k) {
    double x = -std::cos(2 * M_PI * k / (2 * n - 1));  // asymptotic position of the k-th root
    for (int iteration = 0; iteration < 100; ++iteration) {
      // f = P_{n-1} + P_n; f' from (1 - x^2) P_m' = m (P_{m-1} - x P_m).
      const auto [pm2, pm1] = legendre_pair(n - 1, x);
      const auto [unused, pn] = legendre_pair(n, x);
      (void)unused;
      const double f = pm1 + pn;
      const double df = ((n - 1) * (pm2 - x * pm1) + n * (pm1 - x * pn)) / (1 - x * x);
      // Deflate the root at x = -1 and those already found.
      double deflation = 1 / (x + 1);
      for (double root : nodes) deflation += root == -1.0 ? 0 : 1 / (x - root);
      const double step = f / (df - f * deflation);
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    nodes.push_back(x);
    const double p = legendre_pair(n - 1, x).second;
    weights.push_back((1 - x) / (double(n) * n * p * p));
  }
  std::vector<std::size_t> order(nodes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<double> x(nodes), w(weights);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return x[a] > x[b]; });
  for (std::size_t i = 0; i < order.size(); ++i) {  // mirror: fixed node at +1, ascending
    nodes[i] = -x[order[i]];
    weights[i] = w[order[i]];
  }
}

Angles make_angles(int points, std::vector<double> cuts, double beam) {
  const bool oblique = beam > 1e-9 && beam < 1 - 1e-9;
  if (oblique) cuts.push_back(beam);
  cuts.erase(std::remove_if(cuts.begin(), cuts.end(), [](double c) { return !(c > 1e-9 && c < 1 - 1e-9); }),
             cuts.end());
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }),
             cuts.end());
  std::vector<double> ends{0.0};
  ends.insert(ends.end(), cuts.begin(), cuts.end());
  ends.push_back(1.0);
  const int intervals = static_cast<int>(ends.size()) - 1;
  const int share = std::max(2, points / intervals);
  Angles angles;
  for (int k = 0; k < intervals; ++k) {
    const double a = ends[k], b = ends[k + 1];
    const bool last = k + 1 == intervals;
    const bool ends_at_beam = oblique && std::abs(b - beam) < 1e-12;
    const int n = last ? std::max(2, points - share * (intervals - 1)) : share;
    std::vector<double> x, w;
    if (last || ends_at_beam) {
      gauss_radau_right(n, x, w);
    } else {
      const auto& rule = gauss_legendre(static_cast<std::size_t>(n));
      x = rule.nodes;
      w = rule.weights;
      std::vector<std::size_t> order(x.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](auto i, auto j) { return x[i] < x[j]; });
      std::vector<double> xs, ws;
      for (auto i : order) xs.push_back(x[i]), ws.push_back(w[i]);
      x = xs;
      w = ws;
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
      angles.mu.push_back(a + (b - a) * (x[i] + 1) / 2);
      angles.weight.push_back(w[i] * (b - a) / 2);
    }
    if (ends_at_beam) angles.mu.back() = beam;  // exactly the beam's cosine
  }
  angles.mu.back() = 1.0;
  return angles;
}

std::size_t node_of(const Angles& angles, double mu) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < angles.size(); ++i)
    if (std::abs(angles.mu[i] - mu) < std::abs(angles.mu[best] - mu)) best = i;
  return best;
}

}  // namespace bssrdf::adding_doubling
