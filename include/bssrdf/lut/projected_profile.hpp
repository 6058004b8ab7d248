// A radial profile R(r) and its projections onto one axis, which the screen-space, pre-integrated
// and preview forms need:
//
//   line(x)       = int R(sqrt(x^2 + y^2)) dy            the exitance at distance x from a lit line
//                                                         (the profile's 1D cross-section: a 2D
//                                                         Gaussian G2(v) projects to G1(v))
//   half_plane(x) = int_x^inf line(t) dt                 the exitance at signed distance x from the
//                 = int int_{X > x} R dA                 edge of a lit half-plane X > x (the shadow edge)
//   strip(a, b)   = int_a^b line(t) dt                   light from the strip a < X < b
//   half_plane_integral(x) = int_0^x half_plane(t) dt    (x >= 0) for edges that are ramps, not steps
//   total()       = int 2 pi r R(r) dr                   = 2 half_plane(0) = int line
//
// R is tabulated once from the model on 64 points per decade of r (uniform in ln r, from 1e-6 of
// the transport mean free path until the tail holds less than 1e-10 of the total) and interpolated
// as a cubic in (ln r, ln R); line() and half_plane() are tabulated on the same nodes (line by the
// substitution y = x sinh s, half_plane by integrating line in ln x), so every query is O(1).
// conservation_error() = 2 half_plane(0) / total() - 1 measures the projections' numerical error.
//
//   ProjectedProfile p(*make_model("pbd"), skin.reduced(0));
//   double edge = p.half_plane(0.5);   // shadowed side, 0.5 mm from the edge
#pragma once

#include <optional>
#include <vector>

#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

class ProjectedProfile {
 public:
  ProjectedProfile(const Model& model, const Reduced<double>& m);

  double total() const { return total_; }
  double reflectance(double r) const;            // R(r); R(r_min) below the grid, 0 beyond it
  double line(double x) const;                   // even in x
  double line(double x, double ln_abs_x) const;  // the same given ln |x| (shared by several profiles)
  // line(x[k], ln_x[k]) for every k into out[k] (x > 0): the same values, in one loop that inlines the interpolation.
  void lines(const double* x, const double* ln_x, double* out, std::size_t n) const;
  double half_plane(double x) const;             // signed x: total - half_plane(-x) for x < 0
  double strip(double a, double b) const { return half_plane(a) - half_plane(b); }
  double half_plane_integral(double x) const;  // int_0^x half_plane, x >= 0
  // The same given ln x too (tables whose arguments are products s w add logarithms instead).
  double half_plane_integral(double x, double ln_x) const;
  // half_plane_integral(x[k], ln_x[k]) for every k into out[k]: the same values, in one inlined loop.
  void half_plane_integrals(const double* x, const double* ln_x, double* out, std::size_t n) const;
  // The radius holding `fraction` of total() (0 < fraction < 1).
  double radius_for_fraction(double fraction) const;
  // The distance x >= 0 at which 2 half_plane(x) / total falls to 1 - fraction: the half-width of
  // the band |X| < x holding `fraction` of the light of a point (the 1D kernel's support).
  double line_width_for_fraction(double fraction) const;
  double conservation_error() const { return 2 * half_plane(0) / total_ - 1; }
  double r_min() const { return r_min_; }
  double r_max() const { return r_max_; }

 private:
  double u0_ = 0, h_ = 0;                                           // nodes u_j = u0 + j h, u = ln r
  std::vector<double> log_R_, log_line_, half_plane_, cumulative_;  // cumulative: int_0^{r_j} 2 pi r R dr
  std::vector<double> half_plane_integral_;                         // int_0^{x_j} half_plane
  double total_ = 0, half_plane_0_ = 0;
  double r_min_ = 0, r_max_ = 0;  // e^{u_0} and e^{u_last}, kept: every evaluation compares with both
  double cubic(const std::vector<double>& f, double u) const;
};

// One projection per channel that scatters (sigma_s > 0) and none for a channel that does not (its
// profile vanishes: the tables take that limit). Throws InvalidInput when no channel scatters.
std::vector<std::optional<ProjectedProfile>> project_channels(const Medium& medium, const Model& model);

}  // namespace bssrdf
