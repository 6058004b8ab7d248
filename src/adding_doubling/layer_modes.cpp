// Discrete-ordinate modes of a homogeneous layer and its operators at any thickness; see
// layer_modes.hpp.
#include "layer_modes.hpp"

#include <cmath>

namespace bssrdf::adding_doubling {

using Eigen::MatrixXd;
using Eigen::VectorXd;

LayerModes layer_modes(const Angles& angles, double albedo_m, const PhaseBlocks& phase) {
  const auto n = static_cast<Eigen::Index>(angles.size());
  VectorXd root_w(n), root_mu_inverse(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    root_w(i) = std::sqrt(angles.weight[i]);
    root_mu_inverse(i) = 1 / std::sqrt(angles.mu[i]);
  }
  // With u = I+ + I- and v = I+ - I-: du/dtau = -B+ v, dv/dtau = -B- u in the basis
  // diag(sqrt(mu w)) (the doubling's, up to sqrt 2), where
  //   B-+ = M^-1/2 (I - albedo W^1/2 (same +- opposite) W^1/2) M^-1/2
  // are symmetric, B+ positive definite, B- semi-definite (singular for conservative scattering).
  const MatrixXd I = MatrixXd::Identity(n, n);
  auto B = [&](double sign) -> MatrixXd {
    const MatrixXd scattering = root_w.asDiagonal() * (phase.same + sign * phase.opposite) * root_w.asDiagonal();
    return root_mu_inverse.asDiagonal() * (I - albedo_m * scattering) * root_mu_inverse.asDiagonal();
  };
  const MatrixXd B_plus = B(-1), B_minus = B(1);
  // u'' = B+ B- u: with B+ = L L^T, the modes are X = L Y for the symmetric eigenproblem
  // L^T B- L Y = Y K^2, and v = B+^-1 X K = L^-T Y K for the decaying ones (no division by k).
  const Eigen::LLT<MatrixXd> cholesky(B_plus);
  const MatrixXd L = cholesky.matrixL();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eigen(L.transpose() * B_minus * L);
  LayerModes modes;
  modes.k = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const MatrixXd& Y = eigen.eigenvectors();
  const MatrixXd X = L * Y;
  const MatrixXd V = L.transpose().triangularView<Eigen::Upper>().solve(Y * modes.k.asDiagonal());
  // I+ = (u + v)/2, I- = (u - v)/2 of the decaying modes; the growing ones swap them.
  modes.G_plus = (X + V) / 2;
  modes.G_minus = (X - V) / 2;
  modes.Q = modes.G_plus.partialPivLu().solve(modes.G_minus);
  modes.P = modes.G_plus - modes.G_minus * modes.Q;
  modes.s.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) modes.s(i) = std::sqrt(2 * angles.mu[i] * angles.weight[i]);
  return modes;
}

bool modes_well_conditioned(const LayerModes& modes) {
  // The boundary system's smallest singular value is ~k_min (the slowest mode's up- and downward
  // parts nearly cancel), so rounding grows by 1/k_min: 1e-3 keeps it below ~1e-13.
  return modes.k.minCoeff() > 1e-3;
}

LayerOperator layer_from_modes(const LayerModes& modes, double tau) {
  const auto n = modes.k.size();
  // Amplitudes a of the decaying modes (at the top) and b of the growing ones (at the bottom, so
  // that only e^{-k tau} <= 1 appears): light f entering at the top only,
  //   G+ a + G- E b = f,  G- E a + G+ b = 0  =>  b = -Q E a,  Z a = f,  Z = G+ - G- E Q E;
  // reflected I-(0) = (G- - G+ E Q E) a, transmitted I+(tau) = (G+ - G- Q) E a = P E a.
  const VectorXd e = (-modes.k * tau).array().exp().matrix();
  const MatrixXd EQE = e.asDiagonal() * modes.Q * e.asDiagonal();
  const MatrixXd Z = modes.G_plus - modes.G_minus * EQE;
  MatrixXd right(n, 2 * n);  // [R^T, T^T] = Z^-T [N^T, (P E)^T]
  right.leftCols(n) = (modes.G_minus - modes.G_plus * EQE).transpose();
  right.rightCols(n) = (modes.P * e.asDiagonal()).transpose();
  const MatrixXd RT = Z.transpose().partialPivLu().solve(right);
  // Symmetric in this basis by reciprocity, up to rounding; then to flux operators.
  const MatrixXd R = (RT.leftCols(n) + RT.leftCols(n).transpose()) / 2;
  const MatrixXd T = (RT.rightCols(n) + RT.rightCols(n).transpose()) / 2;
  const VectorXd s_inverse = modes.s.cwiseInverse();
  const MatrixXd R_flux = modes.s.asDiagonal() * R * s_inverse.asDiagonal();
  const MatrixXd T_flux = modes.s.asDiagonal() * T * s_inverse.asDiagonal();
  return {R_flux, R_flux, T_flux, T_flux};
}

}  // namespace bssrdf::adding_doubling
