#include "bssrdf/models/multipole.hpp"

#include <cmath>
#include <limits>

#include "bssrdf/error.hpp"
#include "bssrdf/models/diffusion_validity.hpp"

namespace bssrdf::multipole {

double truncation_error(const Reduced<double>& m, const Slab<double>& s, int n) {
  const auto sp = spectra(m, s, m.sigma_tr);
  return std::pow(sp.q, n) * (std::abs(sp.R_tails) + std::abs(sp.T_tails));
}

int pairs_for_tolerance(const Reduced<double>& m, const Slab<double>& s, double tolerance, int max_pairs) {
  const auto sp = spectra(m, s, m.sigma_tr);
  const double tails = std::abs(sp.R_tails) + std::abs(sp.T_tails);
  if (tails <= tolerance) return 0;
  if (!(sp.q < 1)) return max_pairs;
  // q^n tails <= tolerance; the logarithm gives n directly, the loop guards its rounding.
  int n = static_cast<int>(std::max(0.0, std::floor(std::log(tolerance / tails) / std::log(sp.q))));
  n = std::min(n, max_pairs);
  while (n < max_pairs && std::pow(sp.q, n) * tails > tolerance) ++n;
  while (n > 0 && std::pow(sp.q, n - 1) * tails <= tolerance) --n;
  return n;
}

namespace {

template <class PairTerm>
double converged_sum(const Geometry<double>& g, int n, double r, PairTerm term) {
  double sum = term(g, 0, r), magnitude = std::abs(sum);
  for (int i = 1; i <= kMaxPairs; ++i) {
    const double up = term(g, i, r), down = term(g, -i, r);
    sum += up + down;
    magnitude += std::abs(up) + std::abs(down);
    if (i >= n && i * g.period > r && std::abs(up + down) <= 1e-9 * std::abs(sum)) break;
  }
  // Very far out the images cancel to below the rounding of their sum: the profile is 0 there
  // to double precision (and must not come out negative).
  return std::abs(sum) < 1e-12 * magnitude ? 0.0 : sum;
}

}  // namespace

double reflectance_converged(const Reduced<double>& m, const Slab<double>& s, int n, double r) {
  return m.albedo_prime * converged_sum(geometry(m, s), n, r, pair_reflectance<double>);
}
double transmittance_converged(const Reduced<double>& m, const Slab<double>& s, int n, double r) {
  return m.albedo_prime * converged_sum(geometry(m, s), n, r, pair_transmittance<double>);
}

Model::Model(double thickness_mm, std::optional<double> eta_bottom, double tolerance, BoundaryA boundary)
    : thickness_(thickness_mm), eta_bottom_(eta_bottom), tolerance_(tolerance), boundary_(boundary) {
  if (!(thickness_mm > 0) || !std::isfinite(thickness_mm))
    throw InvalidInput("thickness", format_number(thickness_mm), "> 0 and finite");
  if (eta_bottom && (!(*eta_bottom > 0) || !std::isfinite(*eta_bottom)))
    throw InvalidInput("eta_bottom", format_number(*eta_bottom), "> 0 and finite");
  if (!(tolerance > 0 && tolerance < 1))
    throw InvalidInput("pair tolerance", format_number(tolerance), "0 < tolerance < 1");
}

std::string Model::description() const {
  return std::string("multipole (Donner & Jensen 2005): slab of thickness ") + format_number(thickness_) +
         " mm, classical D, " + (boundary_ == BoundaryA::classical ? "classical A" : "improved A") +
         ", dipole pairs chosen for a total tolerance of " + format_number(tolerance_) + ", multiple scattering only";
}

Slab<double> Model::slab(const Reduced<double>& m) const {
  // The improved A costs two Fresnel-moment quadratures: profiles evaluate many radii at one eta.
  thread_local double cached_eta = -1, cached_bottom = -1;
  thread_local BoundaryA cached_boundary = BoundaryA::classical;
  thread_local double A_top = 0, A_bottom = 0;
  const double bottom = eta_bottom_.value_or(m.eta);
  if (m.eta != cached_eta || bottom != cached_bottom || boundary_ != cached_boundary) {
    A_top = boundary_A(m.eta, boundary_);
    A_bottom = boundary_A(bottom, boundary_);
    cached_eta = m.eta;
    cached_bottom = bottom;
    cached_boundary = boundary_;
  }
  return {thickness_, A_top, A_bottom};
}

int Model::n(const Reduced<double>& m) const { return pairs_for_tolerance(m, slab(m), tolerance_); }

int Model::dipole_pairs(const Reduced<double>& m) const { return 2 * n(m) + 1; }

double Model::reflectance(const Reduced<double>& m, double r) const {
  return reflectance_converged(m, slab(m), n(m), r);
}
double Model::transmittance(const Reduced<double>& m, double r) const {
  return transmittance_converged(m, slab(m), n(m), r);
}
double Model::total_reflectance(const Reduced<double>& m) const {
  return multipole::total_reflectance(m, slab(m), n(m));
}
double Model::total_transmittance(const Reduced<double>& m) const {
  return multipole::total_transmittance(m, slab(m), n(m));
}
double Model::cumulative_reflectance(const Reduced<double>& m, double r) const {
  return multipole::cumulative_reflectance(m, slab(m), n(m), r);
}
double Model::cumulative_transmittance(const Reduced<double>& m, double r) const {
  return multipole::cumulative_transmittance(m, slab(m), n(m), r);
}

double Model::transmittance_radius_for_fraction(const Reduced<double>& m, double fraction) const {
  if (!(fraction > 0 && fraction < 1))
    throw InvalidInput("energy fraction", format_number(fraction), "0 < fraction < 1");
  const double target = fraction * total_transmittance(m);
  if (!(target > 0)) return std::numeric_limits<double>::infinity();
  return radius_where([&](double r) { return cumulative_transmittance(m, r); }, target, m.ell);
}

ValidityReport Model::check_validity(const Reduced<double>& m) const {
  const auto s = slab(m);
  const int pairs = n(m);
  SlabState state;
  state.thickness_over_ell = thickness_ / m.ell;
  state.total_transmittance = multipole::total_transmittance(m, s, pairs);
  state.min_reflectance = state.min_transmittance = std::numeric_limits<double>::infinity();
  // Sign of the profiles on a grid out to well past where they matter (40 ell and 10 diffuse mfp).
  const double reach = std::max(40 * m.ell, m.sigma_tr > 0 ? std::min(10 / m.sigma_tr, 1e3 * m.ell) : 1e3 * m.ell);
  for (int i = 0; i <= 64; ++i) {
    const double r = i == 0 ? 0.0 : reach * std::pow(1e-3, 1 - i / 64.0);
    state.min_reflectance = std::min(state.min_reflectance, reflectance_converged(m, s, pairs, r));
    state.min_transmittance = std::min(state.min_transmittance, transmittance_converged(m, s, pairs, r));
  }
  state.truncation_error = truncation_error(m, s, pairs);
  state.tolerance = tolerance_;
  state.converged = state.truncation_error <= tolerance_;
  return slab_validity(m, state);
}

}  // namespace bssrdf::multipole
