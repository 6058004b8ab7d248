// Inverse adding-doubling of an integrating-sphere file (.rxt), each row with its own setup (the
// header with the row's columns applied) and the row's g when it has one: per row, mu_a and mu_s' (and g
// with M_U) with 1-sigma errors propagated from the measurement errors (the file carries none:
// they are options), the fitted M_R, M_T, chi^2 and a status. Forward model: adding-doubling
// (32 angles) with the file's slides and the sphere equations of integrating_sphere.hpp; a row's
// beam at its angle of incidence (column i or options.incidence_degrees, iad's -i). g is
// held (at options.g, 0 by default as in iad) with two measurements and fitted with M_U (> 0).
// A row with M_R alone is a semi-infinite sample (iad's convention: mu_s = 1/mm, the albedo fitted).
// Rows iad would flag (M_R or M_T outside [0, 1], M_R + M_T > 1 without spheres, M_U < 0 or above
// M_T, M_R below a non-scattering sample's) get a status saying so and no fit.
// Lost light (options.lost_light, off by default): light leaving the sample beyond the sphere's
// sample port is not collected. The project's Monte Carlo reference (pencil beam: the beam
// diameter is not modelled) at the current estimate gives the diffuse reflectance and
// transmittance beyond each port's radius; they are subtracted from UR1 and UT1 (as iad does)
// and the row is refitted until the losses change by less than 1e-4 (an accelerated fixed-point
// iteration, at most 20 passes). Losses for diffuse light (URU, UTU) are not corrected.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bssrdf/fit/integrating_sphere.hpp"
#include "bssrdf/io/rxt.hpp"

namespace bssrdf {

// iad's constraints (-a, -b, -A, -F, -j), for every row; a row's own column (a b A F) is used
// where no option is given (the option wins, as in iad). NaN: not given. With one of them a row's
// remaining unknowns are solved as iad's determine_search chooses (constrained_search.hpp): with
// M_R and M_T the other coefficient and g (g held when given by --g or the row's column g, the
// coefficient then from M_T alone, as iad), with M_R or M_T alone the other coefficient.
struct RxtConstraintOptions {
  double albedo = NAN;             // a = mu_s / (mu_a + mu_s), iad -a
  double optical_thickness = NAN;  // b = (mu_a + mu_s) d, iad -b
  double mu_a = NAN, mu_s = NAN;   // 1/mm, iad -A and -F
  double mu_s_prime = NAN;         // 1/mm, iad -j: mu_s = mu_s' / (1 - g) with --g, else mu_s = mu_s' (iad's)
  // iad -F 'P lambda0 mu_s0 gamma': mu_s = mu_s0 (lambda / lambda0)^gamma per row (needs wavelengths).
  double power_lambda0 = NAN, power_mu_s0 = NAN, power_gamma = NAN;
  bool any() const;
};

struct RxtFitOptions {
  double g = NAN;  // iad's -g; NaN: not given (held at 0 as iad; fitted with a constraint and M_R, M_T)
  double reflectance_stderr = 0.002, transmittance_stderr = 0.002, unscattered_stderr = 0.002;
  bool lost_light = false;  // Monte Carlo lost-light correction (needs a sphere)
  std::uint64_t lost_light_photons = 100'000;
  SphereModel sphere;  // iad's instrument options (baffles, f, r_d, dual beam, c, C)
  int quadrature = 0;  // angles per hemisphere as iad's -q; 0: 32 for the result (iad's default is 8)
  RxtConstraintOptions constraints;
  double incidence_degrees = NAN;  // iad's -i: every row's angle of incidence, over the column i; NaN: the file's
};

struct RxtRowFit {
  RxtRow row;
  double mu_a = 0, mu_a_stderr = 0, mu_s_prime = 0, mu_s_prime_stderr = 0, g = 0, g_stderr = 0;  // 1/mm
  double fitted_m_r = 0, fitted_m_t = 0, fitted_m_u = -1;
  double chi2 = 0;
  double ur1_lost = 0, ut1_lost = 0;  // per incident flux, when the lost-light correction is on
  bool converged = false;
  std::string status;      // "converged", or why not
  std::string constraint;  // with a constraint: what was held and what solved, e.g. "a = 0.9 held; b, g from M_R, M_T"
};

struct RxtFit {
  RxtFile file;
  RxtFitOptions options;
  std::vector<RxtRowFit> rows;
  double seconds = 0;
};

RxtFit fit_rxt(const RxtFile& file, const RxtFitOptions& options = {});

}  // namespace bssrdf
