// Fits from totals and from profiles to the few parameters renderers take:
//  - fit_albedo: surface colour (total diffuse reflectance) + one distance per channel -> sigma_a,
//    sigma_s', for any model, solved exactly by root finding on the model's total (no table, no
//    clamping: unreachable inputs are errors);
//  - fit_slab: an integrating-sphere measurement (diffuse reflectance and total transmittance of a
//    slab of known thickness, optionally its unscattered transmittance, between optional glass
//    slides) -> sigma_a, sigma_s' (and g with the unscattered transmittance) through
//    adding-doubling (exact) or the multipole, with uncertainties propagated from the
//    measurement's, which measurement constrains which parameter, chi^2, and a reason when no
//    solution exists;
//  - fit_gaussians: N shared-variance Gaussians with per-channel non-negative weights fitted to a
//    profile by minimising int r (R - sum w G)^2 dr (GPU Gems 3 ch. 14);
//  - fit_burley: Burley's d per channel fitted to a profile (least squares; A fixed to a given total).
#pragma once

#include <string>
#include <vector>

#include "bssrdf/fit/fit_report.hpp"
#include "bssrdf/io/profile_csv.hpp"
#include "bssrdf/profile.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

enum class DistanceConvention { mfp, transport_mfp, dmfp };
DistanceConvention parse_distance_convention(const std::string& text);  // "mfp", "transport-mfp", "dmfp"
std::string_view to_string(DistanceConvention convention);

struct AlbedoInversion {
  double sigma_a, sigma_s_prime, albedo_prime;  // 1/length of the distance given
};

// One channel: the exact inversion. `total`: total diffuse reflectance per entered flux.
AlbedoInversion invert_albedo(const std::string& model, double total, double distance, DistanceConvention convention,
                              double eta, double g = 0);

struct ChannelInput {
  std::string name;
  double value;     // albedo (fit_albedo)
  double distance;  // in `unit`
  double g = 0;
};

// `model` empty: the registry's default for these g and eta (default_model_over_albedos: exact inside its domain).
FitReport fit_albedo(const std::vector<ChannelInput>& channels, DistanceConvention convention, LengthUnit unit,
                     const std::string& model, double eta);

struct SlabMeasurement {
  std::string name;
  double reflectance, transmittance;  // per incident flux: diffuse R (specular excluded), total T (ballistic included)
  double reflectance_stderr, transmittance_stderr;
  double g = 0;             // held, or the start value when g is fitted
  double unscattered = -1;  // unscattered transmittance per incident flux; < 0: not measured
  double unscattered_stderr = 0;
};

struct SlabFitOptions {
  std::string model = "adding-doubling";  // or "multipole" (no slides, no unscattered transmittance)
  double slide_n = 0;                     // glass slides on both faces: index (0: none) and thickness in the fit's unit
  double slide_thickness = 0;
};

// thickness in `unit`; eta = n_slab / n_outside on both faces. With an unscattered transmittance
// g is fitted too (adding-doubling only).
FitReport fit_slab(const std::vector<SlabMeasurement>& channels, double thickness, LengthUnit unit, double eta,
                   const SlabFitOptions& options = {});

// The measurable totals of a slab under the multipole plus the exact ballistic beam (both faces,
// multiple reflections), per incident flux: what fit_slab matches.
std::pair<double, double> slab_measurables(double sigma_a, double sigma_s_prime, double g, double eta,
                                           double thickness_mm);

struct NamedProfile {
  std::string name;
  SampledProfile profile;  // radius in unit, R in 1/unit^2
};

// A measured profile's channels in the file's own unit (radius in it, R per its square): what
// fit_gaussians and fit_burley take with `measured.unit`.
std::vector<NamedProfile> named_profiles_in_own_unit(const MeasuredProfile& measured);

// `totals`: when given (one per channel), the weights of each channel are also held to sum to it
// (a stiff penalty residual): a mixture that conserves the profile's energy even where the
// sampled radii miss part of it (profiles singular at r = 0).
FitReport fit_gaussians(const std::vector<NamedProfile>& channels, int count, LengthUnit unit,
                        const std::string& source, const std::vector<double>& totals = {});
// `totals`: when given (one per channel, in (0, 1]), Burley's A is held at it (the energy of the
// profile, e.g. the physical model's total reflectance) and only d is fitted; without them A is
// fitted too and absorbs the shape's misfit (for measured profiles of unknown scale).
FitReport fit_burley(const std::vector<NamedProfile>& channels, LengthUnit unit, const std::string& source,
                     const std::vector<double>& totals = {});

}  // namespace bssrdf
