// Thin-layer start (diamond initialisation), doubling and adding; see layer_operator.hpp.
#include "layer_operator.hpp"

#include <cmath>
#include <limits>

#include "layer_modes.hpp"

namespace bssrdf::adding_doubling {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Starting layers are no thicker than 4 times the smallest cosine (in optical depth): measured on
// Prahl's tables, 1 and 8 give the same totals to 4e-9, 64 is off by 1.5e-4 (the diamond scheme's
// attenuation (1 - t/2mu)/(1 + t/2mu) of the most grazing angles goes wrong for t >> mu).
constexpr double kStartThicknessPerMu = 4.0;

// Azimuthally averaged HG phase function after delta-M truncation to 2N Legendre terms (Wiscombe
// 1977): chi*_k = (g^k - f)/(1 - f), f = g^2N. p(mu, mu') = sum (2k+1)/2 chi*_k P_k(mu) P_k(mu'),
// normalised so that int_{-1}^{1} p dmu' = 1. Returns the same- and opposite-hemisphere blocks.
PhaseBlocks truncated_phase_blocks(const Angles& angles, double g, double f) {
  const int n = static_cast<int>(angles.size()), terms = 2 * n;
  MatrixXd P(terms, n);  // P_k(mu_i)
  for (int i = 0; i < n; ++i) {
    const double x = angles.mu[i];
    P(0, i) = 1;
    if (terms > 1) P(1, i) = x;
    for (int k = 2; k < terms; ++k) P(k, i) = ((2 * k - 1) * x * P(k - 1, i) - (k - 1) * P(k - 2, i)) / k;
  }
  VectorXd c(terms);
  for (int k = 0; k < terms; ++k) c(k) = (2 * k + 1) / 2.0 * (f < 1 ? (std::pow(g, k) - f) / (1 - f) : (k == 0));
  // P_k(-mu) = (-1)^k P_k(mu): with E and O the sums over even and odd k, same = E + O and
  // opposite = E - O, half the products of forming both directly (terms = 2n is even).
  const int half = terms / 2;
  MatrixXd P_even(half, n), P_odd(half, n);
  VectorXd c_even(half), c_odd(half);
  for (int k = 0; k < half; ++k) {
    P_even.row(k) = P.row(2 * k);
    P_odd.row(k) = P.row(2 * k + 1);
    c_even(k) = c(2 * k);
    c_odd(k) = c(2 * k + 1);
  }
  const MatrixXd E = P_even.transpose() * c_even.asDiagonal() * P_even;
  const MatrixXd O = P_odd.transpose() * c_odd.asDiagonal() * P_odd;
  MatrixXd same = E + O, opposite = E - O;
  // Exact energy conservation on the discrete angles: put each row's defect on the diagonal
  // (forward scattering), keeping the matrix symmetric.
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int j = 0; j < n; ++j) sum += angles.weight[j] * (same(i, j) + opposite(i, j));
    same(i, i) += (1 - sum) / angles.weight[i];
  }
  return {same, opposite};
}

// Diamond initialisation (Wiscombe 1976) of a layer of optical thickness t: the transfer equation
// with the radiance inside taken as the mean of its values on the two faces. With light entering
// at the top only, u = L_down(bottom) + L_up(top) and v = their difference solve two N x N systems.
// Returns R and T (equal from both sides) in the symmetric basis S^-1 (.) S, S = diag(s).
template <int N>
void thin_layer(const Angles& angles, double albedo, const Square<N>& same, const Square<N>& opposite, double t,
                const Column<N>& s, Square<N>& R, Square<N>& T) {
  const int n = static_cast<int>(angles.size());
  Column<N> w(n), mu(n);
  for (int i = 0; i < n; ++i) {
    w(i) = angles.weight[i];
    mu(i) = angles.mu[i];
  }
  const Square<N> Sp = albedo / 2 * same * w.asDiagonal();
  const Square<N> Sm = albedo / 2 * opposite * w.asDiagonal();
  Square<N> D = (mu / t).asDiagonal();
  const Square<N> I = Square<N>::Identity(n, n);
  const Square<N> G = D + I / 2 - Sp, H = D - I / 2 + Sp;
  const Square<N> U = (G - Sm).partialPivLu().solve(H + Sm);
  const Square<N> V = (G + Sm).partialPivLu().solve(H - Sm);
  // Radiance operators to the symmetric basis: the flux operators are C (.) C^-1 with C =
  // diag(2 mu w) = S^2, so S^-1 C (.) C^-1 S = S (.) S^-1; symmetric up to rounding already.
  const Column<N> s_inverse = s.cwiseInverse();
  const Square<N> r = s.asDiagonal() * ((U - V) / 2) * s_inverse.asDiagonal();
  const Square<N> d = s.asDiagonal() * ((U + V) / 2) * s_inverse.asDiagonal();
  R = (r + r.transpose()) / 2;
  T = (d + d.transpose()) / 2;
}

// Two copies of a homogeneous (up-down symmetric) layer: R2 = R + T R (I - RR)^-1 T,
// T2 = T (I - RR)^-1 T (R commutes with (I - RR)^-1). Valid in any basis; the fallback of
// double_symmetric.
template <int N>
void double_layer(Square<N>& R, Square<N>& T) {
  const Square<N> I = Square<N>::Identity(R.rows(), R.cols());
  const Square<N> Y = (I - R * R).partialPivLu().solve(T);
  const Square<N> TR = T * R;
  R += TR * Y;
  T = T * Y;
}

// The same doubling for R and T in the symmetric basis C^-1/2 (.) C^1/2, C = diag(2 mu w), where
// reciprocity makes both symmetric (Prahl 1995, sec. 5.3: his R and T are symmetric and the flux
// operators are C R, C T). Splitting (I - RR)^-1 = [(I - R)^-1 + (I + R)^-1] / 2 gives
//   R2 + T2 = R + T (I - R)^-1 T,   R2 - T2 = R - T (I + R)^-1 T,
// and I -+ R are positive definite (the eigenvalues of R lie in (-1, 1)), so each term is
// T A^-1 T = V V^T with V = T L^-T from a Cholesky factor A = L L^T: under half the operations of
// the LU form, with symmetric results by construction. Returns false (R, T untouched) if a
// factorisation fails. Written as whole-column and rank-one operations on fixed-size matrices,
// which Eigen unrolls and vectorises: at 8-16 angles its blocked factorisation, triangular solve
// and rank update spent most of their time in set-up and packing.
template <int N>
bool double_symmetric(Square<N>& R, Square<N>& T) {
  const Eigen::Index n = R.rows();
  if constexpr (N == Eigen::Dynamic) {
    // Other angle counts (32 and more for tight tolerances): Eigen's blocked factorisation, triangular solve and
    // rank update, which at these sizes beat the column loops below (and stay fast in unoptimised builds).
    MatrixXd sum = R, difference = R;  // lower triangles of R2 + T2 and R2 - T2
    for (const double sign : {1.0, -1.0}) {
      MatrixXd A = -sign * R;
      A.diagonal().array() += 1;
      const Eigen::LLT<MatrixXd> cholesky(A);
      if (cholesky.info() != Eigen::Success) return false;
      const MatrixXd W = cholesky.matrixL().solve(T);
      (sign > 0 ? sum : difference).selfadjointView<Eigen::Lower>().rankUpdate(W.transpose(), sign);
    }
    for (Eigen::Index j = 0; j < n; ++j)
      for (Eigen::Index i = j; i < n; ++i) {
        R(i, j) = R(j, i) = (sum(i, j) + difference(i, j)) / 2;
        T(i, j) = T(j, i) = (sum(i, j) - difference(i, j)) / 2;
      }
    return true;
  }
  Square<N> sum(n, n), difference(n, n);  // R2 + T2 and R2 - T2
  Square<N> A(n, n), L(n, n), V(n, n);
  for (const double sign : {1.0, -1.0}) {
    // Cholesky factor of A = I - sign R, right-looking: column k of L, then A -= l_k l_k^T.
    A = -sign * R;
    A.diagonal().array() += 1;
    L.setZero();
    for (Eigen::Index k = 0; k < n; ++k) {
      if (!(A(k, k) > 0)) return false;
      const double pivot = std::sqrt(A(k, k));
      L.col(k).tail(n - k) = A.col(k).tail(n - k) / pivot;
      A.noalias() -= L.col(k) * L.col(k).transpose();
    }
    // V L^T = T, column by column.
    for (Eigen::Index k = 0; k < n; ++k) {
      V.col(k) = T.col(k);
      for (Eigen::Index m = 0; m < k; ++m) V.col(k) -= L(k, m) * V.col(m);
      V.col(k) /= L(k, k);
    }
    (sign > 0 ? sum : difference) = R + sign * V.lazyProduct(V.transpose());
  }
  R = (sum + difference) / 2;
  T = (sum - difference) / 2;
  return true;
}

template <int N>
void double_in_symmetric_basis(Square<N>& R, Square<N>& T) {
  if (!double_symmetric<N>(R, T)) double_layer<N>(R, T);
}

// The scattering layer of homogeneous_layer after delta-M: thin-layer start of thickness `start`,
// then `doublings` doublings (or, for an infinite layer, doubling until nothing is transmitted).
template <int N>
LayerOperator scattering_layer(const Angles& angles, double albedo_m, const PhaseBlocks& phase, double start,
                               int doublings, bool infinite) {
  const int n = static_cast<int>(angles.size());
  // Double in the symmetric basis: S^-1 (.) S with S = C^1/2 = diag(sqrt(2 mu w)).
  Column<N> s(n);
  for (int i = 0; i < n; ++i) s(i) = std::sqrt(2 * angles.mu[i] * angles.weight[i]);
  const Column<N> s_inverse = s.cwiseInverse();
  Square<N> R(n, n), T(n, n);
  thin_layer<N>(angles, albedo_m, phase.same, phase.opposite, start, s, R, T);
  auto to_flux = [&](const Square<N>& m) -> MatrixXd { return s.asDiagonal() * m * s_inverse.asDiagonal(); };
  if (infinite) {
    // Double until nothing is transmitted (each doubling squares the transmission far out);
    // the column sums of the flux operator are s^T T / s^T.
    auto transmitted = [&] { return ((s.transpose() * T).array() * s_inverse.transpose().array()).maxCoeff(); };
    for (int k = 0; k < 80 && transmitted() > 1e-13; ++k) double_in_symmetric_basis<N>(R, T);
    const MatrixXd R_flux = to_flux(R);
    return {R_flux, R_flux, MatrixXd::Zero(n, n), MatrixXd::Zero(n, n)};
  }
  for (int k = 0; k < doublings; ++k) double_in_symmetric_basis<N>(R, T);
  const MatrixXd R_flux = to_flux(R), T_flux = to_flux(T);
  return {R_flux, R_flux, T_flux, T_flux};
}

// Delta-M's forward peak: the fraction g^{2N} of the phase function beyond its first 2N Legendre
// terms (N = points), which becomes unscattered light.
double delta_m_peak(double g, std::size_t points) { return std::pow(g, 2 * static_cast<int>(points)); }

}  // namespace

PhaseBlocks phase_blocks(const Angles& angles, double g) {
  return truncated_phase_blocks(angles, g, delta_m_peak(g, angles.size()));
}

double delta_m_albedo(double albedo, double g, std::size_t points) {
  const double f = delta_m_peak(g, points);
  return albedo * (1 - f) / (1 - albedo * f);
}

LayerOperator homogeneous_layer(const Angles& angles, double albedo, double g, double optical_thickness,
                                const PhaseBlocks* phase, const LayerModes* modes) {
  const int n = static_cast<int>(angles.size());
  const double f = delta_m_peak(g, angles.size());
  const double albedo_m = delta_m_albedo(albedo, g, angles.size());
  const double tau = optical_thickness * (1 - albedo * f);
  if (albedo_m == 0 || tau == 0) {  // pure absorber (or nothing): straight lines
    VectorXd e(n);
    for (int i = 0; i < n; ++i) e(i) = std::isinf(tau) ? 0.0 : std::exp(-tau / angles.mu[i]);
    const MatrixXd T = e.asDiagonal(), Z = MatrixXd::Zero(n, n);
    return {Z, Z, T, T};
  }
  const PhaseBlocks computed = phase ? PhaseBlocks{} : truncated_phase_blocks(angles, g, f);
  const PhaseBlocks& blocks = phase ? *phase : computed;
  if (!std::isinf(tau)) {
    // The modes, exact for the discrete equations at any thickness, where a thin start doubled
    // ~log2(tau / start) times costs most of a table's solves and carries the diamond scheme's error at
    // the grazing angles (~1e-5 of the totals at 32 angles). Near conservative scattering they lose
    // precision: doubling then.
    const LayerModes computed_modes = modes ? LayerModes{} : layer_modes(angles, albedo_m, blocks);
    const LayerModes& m = modes ? *modes : computed_modes;
    if (modes_well_conditioned(m)) return layer_from_modes(m, tau);
  }
  return doubled_layer(angles, albedo_m, blocks, tau);
}

LayerOperator doubled_layer(const Angles& angles, double albedo_m, const PhaseBlocks& blocks, double tau) {
  const double start_max = kStartThicknessPerMu * angles.mu.front();
  const bool infinite = std::isinf(tau);
  const int doublings = infinite ? 0 : std::max(0, static_cast<int>(std::ceil(std::log2(tau / start_max))));
  const double start = infinite ? start_max : std::ldexp(tau, -doublings);
  switch (angles.size()) {
    case 8:
      return scattering_layer<8>(angles, albedo_m, blocks, start, doublings, infinite);
    case 12:
      return scattering_layer<12>(angles, albedo_m, blocks, start, doublings, infinite);
    case 16:
      return scattering_layer<16>(angles, albedo_m, blocks, start, doublings, infinite);
    default:
      return scattering_layer<Eigen::Dynamic>(angles, albedo_m, blocks, start, doublings, infinite);
  }
}

LayerOperator add(const LayerOperator& upper, const LayerOperator& lower) {
  const auto n = upper.R_top.rows();
  const MatrixXd I = MatrixXd::Identity(n, n);
  // Downward (I - R1b R2t)^-1 and upward (I - R2t R1b)^-1 multiple reflections at the junction.
  const auto down = (I - upper.R_bottom * lower.R_top).partialPivLu();
  const auto up = (I - lower.R_top * upper.R_bottom).partialPivLu();
  LayerOperator out;
  out.T_down = lower.T_down * down.solve(upper.T_down);
  out.R_top = upper.R_top + upper.T_up * up.solve(lower.R_top * upper.T_down);
  out.R_bottom = lower.R_bottom + lower.T_down * down.solve(upper.R_bottom * lower.T_up);
  out.T_up = upper.T_up * up.solve(lower.T_up);
  return out;
}

}  // namespace bssrdf::adding_doubling
