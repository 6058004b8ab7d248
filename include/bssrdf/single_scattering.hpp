// Exact single scattering below a smooth planar boundary for a normally incident pencil beam, with
// the true Henyey-Greenstein phase function (not the similarity-reduced one) and total internal
// reflection on exit. Diffusion models omit this part; add it before comparing with totals that
// include it (adding-doubling, Monte Carlo).
//
//   R_ss = alpha int_0^1 2 pi p_HG(-mu) (1 - F_r(mu; eta)) mu / (1 + mu) dmu     (per entered flux)
//   eta = 1, g = 0:  R_ss = (alpha / 2)(1 - ln 2)
#pragma once

namespace bssrdf {

// Henyey-Greenstein phase function value for the cosine between propagation directions.
double henyey_greenstein(double cos_theta, double g);

// Total single-scattering reflectance per unit entered flux, semi-infinite medium.
double single_scattering_total(double albedo, double g, double eta);

}  // namespace bssrdf
