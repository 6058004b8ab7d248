// Interpolation on a tabulated grid, as the tables' consumers perform it, so that the adaptive
// tabulators measure exactly the error a renderer will see.
//
// Catmull-Rom (pbrt's CatmullRomWeights): on [x_i, x_{i+1}] a cubic Hermite whose slopes are the
// centred differences (f_{i+1} - f_{i-1}) / (x_{i+1} - x_{i-1}), one-sided at the ends. Third
// order; its error inside an interval peaks near t = 0.21 and 0.79 rather than the midpoint, which
// is where the tabulators check it (they are also the two Gauss-Legendre nodes, reused to
// integrate). Linear: what a hardware texture fetch does.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

namespace bssrdf {

enum class Interpolation { catmull_rom, linear };

std::string_view to_string(Interpolation scheme);
Interpolation parse_interpolation(std::string_view text, const std::string& field);  // throws InvalidInput

// Weights of the four nodes offset .. offset + 3 (entries outside [0, n) get weight 0) for the value
// at x; x is clamped to [nodes.front(), nodes.back()].
struct NodeWeights {
  int offset = 0;
  std::array<double, 4> weight{};
};
NodeWeights catmull_rom_weights(std::span<const double> nodes, double x);

// The interpolated value at x (clamped to the node range).
double interpolate(std::span<const double> nodes, std::span<const double> values, double x,
                   Interpolation scheme = Interpolation::catmull_rom);

// Gauss-Legendre 2-point nodes on [0, 1]: where the tabulators check and integrate each interval.
inline constexpr double kCheckPoint[2] = {0.21132486540518713, 0.78867513459481287};

// The integral over [a, b] of the Catmull-Rom curve through (nodes, values), exact (two-point
// Gauss-Legendre on each cubic piece): how a renderer's interpolated table averages over a range.
double catmull_rom_integral(std::span<const double> nodes, std::span<const double> values, double a, double b);

// The inverse of a non-decreasing radial CDF (last value 1) tabulated at nodes of radius r_j and
// grid coordinate x_j (increasing with r; radius_at(x) maps back), at each value of u: linear in
// (cdf, x) between nodes, linear in r from the origin below the first node (where R ~ 1/r makes
// the CDF ~ r), and the last radius for u >= 1. Importance sampling reads radii from it.
std::vector<double> inverse_cdf(std::span<const double> cdf, std::span<const double> radius, std::span<const double> x,
                                const std::function<double(double)>& radius_at, std::span<const double> u);

}  // namespace bssrdf
