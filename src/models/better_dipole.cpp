#include "bssrdf/models/better_dipole.hpp"

#include "bssrdf/models/diffusion_validity.hpp"

namespace bssrdf::better_dipole {
std::string Model::description() const {
  return "better dipole (d'Eon 2012): Grosjean D, exact Fresnel moments, fluence + flux exitance, "
         "multiple scattering only";
}

double Model::reflectance(const Reduced<double>& m, double r) const {
  return better_dipole::reflectance(m, cached_improved_boundary(m.eta), r);
}

double Model::total_reflectance(const Reduced<double>& m) const {
  return better_dipole::total_reflectance(m.albedo_prime, cached_improved_boundary(m.eta));
}

double Model::cumulative_reflectance(const Reduced<double>& m, double r) const {
  return better_dipole::cumulative_reflectance(m, cached_improved_boundary(m.eta), r);
}

ValidityReport Model::check_validity(const Reduced<double>& m) const {
  return diffusion_validity(m, measured_limits(name()));
}

}  // namespace bssrdf::better_dipole
