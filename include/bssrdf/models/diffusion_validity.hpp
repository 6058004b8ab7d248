// The validity report shared by semi-infinite diffusion models. Each model states the worst total-
// reflectance error it was measured to have against adding-doubling (tests/data/
// ad_semi_infinite.tsv: eta 1 and 1.4, g 0 and 0.9), by band of reduced albedo; the test
// tests/test_adding_doubling.cpp prints the full table and checks that every band holds.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "bssrdf/reduced.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {

struct AccuracyBand {
  double min_albedo_prime;  // the band is alpha' >= this (down to the next band's bound)
  double worst_error;       // worst |relative error| of the total against adding-doubling
};

struct DiffusionLimits {
  // Highest band first; below the last band's bound the error is unknown (reported invalid).
  // Measured at g = 0 (used for g < 0.5, negative g included) and at g = 0.9 (used for g >= 0.5).
  std::vector<AccuracyBand> isotropic_bands, forward_bands;
  double warn_above_error = 0.03;           // a warning where the band's worst error exceeds this
  double invalid_above_error = 0.3;         // invalid where it exceeds this
  double invalid_below_albedo_prime = 0.1;  // diffusion needs scattering to dominate absorption
  double eta_min = 1.0, eta_max = 1.4;      // range of eta the bands were measured over
  std::string context;                      // appended to the error figure, e.g. what it omits
};

// The measured accuracy of a model by its command-line name ("dipole", "better-dipole+ss", ...):
// the data in src/models/measured_bands.cpp, which the model registry quotes in its rows.
// Throws std::out_of_range for a model that has not been measured.
const DiffusionLimits& measured_limits(std::string_view model_name);

// The worst measured total error for this alpha' and g (the band containing it), or infinity
// below the last band.
double documented_total_error(const DiffusionLimits& limits, double albedo_prime, double g);

ValidityReport diffusion_validity(const Reduced<double>& m, const DiffusionLimits& limits);

// What a slab model (multipole) found for one channel; slab_validity() turns it into the report.
struct SlabState {
  double thickness_over_ell = 0;                      // d / ell
  double total_transmittance = 0;                     // of the pairs used
  double min_reflectance = 0, min_transmittance = 0;  // smallest R(r), T(r) over a radius grid
  double truncation_error = 0;                        // |R_rest| + |T_rest| of the pairs not used
  double tolerance = 0;                               // what the pair count was chosen for
  bool converged = true;
};

// The thin-slab breakdown of the multipole (source outside the slab, thin slab, negative R or T,
// unconverged pair sum) with the multipole's measured total errors against adding-doubling
// slabs (tests/data/ad_slab.tsv, printed by tests/test_multipole.cpp), then the semi-infinite
// dipole's albedo bands, which the multipole reduces to as d grows.
ValidityReport slab_validity(const Reduced<double>& m, const SlabState& state);

}  // namespace bssrdf
