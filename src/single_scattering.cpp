#include "bssrdf/single_scattering.hpp"

#include <cmath>
#include <numbers>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/quadrature.hpp"

namespace bssrdf {

double single_scattering_total(double albedo, double g, double eta) {
  // Light leaving with cosine mu below mu_c is totally reflected; substitute mu = mu_c + (1-mu_c)s^2
  // so the square-root onset of transmission at mu_c is smooth for the quadrature.
  const double mu_c = eta > 1 ? std::sqrt(1 - 1 / (eta * eta)) : 0.0;
  const double span = 1 - mu_c;
  const auto integrand = [&](double s) {
    const double mu = mu_c + span * s * s;
    return 2 * std::numbers::pi * henyey_greenstein(-mu, g) * (1 - fresnel_reflectance(mu, eta)) * mu / (1 + mu) * 2 *
           span * s;
  };
  return albedo * integrate_adaptive(integrand, 0.0, 1.0, 1e-12).value;
}

}  // namespace bssrdf
