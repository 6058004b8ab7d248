// The interface every radial-profile model implements (models/*: the dipoles, multipole, photon beam
// diffusion, quantized and normalized diffusion, the exact tabulated transport solution). A model
// evaluates one channel at a time from its reduced coefficients. Models are made by name through the
// registry above this interface (model_registry.hpp: make_model), which nothing here includes.
//
//   auto model = bssrdf::make_model("better-dipole");     // model_registry.hpp
//   auto m = medium.reduced(0);
//   double R = model->reflectance(m, 0.5);          // per unit entered flux, 1/mm^2
//   double total = model->total_reflectance(m);     // int 2 pi r R(r) dr
//   for (auto& note : model->validity(m)) ...
//
// Each model's math lives in templated free functions (see models/*.hpp) so that Ceres can
// differentiate it; this class is the runtime face used by the command line and the tabulators.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "bssrdf/profile.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {

class Model {
 public:
  virtual ~Model() = default;

  virtual std::string name() const = 0;         // command-line name, e.g. "better-dipole"
  virtual std::string description() const = 0;  // one line with the citation
  // Whether R(r) contains single scattering; models that omit it must not be compared with totals
  // that include it without adding it (see single_scattering.hpp).
  virtual bool includes_single_scattering() const = 0;

  // R(r): exitance at distance r from a normally incident pencil beam, per unit entered flux.
  virtual double reflectance(const Reduced<double>& m, double r) const = 0;
  // int_0^inf 2 pi r R(r) dr, in closed form where the model has one.
  virtual double total_reflectance(const Reduced<double>& m) const = 0;
  // int_0^r 2 pi r' R(r') dr'. The default integrates reflectance() numerically.
  virtual double cumulative_reflectance(const Reduced<double>& m, double r) const;
  // Where the model's assumptions fail for these coefficients: the model's own checks, plus an
  // "energy" entry (invalid) whenever its total reflectance exceeds 1.
  ValidityReport validity(const Reduced<double>& m) const;

  // Albedo inversion: the reduced albedo alpha' whose total reflectance equals `total` at index
  // eta and anisotropy g (models that see only alpha' give the same answer for every g). Throws
  // InvalidInput when `total` is outside what the model can produce there.
  virtual double albedo_prime_from_total(double total, double eta, double g) const;

  // The radius holding `fraction` (0 < fraction < 1) of the total reflectance.
  double radius_for_fraction(const Reduced<double>& m, double fraction) const;

  // R(r) sampled at the given radii.
  SampledProfile sample(const Reduced<double>& m, const std::vector<double>& radii) const;

 protected:
  // The model-specific part of validity().
  virtual ValidityReport check_validity(const Reduced<double>& m) const = 0;
};

// The radius where a non-decreasing cumulative energy reaches `target`: doubling from `start`,
// then bisection in log r to relative precision `precision`; infinite if it is not reached before
// `start` * 2^60.
double radius_where(const std::function<double(double)>& cumulative, double target, double start,
                    double precision = 1e-12);

}  // namespace bssrdf
