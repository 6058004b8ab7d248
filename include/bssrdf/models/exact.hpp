// The `exact` model: the radiative-transfer solution itself, not an approximation. R(r) for a
// normally incident pencil beam on a semi-infinite medium with the true Henyey-Greenstein phase
// function and a smooth boundary, per unit entered flux, single scattering included, read from a
// precomputed table (exact_table.hpp: project Monte Carlo for multiple scattering, the exact
// single-scattering integral, adding-doubling totals) and interpolated.
//
//   ExactProfile p(bundled_exact_table(), 0.95, 0.9, 1.4);   // alpha', g, eta
//   double R = p.reflectance(0.5);                          // r in transport mfp, R in 1/mfp^2
//   double total = p.total();                               // the adding-doubling total
//
// Interpolation: cubic Hermite in logit(alpha'), -ln(1 - g) and eta (slopes from three-point
// differences: continuous first derivatives, so fits through it converge) of ln y, y = 2 pi r^2 R,
// at each tabulated radius; Catmull-Rom in ln r between radii. The curve is then scaled so that its
// integral equals the interpolated adding-doubling total, which is what total() returns.
// Domain: alpha' in [0, 1], g in [0, 0.999], eta over the table's nodes (1 to 2); outside it the
// constructor throws InvalidInput naming the parameter. Beyond the table's nodes the model continues
// where the continuation is measured to hold (tools/validation/exact_vs_montecarlo.txt):
//  - below the first albedo node (8.9e-5) single scattering is exact
//    and multiple scattering follows from the first two nodes' at the medium's own optical radius
//    rho = sigma_t r, ln(MS / alpha^2) linear in alpha (the order-of-scattering series); at
//    alpha' = 0, R = 0;
//  - above the last albedo node (0.9999) the last node's profile times the classical dipole's ratio of
//    the two albedos' profiles (diffusion's far field, exact there), its total from
//    1 - T = c1 s + c2 s^2, s = sqrt(1 - alpha'), through the last two nodes to T(1) = 1;
//  - below the first radius (0.001 transport mfp) y as a power of r, at least r^1 (single
//    scattering's R ~ 1/r is the strongest singularity at r -> 0); for strongly forward media
//    (g above about 0.93, where 0.001 transport mfp is under 0.05 mean free paths short of that
//    limit) radii are prepended at the table's step down to sigma_t r = 0.05, holding single
//    scattering exactly and the first radius's multiple scattering flat in R, and below them
//    y = y_first x (a + (1 - a) x): R -> a y_first / (2 pi r_first^2 x), single scattering's 1/r.
// In g the nodes reach 0.999 (a table ending lower, as those before 2026-12-07, ends the domain there).
// Accuracy and speed: README "The exact model" (measured against fresh Monte Carlo off the grid).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bssrdf/models/exact_table.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {

// The model's domain, inclusive: alpha' 0 to 1 (continued below the first albedo node exactly and
// above the last by diffusion), g and eta over the nodes (0 to 0.999, 1 to 2).
std::pair<double, double> exact_albedo_range(const ExactTable& table);
std::pair<double, double> exact_g_range(const ExactTable& table);
std::pair<double, double> exact_eta_range(const ExactTable& table);

// The model's domain for one medium: an empty report inside, an "invalid" entry per parameter
// outside (codes exact_albedo, exact_g, exact_eta), each naming the value and the covered range.
ValidityReport exact_domain(const ExactTable& table, double albedo_prime, double g, double eta);

// Total diffuse reflectance per unit entered flux at (alpha', g, eta), interpolated from the
// adding-doubling totals (no profile is built: ~0.1 us). Throws InvalidInput outside the domain.
double exact_total(const ExactTable& table, double albedo_prime, double g, double eta);

// The reduced albedo whose exact total is `total` at (g, eta): the inverse of exact_total,
// monotone in alpha'. Throws InvalidInput when `total` is outside [total(first albedo node), 1].
double exact_albedo_prime_from_total(const ExactTable& table, double total, double g, double eta);

// How a build below the first albedo node integrates the medium's single scattering at the table's
// radii: `log_grid` (single_scattering_ln_y, all radii at once: the whole build 84 700 instructions,
// 15 us on the development machine's 2026-12-07 timings, tools/bench/bench_exact and docs/exact.md) or
// `per_radius` (96-point Gauss-Legendre at each radius, as the table's generator did: 188 us; the
// measured baseline of bench_exact and the tests). The profiles agree to 1e-6 relative
// (tests/test_exact_model.cpp).
enum class SingleScatteringRadii { log_grid, per_radius };

class ExactProfile {
 public:
  ExactProfile(const ExactTable& table, double albedo_prime, double g, double eta,
               SingleScatteringRadii single_scattering = SingleScatteringRadii::log_grid);

  // Lengths in transport mean free paths (sigma_t' = 1), R in 1/mfp^2.
  double reflectance(double r) const;
  double cumulative(double r) const;  // int_0^r 2 pi r' R dr'
  double total() const { return total_; }
  double albedo_prime() const { return albedo_prime_; }
  double g() const { return g_; }
  double eta() const { return eta_; }

 private:
  double ln_y(double ln_r) const;  // the interpolated, normalised curve
  // Below the first radius, x = r / r_first <= 1: ln(y / y_first) at ln x, and int_0^r y d ln r over
  // y_first (the head's closed forms).
  double head_ln_shape(double ln_x) const;
  double head_energy(double x) const;

  double albedo_prime_, g_, eta_;
  double ln_r0_, d_ln_r_;
  std::vector<double> ln_y_;        // per tabulated radius, normalised
  std::vector<double> cumulative_;  // int_0^{r_k} y d ln r at each tabulated radius
  double head_slope_ = 1, tail_slope_ = 0, total_ = 0;
  double head_linear_ = 0;  // a in y = y_first (a x + (1 - a) x^2) below the first radius, where a head was prepended
};

class Model;
// The `exact` model on the bundled table (loaded on first use), for make_model("exact").
std::unique_ptr<Model> make_exact_model();

}  // namespace bssrdf
