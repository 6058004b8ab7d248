#include "bssrdf/models/dipole.hpp"

#include "bssrdf/models/diffusion_validity.hpp"

namespace bssrdf::classical_dipole {

std::string Model::description() const {
  return "classical dipole (Jensen et al. 2001): classical D and A (Egan-Hilgeman F_dr); its total matches the full "
         "total, single scattering included (measured against adding-doubling)";
}

double Model::reflectance(const Reduced<double>& m, double r) const { return classical_dipole::reflectance(m, r); }

double Model::total_reflectance(const Reduced<double>& m) const {
  return classical_dipole::total_reflectance(m.albedo_prime, m.eta);
}

double Model::cumulative_reflectance(const Reduced<double>& m, double r) const {
  return classical_dipole::cumulative_reflectance(m, r);
}

ValidityReport Model::check_validity(const Reduced<double>& m) const {
  return diffusion_validity(m, measured_limits(name()));
}

}  // namespace bssrdf::classical_dipole
