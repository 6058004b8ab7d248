// What a material's coefficients imply, per channel: albedos, the four distance conventions
// renderers use (mfp 1/sigma_t, transport mfp 1/sigma_t', dmfp 1/sigma_tr, Burley's d), the surface albedo and Burley's
// d fitted to a physical profile (the exact model's inside its domain), and whether diffusion applies at all. Computed
// from the coefficients on demand, never stored in material files, so they cannot disagree with them.
//
//   const auto q = bssrdf::derive_quantities(material.medium);      // exact (pbd outside), object size 10 mm
//   for (const auto& c : q.channels) if (!c.diffusion_valid) std::cout << c.reason;
//
//   mfp            1/sigma_t     (unreduced; Blender's Random Walk radius, Mitsuba's sigma_t)
//   transport_mfp  ell = 1/sigma_t'
//   diffuse_mfp    ell_d = 1/sigma_tr, sigma_tr = sqrt(3 sigma_a sigma_t') (classical)
//   burley_d       d of R(r) = A (e^{-r/d} + e^{-r/3d}) / (8 pi d r), A = the surface albedo, d by
//                  least squares against the physical model's R(r) (fit_burley), with its relative L2 error;
//                  the physical model is the exact one (the radiative-transfer solution, models/exact.hpp)
//                  for every channel inside its domain and `fallback_model` for the others
#pragma once

#include <string>
#include <vector>

#include "bssrdf/medium.hpp"

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
  bool diffusion_valid = true;
  std::string reason;  // why diffusion does not apply (empty when it does)
};

struct DerivationOptions {
  // The profile Burley's d is fitted to; "exact" takes `fallback_model` for channels outside its
  // domain (alpha' 0.001-0.9999, g 0-0.99, eta 1-1.6); with "exact", `fallback_model`'s validity
  // decides diffusion_valid (whether diffusion applies is a diffusion model's verdict).
  std::string physical_model = "exact";
  std::string fallback_model = "pbd";
  double object_size_mm = 10;  // diffusion needs the transport mfp below this
  std::size_t radii = 100;     // samples of the physical profile for the fit
};

struct DerivedQuantities {
  // The model every channel used ("exact", "pbd"), or "exact (pbd for R, G)" when some fell back.
  std::string physical_model;
  double object_size_mm = 0;
  std::vector<DerivedChannel> channels;
};

// Throws InvalidInput for an unvalidated medium, an unknown model or object_size_mm <= 0.
DerivedQuantities derive_quantities(const Medium& medium, const DerivationOptions& options = {});

// The radii (mm) the physical profile is sampled at for the Burley fit: geometric from
// 1e-3 min(ell, ell_d) to 16 ell_d (the kernel's e^{-16} tail), or 1000 ell without absorption.
std::vector<double> burley_fit_radii_mm(const Reduced<double>& m, std::size_t count);

}  // namespace bssrdf
