// pbrt-v3's photon beam diffusion evaluation, written plainly for benchmarks that measure against
// it in the same process: 100 + 100 midpoint samples of the exponential per R(r).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/single_scattering.hpp"

namespace bssrdf::bench {

// pbrt-v3's BeamDiffusionMS + BeamDiffusionSS, written plainly (same physics as ours: exact
// internal Fresnel moments for the boundary, true HG phase for single scattering).
inline double pbrt_style_pbd(const Reduced<double>& m, const ImprovedBoundary<double>& b, double r, int samples = 100) {
  const double sigma_tp = m.sigma_t_prime, D = m.D_G, sigma_tr = m.sigma_tr_G, ze = -2 * D * b.A;
  double ms = 0;
  for (int i = 0; i < samples; ++i) {
    const double zr = -std::log(1 - (i + 0.5) / samples) / sigma_tp;
    const double zv = -zr + 2 * ze;
    const double dr = std::sqrt(r * r + zr * zr), dv = std::sqrt(r * r + zv * zv);
    const double phiD =
        1 / (4 * std::numbers::pi * D) * (std::exp(-sigma_tr * dr) / dr - std::exp(-sigma_tr * dv) / dv);
    const double EDn = 1 / (4 * std::numbers::pi) *
                       (zr * (1 + sigma_tr * dr) * std::exp(-sigma_tr * dr) / (dr * dr * dr) -
                        zv * (1 + sigma_tr * dv) * std::exp(-sigma_tr * dv) / (dv * dv * dv));
    const double E = phiD * b.C_phi + EDn * b.C_E;
    const double kappa = 1 - std::exp(-2 * sigma_tp * (dr + zr));
    ms += kappa * m.albedo_prime * m.albedo_prime * E;
  }
  ms /= samples;
  const double sigma_t = m.sigma_t(), t_crit = r * std::sqrt(std::max(0.0, m.eta * m.eta - 1));
  double ss = 0;
  for (int i = 0; i < samples; ++i) {
    const double t = t_crit - std::log(1 - (i + 0.5) / samples) / sigma_t;
    const double d = std::sqrt(r * r + t * t), cos_o = t / d;
    ss += m.albedo() * std::exp(-sigma_t * (d + t_crit)) / (d * d) * henyey_greenstein(-cos_o, m.g) *
          (1 - fresnel_reflectance(cos_o, m.eta)) * cos_o;
  }
  return ms + ss / samples;
}

}  // namespace bssrdf::bench
