// A homogeneous layer at any thickness from the modes of its transfer equation on the quadrature
// angles (discrete ordinates: Stamnes & Swanson 1981; Nakajima & Tanaka 1986, the symmetric form).
// The radiance equations M dI+/dtau = -(I - S+) I+ + S- I-, -M dI-/dtau = ... have solutions
// e^{-+k tau} along 2N modes; one eigen-decomposition per medium and angle count gives R(tau) and
// T(tau) for every thickness with a few N x N products, where doubling spends ~log2(tau / start)
// doublings per thickness. They solve the same discrete equations; doubling adds its thin start's
// error (~1e-9), the modes the eigen-solver's rounding.
#pragma once

#include <Eigen/Dense>

#include "angles.hpp"
#include "layer_operator.hpp"

namespace bssrdf::adding_doubling {

// The modes of one medium (delta-M albedo, phase function) on one set of angles, in the symmetric
// basis of the doubling (R and T symmetric there).
struct LayerModes {
  Eigen::VectorXd k;        // decay rate of each mode per optical depth, >= 0
  Eigen::MatrixXd G_plus;   // downward radiance of the decaying modes (upward of the growing ones)
  Eigen::MatrixXd G_minus;  // upward radiance of the decaying modes (downward of the growing ones)
  Eigen::MatrixXd Q;        // G_plus^-1 G_minus
  Eigen::MatrixXd P;        // G_plus - G_minus Q
  Eigen::VectorXd s;        // the symmetric basis: S^-1 (flux operator) S, S = diag(sqrt(2 mu w))
};

LayerModes layer_modes(const Angles& angles, double albedo_m, const PhaseBlocks& phase);

// Whether the modes give a layer to full precision: not near conservative scattering, where the
// slowest mode's k -> 0 makes the boundary system singular (the solution turns linear in tau).
bool modes_well_conditioned(const LayerModes& modes);

// The flux operators of a layer of optical thickness tau (finite, delta-M scaled).
LayerOperator layer_from_modes(const LayerModes& modes, double tau);

}  // namespace bssrdf::adding_doubling
