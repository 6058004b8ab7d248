// Multipole for slabs (Donner & Jensen 2005): a slab of thickness d
// between two boundaries with their own extrapolation distances z_b0 = 2 A_0 D (top) and
// z_bd = 2 A_d D (bottom), classical D = 1/(3 sigma_t'). Dipole pairs i = -n..n mirror the real
// source at depth ell in both extrapolated boundaries, with period L = 2 (d + z_b0 + z_bd):
//
//   z_{r,i} = i L + ell            z_{v,i} = i L - ell - 2 z_b0
//   R(r) = alpha' sum_i [ flux(z_{r,i}, r) - flux(z_{v,i}, r) ]           (flux() of point_source.hpp)
//   T(r) = alpha' sum_i [ flux(d - z_{r,i}, r) - flux(d - z_{v,i}, r) ]
//
// n = 0 with the classical A is the classical dipole; n grows until the totals of the truncated
// sum lie within a tolerance of the infinite series (pairs_for_tolerance). Multiple scattering
// only; the ballistic (unscattered) transmission e^{-sigma_t d} is not part of T.
//
// Spectra: the 2D Fourier (zero-order Hankel) transform of flux(z, .) is sgn(z) e^{-|z| s}/2 with
// s = sqrt(sigma_tr^2 + k^2), so the infinite series of every slab is a geometric series with a
// closed form at every k (spectra()); at k = 0 it gives the exact totals of the infinite multipole.
// Layer stacks combine these spectra (layered.hpp).
//
//   auto slab = multipole::make_slab(2.0, 1.3, 1.3);      // d = 2 mm, eta above and below
//   int n = multipole::pairs_for_tolerance(m, slab, 1e-5);
//   double R = multipole::reflectance(m, slab, n, 0.5), T = multipole::transmittance(m, slab, n, 0.5);
#pragma once

#include <cmath>
#include <optional>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/image_source.hpp"
#include "bssrdf/models/point_source.hpp"

namespace bssrdf::multipole {

// Which boundary parameter A each face uses: the Egan-Hilgeman A of Donner & Jensen, or the
// improved (1 + 3C2)/(1 - 2C1) of d'Eon 2012. Classical is the default: it is measurably closer to
// adding-doubling on slabs (tests/test_multipole.cpp prints both).
enum class BoundaryA { classical, improved };

template <class T>
T boundary_A(T eta, BoundaryA which) {
  return which == BoundaryA::classical ? boundary_A_classical(eta) : improved_boundary(eta).A;
}

// A slab: thickness (length) and the A of its top and bottom faces.
template <class T>
struct Slab {
  T thickness;
  T A_top, A_bottom;
};

// eta_top = n_slab / n_above, eta_bottom = n_slab / n_below.
template <class T>
Slab<T> make_slab(T thickness, T eta_top, T eta_bottom, BoundaryA which = BoundaryA::classical) {
  return {thickness, boundary_A(eta_top, which), boundary_A(eta_bottom, which)};
}

// The same slab lit from below (faces swapped): what light coming back up from a lower layer sees.
template <class T>
Slab<T> flipped(const Slab<T>& s) {
  return {s.thickness, s.A_bottom, s.A_top};
}

template <class T>
struct Geometry {
  T d, ell, z_b0, z_bd, period, sigma_tr;
  T z_r(int i) const { return T(i) * period + ell; }
  T z_v(int i) const { return T(i) * period + image_depth(ell, z_b0); }
};

template <class T>
Geometry<T> geometry(const Reduced<T>& m, const Slab<T>& s) {
  const T z_b0 = extrapolation_distance(s.A_top, m.D), z_bd = extrapolation_distance(s.A_bottom, m.D);
  return {s.thickness, m.ell, z_b0, z_bd, T(2) * (s.thickness + z_b0 + z_bd), m.sigma_tr};
}

// Pair i's share of R(r) (at the top face) or of T(r) (at the bottom face), without alpha'.
template <class T>
T pair_reflectance(const Geometry<T>& g, int i, T r) {
  return point_source::flux(g.z_r(i), g.sigma_tr, r) - point_source::flux(g.z_v(i), g.sigma_tr, r);
}
template <class T>
T pair_transmittance(const Geometry<T>& g, int i, T r) {
  return point_source::flux(g.d - g.z_r(i), g.sigma_tr, r) - point_source::flux(g.d - g.z_v(i), g.sigma_tr, r);
}

template <class T>
T reflectance(const Reduced<T>& m, const Slab<T>& s, int n, T r) {
  const auto g = geometry(m, s);
  T sum = T(0);
  for (int i = -n; i <= n; ++i) sum += pair_reflectance(g, i, r);
  return m.albedo_prime * sum;
}

template <class T>
T transmittance(const Reduced<T>& m, const Slab<T>& s, int n, T r) {
  const auto g = geometry(m, s);
  T sum = T(0);
  for (int i = -n; i <= n; ++i) sum += pair_transmittance(g, i, r);
  return m.albedo_prime * sum;
}

// Far from the beam the truncated sum is not enough: each image decays like e^{-sigma_tr r},
// the slab's true profile faster, so the truncation error overtakes R(r) at r of a few n L.
// These add pairs beyond n (at least until the images lie deeper than r) until the last pair
// changes the sum by less than 1e-9 of it: R(r), T(r) of the infinite series pointwise. Where
// the images cancel below the rounding of their sum (R < 1e-12 of the sum of magnitudes) they
// return 0.
double reflectance_converged(const Reduced<double>& m, const Slab<double>& s, int n, double r);
double transmittance_converged(const Reduced<double>& m, const Slab<double>& s, int n, double r);

// int_0^rho 2 pi r R(r) dr and the same for T (rho = infinity: the n-pair totals).
template <class T>
T cumulative_reflectance(const Reduced<T>& m, const Slab<T>& s, int n, T rho) {
  using point_source::flux_cumulative;
  const auto g = geometry(m, s);
  T sum = T(0);
  for (int i = -n; i <= n; ++i)
    sum += flux_cumulative(g.z_r(i), g.sigma_tr, rho) - flux_cumulative(g.z_v(i), g.sigma_tr, rho);
  return m.albedo_prime * sum;
}

template <class T>
T cumulative_transmittance(const Reduced<T>& m, const Slab<T>& s, int n, T rho) {
  using point_source::flux_cumulative;
  const auto g = geometry(m, s);
  T sum = T(0);
  for (int i = -n; i <= n; ++i)
    sum += flux_cumulative(g.d - g.z_r(i), g.sigma_tr, rho) - flux_cumulative(g.d - g.z_v(i), g.sigma_tr, rho);
  return m.albedo_prime * sum;
}

// The spectra of the infinite series at s = sqrt(sigma_tr^2 + k^2), split into the i = 0 pair
// and the tails |i| >= 1; the tails of pairs |i| > n are q^n times the tails, q = e^{-L s}.
template <class T>
struct Spectra {
  T R_pair0, R_tails, T_pair0, T_tails, q;
  T reflectance() const { return R_pair0 + R_tails; }
  T transmittance() const { return T_pair0 + T_tails; }
};

// sum_{j>=1} e^{-j L s} sinh(a s), written so that it neither overflows at large s nor divides
// 0 by 0 as s -> 0 (its limit there is a / L); requires |a| < L.
template <class T>
T image_tail(T a, T period, T s) {
  using point_source::one_minus_exp_over_x;
  using std::abs;
  using std::exp;
  const T b = abs(a);
  const T value =
      exp(-(period - b) * s) * b * one_minus_exp_over_x(T(2) * b * s) / (period * one_minus_exp_over_x(period * s));
  return a < T(0) ? -value : value;
}

template <class T>
Spectra<T> spectra(const Reduced<T>& m, const Slab<T>& slab, T s) {
  using std::abs;
  using std::exp;
  const auto g = geometry(m, slab);
  const T a = m.albedo_prime;
  const T upper = g.ell + T(2) * g.z_b0;  // |z_{v,0}|
  Spectra<T> out;
  // Reflectance: pair 0 is the dipole; the tails pair i with -i:  -sum_j q^j [sinh(ell s) + sinh(upper s)].
  out.R_pair0 = a * T(0.5) * (exp(-g.ell * s) + exp(-upper * s));
  out.R_tails = -a * (image_tail(g.ell, g.period, s) + image_tail(upper, g.period, s));
  // Transmittance: depths below the bottom, c = d - ell (negative when the source lies outside).
  const T c = g.d - g.ell, b = g.d + upper;
  out.T_pair0 = a * T(0.5) * ((c < T(0) ? -exp(-abs(c) * s) : exp(-c * s)) - exp(-b * s));
  out.T_tails = a * (image_tail(b, g.period, s) - image_tail(c, g.period, s));
  out.q = exp(-g.period * s);
  return out;
}

template <class T>
Spectra<T> spectra_at_k(const Reduced<T>& m, const Slab<T>& slab, T k) {
  using std::sqrt;
  return spectra(m, slab, sqrt(m.sigma_tr * m.sigma_tr + k * k));
}

// Closed-form totals of the infinite series (k = 0), and of the n-pair truncation.
template <class T>
T total_reflectance(const Reduced<T>& m, const Slab<T>& s) {
  return spectra(m, s, m.sigma_tr).reflectance();
}
template <class T>
T total_transmittance(const Reduced<T>& m, const Slab<T>& s) {
  return spectra(m, s, m.sigma_tr).transmittance();
}
template <class T>
T total_reflectance(const Reduced<T>& m, const Slab<T>& s, int n) {
  using std::pow;
  const auto sp = spectra(m, s, m.sigma_tr);
  return sp.R_pair0 + sp.R_tails * (T(1) - pow(sp.q, n));
}
template <class T>
T total_transmittance(const Reduced<T>& m, const Slab<T>& s, int n) {
  using std::pow;
  const auto sp = spectra(m, s, m.sigma_tr);
  return sp.T_pair0 + sp.T_tails * (T(1) - pow(sp.q, n));
}

// The smallest n (pairs i = -n..n, 2n + 1 dipoles) whose totals are within `tolerance` of the
// infinite series: |R_rest| + |T_rest| = q^n (|R_tails| + |T_tails|) <= tolerance. This bounds the
// sum of all further increments, not just the next one. Without absorption (q = 1) the series
// never converges in finitely many pairs: returns max_pairs (see converged()).
inline constexpr int kMaxPairs = 2000;
int pairs_for_tolerance(const Reduced<double>& m, const Slab<double>& s, double tolerance, int max_pairs = kMaxPairs);
// |R_rest| + |T_rest| after n pairs.
double truncation_error(const Reduced<double>& m, const Slab<double>& s, int n);

// The runtime face: a slab of fixed thickness (mm) in the library's unit; the top face uses the
// medium's eta, the bottom face eta_bottom (n_slab / n_below; default the same as the top, i.e.
// the same ambient on both sides). total_reflectance() is the closed-form total of the 2n + 1
// pairs chosen for the tolerance (within it of the infinite series; cumulative_reflectance() uses
// the same pairs); reflectance() is R(r) of at least those pairs, more far from the beam
// (reflectance_converged), so the profile stays accurate and positive where it is tiny.
class Model final : public bssrdf::Model {
 public:
  explicit Model(double thickness_mm, std::optional<double> eta_bottom = std::nullopt, double tolerance = 1e-5,
                 BoundaryA boundary = BoundaryA::classical);

  std::string name() const override { return "multipole"; }
  std::string description() const override;
  bool includes_single_scattering() const override { return false; }
  double reflectance(const Reduced<double>& m, double r) const override;
  double total_reflectance(const Reduced<double>& m) const override;
  double cumulative_reflectance(const Reduced<double>& m, double r) const override;
  ValidityReport check_validity(const Reduced<double>& m) const override;

  double transmittance(const Reduced<double>& m, double r) const;
  double total_transmittance(const Reduced<double>& m) const;
  double cumulative_transmittance(const Reduced<double>& m, double r) const;
  // The radius holding `fraction` of the total transmittance (infinite if T_total <= 0).
  double transmittance_radius_for_fraction(const Reduced<double>& m, double fraction) const;
  // Dipole pairs used (2n + 1) for this channel.
  int dipole_pairs(const Reduced<double>& m) const;

  double thickness() const { return thickness_; }
  double tolerance() const { return tolerance_; }
  Slab<double> slab(const Reduced<double>& m) const;

 private:
  int n(const Reduced<double>& m) const;
  double thickness_;
  std::optional<double> eta_bottom_;
  double tolerance_;
  BoundaryA boundary_;
};

}  // namespace bssrdf::multipole
