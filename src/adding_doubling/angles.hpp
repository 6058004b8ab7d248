// The quadrature angles of adding-doubling (Prahl 1995, sec. 5.4): cosines in (0, 1] split at the
// critical cosines of the boundaries, Gauss-Legendre on every interval but the last, Gauss-Radau
// on the last with its fixed node at mu = 1 (a normally incident beam's direction).
#pragma once

#include <vector>

namespace bssrdf::adding_doubling {

struct Angles {
  std::vector<double> mu;      // ascending; mu.back() == 1
  std::vector<double> weight;  // sum to 1 (integrals over mu in [0, 1])
  std::size_t size() const { return mu.size(); }
};

// `points` angles in all, split at the `cuts` (critical cosines in (0, 1), any order, duplicates
// ignored); each interval gets an equal share (at least 2), the last the remainder. `beam`, the
// cosine of an oblique beam inside the slab, is made a node too: the interval ending there is
// Gauss-Radau with its fixed node at `beam` (Prahl's iad, ad_start.w Choose_Cone_Method).
Angles make_angles(int points, std::vector<double> cuts, double beam = 1.0);

// The index of the node nearest to mu (the beam's node after make_angles).
std::size_t node_of(const Angles& angles, double mu);

// n-point Gauss-Radau rule on [-1, 1] with the fixed node at +1 (nodes ascending).
void gauss_radau_right(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace bssrdf::adding_doubling
