// The radial lookup table: one material's R(r) per channel on one radius grid, with 2 pi r R(r),
// its CDF and inverse CDF for importance sampling, sized adaptively: the smallest grid (uniform in
// x = ln r + r/L) whose interpolation (Catmull-Rom or linear, in x) stays within a relative tolerance of the
// model, checked at the two Gauss-Legendre points of every interval, over each channel's radius
// range holding a given fraction of its total reflectance. The size is searched against a dense
// stand-in (the model on a doubling grid, 6-point Lagrange in ln R, refined until accurate to about
// 1/256 of the tolerance), so the model is evaluated only there, at the chosen nodes and in a probe.
//
//   RadialTableOptions o;  o.tolerance = 1e-3;  o.energy = 0.999;
//   auto table = build_radial_table(skin, *make_model("pbd"), o);
//   double R = table.interpolate(0, 0.7);          // channel 0 at r = 0.7 mm
//
// Range: channel c's range [r_lo, r_hi] holds `energy` of its total with (1 - energy)/2 inside r_lo
// and beyond r_hi; the table spans the union over channels. Totals and ranges come from a probe
// of the profile on 16 points per decade of radius, integrated by the trapezoid rule in ln r
// (spectrally accurate: 2 pi r^2 R vanishes at both ends).
#pragma once

#include <string>
#include <vector>

#include "bssrdf/lut/interpolation.hpp"
#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

struct RadialTableOptions {
  double tolerance = 1e-3;  // relative interpolation error bound
  double energy = 0.999;    // fraction of each channel's total inside its checked range
  Interpolation interpolation = Interpolation::catmull_rom;
  std::size_t max_size = 16384;
  unsigned threads = 1;  // 0: all hardware threads; results never depend on it

  void validate() const;  // throws InvalidInput naming the option
};

struct RadialTable {
  RadialTableOptions options;
  std::vector<std::string> channel_names;
  // Grid: uniform in x = ln r + r / L from r_min to r_max (ln of r in mm): logarithmic in the near
  // field, linear in the exponential tail, L = the shortest local decay length -1/(d ln R/dr) of
  // the channels at their r_hi.
  double decay_length = 1;                       // L, mm
  std::vector<double> radius;                    // mm
  std::vector<std::vector<double>> reflectance;  // [channel][j]: R(r_j), 1/mm^2, per entered flux
  std::vector<std::vector<double>> ring;         // 2 pi r_j R(r_j), 1/mm
  std::vector<std::vector<double>> cdf;          // int_0^{r_j} 2 pi r R dr / table_reflectance
  std::vector<double> u;                         // j / (N - 1)
  std::vector<std::vector<double>> inverse_cdf;  // [channel][j]: r with cdf(r) = u_j, mm
  std::vector<double> total_reflectance;         // int_0^inf 2 pi r R dr
  std::vector<double> table_reflectance;         // int_0^{r_max} 2 pi r R dr
  std::vector<double> range_min, range_max;      // per channel, mm
  double max_error = 0;         // worst relative error at the check points, over channels in their ranges
  std::size_t evaluations = 0;  // model evaluations spent (all channels)

  std::size_t size() const { return radius.size(); }
  double grid_coordinate(double r_mm) const;  // x(r)
  // R(r) as a consumer interpolates it (the options' scheme in x); 0 outside the table.
  double interpolate(std::size_t channel, double r) const;
};

RadialTable build_radial_table(const Medium& medium, const Model& model, const RadialTableOptions& options);

// Channels: R(r) under the medium's channel names, "radius" (unit), "ring.<c>" (2 pi r R, 1/unit),
// "cdf.<c>", "u", "inverse_cdf.<c>" (unit); attributes record the grid, range, tolerance and totals.
LookupTable to_lookup_table(const RadialTable& table, const TableContext& context);
// A few lines for people: radii, error against the tolerance, each channel's total and range.
std::string summary(const RadialTable& table, const TableContext& context);

// The importance-sampling channels every radial table writes, in this order: "ring.<c>" (2 pi r R,
// 1/unit), "cdf.<c>" (described by cdf_description), "u" and "inverse_cdf.<c>" (unit); lengths
// given in mm.
void add_sampling_channels(LookupTable& out, const std::vector<std::string>& channel_names,
                           const std::vector<std::vector<double>>& ring, const std::vector<std::vector<double>>& cdf,
                           const std::vector<double>& u, const std::vector<std::vector<double>>& inverse_cdf,
                           const std::string& cdf_description, LengthUnit unit);

}  // namespace bssrdf
