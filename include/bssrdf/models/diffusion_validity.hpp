// The validity report shared by semi-infinite diffusion models. Each model passes the limits it was
// measured to have against adding-doubling (tests/test_adding_doubling.cpp prints the tables).
#pragma once

#include <string>

#include "bssrdf/reduced.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {

struct DiffusionLimits {
  double invalid_below_albedo_prime;  // total error beyond `invalid_error` below this alpha'
  std::string invalid_error;          // e.g. "40 %"
  double warn_below_albedo_prime;     // total error beyond `warn_error` below this alpha'
  std::string warn_error;
  double eta_min, eta_max;            // range of eta the model was checked over
};

DiffusionLimits dipole_limits();
DiffusionLimits better_dipole_limits();

ValidityReport diffusion_validity(const Reduced<double>& m, const DiffusionLimits& limits);

}  // namespace bssrdf
