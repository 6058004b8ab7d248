// Profiles of every channel of a medium under one model, with the derived quantities and validity
// notes, in an output unit; and their JSON, CSV and text-table forms. This is what
// `bssrdf profile` prints, and what scripts read.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/profile.hpp"
#include "bssrdf/units.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {

struct ChannelProfile {
  std::string name;
  // Coefficients in 1/unit and lengths in unit (the report's unit).
  double sigma_a = 0, sigma_s = 0, g = 0, sigma_s_prime = 0, albedo_prime = 0;
  double transport_mfp = 0;  // ell = 1/sigma_t'
  double diffuse_mfp = 0;    // ell_d = 1/sigma_tr (classical); infinite when sigma_a = 0
  double total_reflectance = 0;
  double radius_99 = 0;    // radius holding 99 % of total_reflectance
  SampledProfile profile;  // radius in unit, R(r) in 1/unit^2
  ValidityReport validity;
  // Model-specific forms renderers use directly (empty when the model has none):
  // quantized diffusion's mixture R(r) = sum w_i e^{-r^2/(2 v_i)}/(2 pi v_i) (v_i in unit^2),
  std::vector<double> gaussian_variance, gaussian_weight;
  // normalized diffusion's shape parameter d (unit) and surface albedo A.
  double burley_d = 0, surface_albedo = 0;
  // Slabs and layer stacks only: T(r) at the same radii (1/unit^2), its total, and for a single
  // multipole slab the number of dipole pairs behind the totals (0: not applicable).
  std::optional<double> total_transmittance;
  std::vector<double> transmittance;
  int dipole_pairs = 0;
};

// A profile report whose channels are colours integrated from a spectral one (spectral/colour_profile.hpp).
struct ColourNote {
  std::string observer, illuminant, space;  // "CIE 1931 2-degree", "D65", "linear sRGB"
  std::vector<double> wavelength_nm;        // the spectral channels integrated
};

struct ProfileReport {
  std::string model, model_description;
  std::string model_choice;  // why this model, when it was chosen for an accuracy (--model auto)
  bool includes_single_scattering = false;
  LengthUnit unit = LengthUnit::millimetre;
  double eta = 1;
  std::optional<Material> material;  // when the medium came from the database
  std::vector<ChannelProfile> channels;
  std::optional<double> thickness;   // a single slab, in unit
  std::optional<ColourNote> colour;  // the channels are R, G, B integrated from wavelengths
  std::optional<LayerStack> layers;  // a layer stack (mm inside; reported in unit); channel
                                     // coefficients are then those of the top layer
};

// Radii for a profile when none are given: geometric from 1e-3 of the smallest transport mfp to
// the largest 99.9 %-energy radius over the channels (mm).
std::vector<double> default_radii_mm(const Medium& medium, const Model& model, std::size_t samples);

// radii_mm: one radius grid (mm) shared by all channels.
ProfileReport compute_profile_report(const Medium& medium, const Model& model, const std::vector<double>& radii_mm,
                                     LengthUnit unit);

// A layer stack under the multipole with the adding equations (models/layered.hpp).
ProfileReport compute_stack_report(const LayerStack& stack, const std::vector<double>& radii_mm, LengthUnit unit);
std::vector<double> default_stack_radii_mm(const LayerStack& stack, std::size_t samples);

std::string to_json(const ProfileReport& report);   // pretty-printed, trailing newline
std::string to_csv(const ProfileReport& report);    // radius + one column per channel
std::string to_table(const ProfileReport& report);  // for people

}  // namespace bssrdf
