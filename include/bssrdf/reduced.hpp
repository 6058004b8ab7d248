// Reduced (similarity-relation) coefficients and the diffusion quantities derived from them, named
// as in the papers (Jensen et al. 2001; d'Eon 2012). Templated on the scalar so the same code runs in double and
// under ceres::Jet for fitting.
//
//   sigma_s'  = sigma_s (1 - g)            sigma_t' = sigma_a + sigma_s'
//   alpha'    = sigma_s' / sigma_t'        ell      = 1 / sigma_t'        (transport mfp)
//   D         = 1 / (3 sigma_t')           D_G      = (2 sigma_a + sigma_s') / (3 sigma_t'^2)
//   sigma_tr  = sqrt(sigma_a / D)          ell_d    = 1 / sigma_tr        (diffuse mfp)
#pragma once

#include <cmath>

namespace bssrdf {

template <class T>
struct Reduced {
  T sigma_a;        // absorption, 1/length
  T sigma_s;        // scattering (unreduced), 1/length
  T g;              // phase-function mean cosine
  T eta;            // relative index n_medium / n_outside
  T sigma_s_prime;  // reduced scattering
  T sigma_t_prime;  // reduced extinction
  T albedo_prime;   // reduced single-scattering albedo alpha'
  T ell;            // transport mean free path 1/sigma_t'
  T D;              // classical diffusion coefficient 1/(3 sigma_t')
  T D_G;            // Grosjean diffusion coefficient
  T sigma_tr;       // classical effective transport coefficient sqrt(3 sigma_a sigma_t')
  T sigma_tr_G;     // sqrt(sigma_a / D_G), used by the improved (better-dipole) theory
  T ell_d;          // classical diffuse mean free path 1/sigma_tr (infinite when sigma_a = 0)

  T sigma_t() const { return sigma_a + sigma_s; }
  T albedo() const { return sigma_s / sigma_t(); }
};

template <class T>
Reduced<T> reduce(T sigma_a, T sigma_s, T g, T eta) {
  using std::sqrt;
  Reduced<T> m;
  m.sigma_a = sigma_a;
  m.sigma_s = sigma_s;
  m.g = g;
  m.eta = eta;
  m.sigma_s_prime = sigma_s * (T(1) - g);
  m.sigma_t_prime = sigma_a + m.sigma_s_prime;
  m.albedo_prime = m.sigma_s_prime / m.sigma_t_prime;
  m.ell = T(1) / m.sigma_t_prime;
  m.D = T(1) / (T(3) * m.sigma_t_prime);
  m.D_G = (T(2) * sigma_a + m.sigma_s_prime) / (T(3) * m.sigma_t_prime * m.sigma_t_prime);
  m.sigma_tr = sqrt(T(3) * sigma_a * m.sigma_t_prime);
  m.sigma_tr_G = sqrt(sigma_a / m.D_G);
  m.ell_d = T(1) / m.sigma_tr;
  return m;
}

// From reduced coefficients directly (g = 0, sigma_s = sigma_s'), e.g. for published data that
// give only sigma_s', or for optical units where sigma_t' = 1.
template <class T>
Reduced<T> reduce_prime(T sigma_a, T sigma_s_prime, T eta) {
  return reduce(sigma_a, sigma_s_prime, T(0), eta);
}

// The similarity relation: the reduced albedo alpha' = alpha (1 - g) / (1 - alpha g) of a medium of
// single-scattering albedo alpha and anisotropy g (Wyman, Patterson & Wilson 1989);
// albedo_from_reduced below is its inverse.
template <class T>
T reduced_albedo(T albedo, T g) {
  return albedo * (T(1) - g) / (T(1) - albedo * g);
}

// The single-scattering albedo alpha whose similarity-reduced albedo is alpha' at anisotropy g:
// the inverse of alpha' = alpha (1 - g) / (1 - alpha g).
template <class T>
T albedo_from_reduced(T albedo_prime, T g) {
  return albedo_prime / (T(1) - g + albedo_prime * g);
}

// Optical units (sigma_t' = 1, lengths in transport mean free paths) for a given alpha'.
template <class T>
Reduced<T> reduced_optical(T albedo_prime, T eta) {
  return reduce_prime(T(1) - albedo_prime, albedo_prime, eta);
}

// The same at anisotropy g: sigma_s' = alpha', sigma_a = 1 - alpha', sigma_s = alpha' / (1 - g).
template <class T>
Reduced<T> reduced_optical(T albedo_prime, T g, T eta) {
  return reduce(T(1) - albedo_prime, albedo_prime / (T(1) - g), g, eta);
}

// Units of the (unreduced) extinction: sigma_t = 1, lengths in mean free paths, for albedo alpha.
template <class T>
Reduced<T> reduced_unit_extinction(T albedo, T g, T eta) {
  return reduce(T(1) - albedo, albedo, g, eta);
}

}  // namespace bssrdf
