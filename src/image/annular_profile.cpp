#include "bssrdf/image/annular_profile.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

// Gauss-Legendre on [-1, 1]: 8 points for the first annulus (six decades of r, where R may be
// singular as 1/r), 2 for the others (a 5 % step in r at 48 annuli a decade: error ~ step^4, about
// 1e-7 of the annulus for a smooth R, and a quarter of the model evaluations of 8 points).
constexpr std::array<double, 8> kNodes8 = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                           -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                           0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kWeights8 = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                             0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                             0.2223810344533745, 0.1012285362903763};
constexpr std::array<double, 2> kNodes2 = {-0.5773502691896258, 0.5773502691896258};
constexpr std::array<double, 2> kWeights2 = {1.0, 1.0};

// int_lo^hi 2 pi r R(r) dr = int 2 pi r^2 R(r) d(ln r).
template <std::size_t N>
double ring_integral(const std::function<double(double)>& reflectance, double lo, double hi,
                     const std::array<double, N>& nodes, const std::array<double, N>& weights) {
  const double u0 = std::log(lo), u1 = std::log(hi), half = (u1 - u0) / 2, mid = (u0 + u1) / 2;
  double sum = 0;
  for (std::size_t k = 0; k < N; ++k) {
    const double r = std::exp(mid + half * nodes[k]);
    sum += weights[k] * 2 * std::numbers::pi * r * r * reflectance(r);
  }
  return sum * half;
}

void check_edges(const std::vector<double>& edges) {
  if (edges.size() < 2 || edges.front() != 0)
    throw InvalidInput("annulus edges", std::to_string(edges.size()), "0 = r_0 < r_1 < ...");
  for (std::size_t i = 1; i < edges.size(); ++i)
    if (!(edges[i] > edges[i - 1])) throw InvalidInput("annulus edges", format_number(edges[i]), "increasing");
}

}  // namespace

double AnnularProfile::total() const { return std::accumulate(energy.begin(), energy.end(), 0.0); }

double AnnularProfile::radius_for_fraction(double fraction) const {
  const double target = fraction * total();
  double cumulative = 0;
  for (std::size_t i = 0; i < energy.size(); ++i) {
    if (cumulative + energy[i] >= target && energy[i] > 0) {
      const double t = (target - cumulative) / energy[i];
      return std::sqrt(edges[i] * edges[i] + t * (edges[i + 1] * edges[i + 1] - edges[i] * edges[i]));
    }
    cumulative += energy[i];
  }
  return edges.back();
}

AnnularProfile annuli_of(const std::vector<double>& edges, const std::function<double(double)>& reflectance,
                         double total) {
  check_edges(edges);
  AnnularProfile p{edges, std::vector<double>(edges.size() - 1), std::vector<double>(edges.size() - 1, 0.0)};
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    p.energy[i] = i == 0 ? ring_integral(reflectance, 1e-6 * edges[1], edges[1], kNodes8, kWeights8)
                         : ring_integral(reflectance, edges[i], edges[i + 1], kNodes2, kWeights2);
  }
  p.energy.back() += std::max(0.0, total - p.total());
  return p;
}

AnnularProfile point_profile(const std::vector<double>& edges, double total) {
  check_edges(edges);
  AnnularProfile p{edges, std::vector<double>(edges.size() - 1, 0.0), std::vector<double>(edges.size() - 1, 0.0)};
  p.energy[0] = total;
  return p;
}

}  // namespace bssrdf
