// Reflection and transmission operators of scattering layers on the quadrature angles, and the
// adding equations that combine them (van de Hulst 1980; Prahl 1995, sec. 5.3-5.6).
//
// Operators act on flux vectors: component i is the flux 2 mu_i w_i L(mu_i) carried by angle i
// (normalised so that a unit flux leaving in every direction sums to one). In this form Prahl's
// "star" product is the ordinary matrix product, and the total reflectance of unit flux arriving
// in angle j is the column sum of R.
#pragma once

#include <Eigen/Dense>

#include "angles.hpp"

namespace bssrdf::adding_doubling {

// Fixed-size matrices for the angle counts inversions use most (iad's 8, oblique 12, the search's
// 16): Eigen then unrolls the small products and allocates nothing, where the dynamic-size path
// spends most of an 8-angle solve in its general product kernels and malloc. Any other count takes
// the dynamic path (Eigen::Dynamic); the same formulas either way.
template <int N>
using Square = Eigen::Matrix<double, N, N>;
template <int N>
using Column = Eigen::Matrix<double, N, 1>;

struct LayerOperator {
  Eigen::MatrixXd R_top;     // light arriving from above, reflected up
  Eigen::MatrixXd R_bottom;  // light arriving from below, reflected down
  Eigen::MatrixXd T_down;    // from above, transmitted down
  Eigen::MatrixXd T_up;      // from below, transmitted up
};

// The Henyey-Greenstein phase function of asymmetry g on the angles, azimuthally averaged, after delta-M
// truncation to 2N Legendre terms: the same- and opposite-hemisphere blocks. It depends on g and the
// angles only, so slabs of one medium at several thicknesses share it.
struct PhaseBlocks {
  Eigen::MatrixXd same, opposite;
};
PhaseBlocks phase_blocks(const Angles& angles, double g);

// The single-scattering albedo after delta-M truncation to 2N Legendre terms (N = points).
double delta_m_albedo(double albedo, double g, std::size_t points);

struct LayerModes;

// A homogeneous Henyey-Greenstein layer of single-scattering albedo `albedo` and optical thickness
// `optical_thickness` (may be infinite: the semi-infinite medium). Delta-M with 2N Legendre terms;
// `phase`, when given, is phase_blocks(angles, g) computed once for several layers. Finite layers
// come from the medium's modes (layer_modes.hpp; `modes`, when given, is
// layer_modes(angles, delta_m_albedo(...), phase) computed once for several thicknesses); the
// semi-infinite one, and finite ones near conservative scattering (where the modes lose precision),
// from doubled_layer.
LayerOperator homogeneous_layer(const Angles& angles, double albedo, double g, double optical_thickness,
                                const PhaseBlocks* phase = nullptr, const LayerModes* modes = nullptr);

// The same by doubling a thin start (the diamond scheme) ~log2(tau / start) times, or until it stops
// changing for tau infinite; albedo_m and tau delta-M scaled, `phase` as phase_blocks.
LayerOperator doubled_layer(const Angles& angles, double albedo_m, const PhaseBlocks& phase, double tau);

// `upper` on top of `lower`.
LayerOperator add(const LayerOperator& upper, const LayerOperator& lower);

}  // namespace bssrdf::adding_doubling
