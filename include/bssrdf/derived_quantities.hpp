// What a material's coefficients imply, per channel: albedos, the four distance conventions
// renderers use (mfp 1/sigma_t, transport mfp 1/sigma_t', dmfp 1/sigma_tr, Burley's d), the surface albedo and Burley's
// d fitted to a physical profile (the registry's default model: exact inside its domain), and that profile's validity
// (the same verdict `bssrdf profile` prints). Computed from the coefficients on demand, never stored in material
// files, so they cannot disagree with them.
//
//   const auto q = bssrdf::derive_quantities(material.medium);      // the default model, object size 10 mm
//   for (const auto& c : q.channels) for (const auto& note : c.validity) std::cout << describe(note);
//
//   mfp            1/sigma_t     (unreduced; Blender's Random Walk radius, Mitsuba's sigma_t)
//   transport_mfp  ell = 1/sigma_t'
//   diffuse_mfp    ell_d = 1/sigma_tr, sigma_tr = sqrt(3 sigma_a sigma_t') (classical)
//   burley_d       d of R(r) = A (e^{-r/d} + e^{-r/3d}) / (8 pi d r), A = the surface albedo, d by
//                  least squares against the physical model's R(r) (fit_burley), with its relative L2 error;
//                  the physical model is the registry's default for the channel (default_model: the exact
//                  radiative-transfer solution inside its domain, models/exact.hpp) unless one is given
#pragma once

#include <string>
#include <vector>

#include "bssrdf/medium.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {

struct DerivedChannel {
  std::string name;
  double sigma_a = 0, sigma_s = 0, g = 0;  // 1/mm
  double sigma_t = 0, albedo = 0;          // sigma_a + sigma_s, sigma_s / sigma_t
  double sigma_s_prime = 0, sigma_t_prime = 0, albedo_prime = 0;
  double mfp = 0, transport_mfp = 0, diffuse_mfp = 0;  // mm; diffuse_mfp is infinite when sigma_a = 0
  // Total diffuse reflectance per entered flux (single scattering included): the exact model's
  // total inside its domain (models/exact.hpp: the radiative-transfer solution); outside it the
  // physical model's, or where that model creates energy (total above 1: pbd at alpha' near 1) the
  // exact total by adding-doubling, and `reason` says so: never above 1.
  double surface_albedo = 0;
  // Burley's d (mm) fitted to the physical profile's shape with A held at surface_albedo (energy
  // conserved: A <= 1), and the fit's relative L2 error sqrt(int r (fit - R)^2 dr / int r R^2 dr).
  // NaN when the channel does not scatter (sigma_s = 0).
  double burley_d = 0, burley_albedo = 0, burley_error = 0;
  std::string physical_model;  // the profile this channel's Burley d is fitted to
  std::string model_choice;    // why physical_model is not `exact` when it is the default (default_model); else empty
  // The physical model's own validity (Model::validity, what `bssrdf profile` reports for it), then
  // the object-size warning, the surface-albedo note and "no scattering" (a note: R = 0) where they apply.
  ValidityReport validity;
  bool valid() const { return worst(validity) != Severity::invalid; }
};

struct DerivationOptions {
  // The profile Burley's d is fitted to; empty: each channel's default (default_model).
  std::string physical_model;
  double object_size_mm = 10;  // a warning where the transport mfp exceeds it: light leaves before it becomes diffuse
  std::size_t radii = 100;     // samples of the physical profile for the fit
};

struct DerivedQuantities {
  // The model every channel used ("exact"), or "exact (pbd for R, G)" when they differ.
  std::string physical_model;
  double object_size_mm = 0;
  std::vector<DerivedChannel> channels;
  // A spectral material's colour stand-in (spectral/colour_medium.hpp): the colour integration and how well the R, G,
  // B coefficients match it, said in every export beside the validity; empty otherwise.
  std::string colour;
};

// Throws InvalidInput for an unvalidated medium, an unknown model or object_size_mm <= 0.
DerivedQuantities derive_quantities(const Medium& medium, const DerivationOptions& options = {});

// The radii (mm) the physical profile is sampled at for the Burley fit: geometric from
// 1e-3 min(ell, ell_d) to 16 ell_d (the kernel's e^{-16} tail), or 1000 ell without absorption.
std::vector<double> burley_fit_radii_mm(const Reduced<double>& m, std::size_t count);

}  // namespace bssrdf
