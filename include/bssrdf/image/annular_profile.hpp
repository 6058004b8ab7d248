// A radial profile as the energy it sends into each of a set of annuli around the point of entry:
// the common form of the reference (Monte Carlo bins, or a tabulated exact model) and of every
// representation measured against it (a model, a Lambertian surface, a radial table), so that the
// image-space error compares them annulus by annulus on the same rings.
//
//   AnnularProfile p = annuli_of(edges, [&](double r) { return model->reflectance(m, r); },
//                                model->total_reflectance(m));
//
// edges: r_0 = 0 < r_1 < ... < r_n (mm). energy[i] = int over r_i <= r < r_{i+1} of R dA, per unit
// entered flux. Light beyond r_n (a profile's tail, or the Monte Carlo photons leaving beyond its
// last bin) is put in the last annulus, which callers make wide ([r_max, 2 r_max]).
#pragma once

#include <functional>
#include <vector>

namespace bssrdf {

struct AnnularProfile {
  std::vector<double> edges;          // mm, edges.front() == 0
  std::vector<double> energy;         // per unit entered flux, one per annulus
  std::vector<double> energy_stderr;  // Monte Carlo standard errors; zeros for a formula

  double total() const;
  // The radius holding `fraction` of total() (linear in area within the annulus where it is reached).
  double radius_for_fraction(double fraction) const;
};

// R(r) integrated over each annulus (Gauss-Legendre in ln r, 2 points per annulus; the first annulus
// from 1e-6 r_1 to r_1 with 8), plus total - (sum of the annuli) added to the last one (clamped at 0).
AnnularProfile annuli_of(const std::vector<double>& edges, const std::function<double(double)>& reflectance,
                         double total);

// All of `total` at the centre (a Lambertian surface: light leaves where it entered).
AnnularProfile point_profile(const std::vector<double>& edges, double total);

}  // namespace bssrdf
