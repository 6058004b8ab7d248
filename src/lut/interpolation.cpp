#include "bssrdf/lut/interpolation.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "bssrdf/cubic_hermite.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf {

std::string_view to_string(Interpolation scheme) { return scheme == Interpolation::linear ? "linear" : "catmull-rom"; }

Interpolation parse_interpolation(std::string_view text, const std::string& field) {
  if (text == "catmull-rom") return Interpolation::catmull_rom;
  if (text == "linear") return Interpolation::linear;
  throw InvalidInput(field, "'" + std::string(text) + "'", "catmull-rom or linear");
}

NodeWeights catmull_rom_weights(std::span<const double> nodes, double x) {
  const int n = static_cast<int>(nodes.size());
  NodeWeights out;
  if (n == 1) {
    out.offset = -1;
    out.weight = {0, 1, 0, 0};
    return out;
  }
  x = std::clamp(x, nodes.front(), nodes.back());
  const int i =
      std::clamp(static_cast<int>(std::upper_bound(nodes.begin(), nodes.end(), x) - nodes.begin()) - 1, 0, n - 2);
  const double x0 = nodes[i], x1 = nodes[i + 1], h = x1 - x0;
  // Hermite basis: values at x0, x1 and slopes (times h) at x0, x1.
  const auto [h00, h10, h01, h11] = hermite_basis((x - x0) / h);
  out.offset = i - 1;
  auto& w = out.weight;  // nodes i-1, i, i+1, i+2
  w = {0, h00, h01, 0};
  if (i > 0) {  // slope at x0: (f1 - f_{-1}) / (x1 - x_{-1})
    const double s = h10 * h / (x1 - nodes[i - 1]);
    w[0] -= s;
    w[2] += s;
  } else {  // one-sided: (f1 - f0) / h
    w[1] -= h10;
    w[2] += h10;
  }
  if (i + 2 < n) {  // slope at x1: (f2 - f0) / (x2 - x0)
    const double s = h11 * h / (nodes[i + 2] - x0);
    w[1] -= s;
    w[3] += s;
  } else {
    w[1] -= h11;
    w[2] += h11;
  }
  return out;
}

double interpolate(std::span<const double> nodes, std::span<const double> values, double x, Interpolation scheme) {
  const int n = static_cast<int>(nodes.size());
  if (n == 0) return 0;
  if (n == 1) return values[0];
  if (scheme == Interpolation::linear) {
    x = std::clamp(x, nodes.front(), nodes.back());
    const int i =
        std::clamp(static_cast<int>(std::upper_bound(nodes.begin(), nodes.end(), x) - nodes.begin()) - 1, 0, n - 2);
    const double t = (x - nodes[i]) / (nodes[i + 1] - nodes[i]);
    return values[i] + t * (values[i + 1] - values[i]);
  }
  const auto w = catmull_rom_weights(nodes, x);
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    const int j = w.offset + k;
    if (j >= 0 && j < n && w.weight[k] != 0) sum += w.weight[k] * values[j];
  }
  return sum;
}

double catmull_rom_integral(std::span<const double> nodes, std::span<const double> values, double a, double b) {
  std::vector<double> cuts{a};
  for (double x : nodes)
    if (x > a && x < b) cuts.push_back(x);
  cuts.push_back(b);
  double sum = 0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double h = cuts[k + 1] - cuts[k];
    for (double t : kCheckPoint) sum += 0.5 * h * interpolate(nodes, values, cuts[k] + t * h);
  }
  return sum;
}

std::vector<double> inverse_cdf(std::span<const double> cdf, std::span<const double> radius, std::span<const double> x,
                                const std::function<double(double)>& radius_at, std::span<const double> u) {
  std::vector<double> out;
  for (double target : u) {
    if (target >= 1) {
      out.push_back(radius.back());
    } else if (target <= cdf[0]) {
      out.push_back(radius[0] * target / cdf[0]);
    } else {
      const auto i = std::min<std::size_t>(
          cdf.size() - 1, static_cast<std::size_t>(std::lower_bound(cdf.begin(), cdf.end(), target) - cdf.begin()));
      const double t = cdf[i] > cdf[i - 1] ? (target - cdf[i - 1]) / (cdf[i] - cdf[i - 1]) : 1.0;
      out.push_back(radius_at(x[i - 1] + t * (x[i] - x[i - 1])));
    }
  }
  return out;
}

}  // namespace bssrdf
