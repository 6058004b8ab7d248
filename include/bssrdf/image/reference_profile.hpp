// Where the truth comes from when a representation is judged: one interface, so that the exact
// model, when it exists, replaces the Monte Carlo reference by one change (a ModelReference of it).
//
//   MonteCarloReference mc({.photons = 200'000});
//   ReferenceProfiles ref = mc.profiles(skin);       // one AnnularProfile per channel, with stderr
//   ModelReference exact(make_model("pbd"));         // a formula as the reference: no noise, fast
//
// Annuli: the first [0, r_min), then geometric from r_min = 1e-3 ell (ell: the transport mean free
// path, smallest over the channels) to r_max, the largest profile_extent() of the channels, 48 per
// decade, then [r_max, 2 r_max] for the light beyond. All channels share them. Spreading each annulus's light
// evenly over it is the image error's one approximation: for a Gaussian profile it is measured at
// 0.6 code values with 24 annuli per decade, 0.15 with 48 (second order; tests/test_image_error.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bssrdf/image/annular_profile.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

// Where one channel of the reference comes from and how far it is trusted (reference_uncertainty.hpp
// turns the bands into image-space error). A Monte Carlo channel has no band: its statistical error
// is in the profile's energy_stderr.
struct ReferenceSource {
  std::string name;         // "montecarlo", "exact", or the model whose shape is used
  double total_band = 0;    // measured relative accuracy of the total reflectance (0: none stated)
  double profile_band = 0;  // of the shape: relative L2 of r R(r), the larger inside / beyond one transport mfp
  // R(r), 1/mm^2 per entered flux, where the channel is a formula (empty for Monte Carlo); valid while
  // the ReferenceProfile that produced it lives.
  std::function<double(double)> reflectance;
};

struct ReferenceProfiles {
  std::string description;               // what was run, for reports
  std::vector<AnnularProfile> channels;  // per entered flux
  std::vector<ReferenceSource> sources;  // one per channel
  double seconds = 0;                    // wall-clock cost of producing them
};

class ReferenceProfile {
 public:
  virtual ~ReferenceProfile() = default;
  virtual ReferenceProfiles profiles(const Medium& medium) const = 0;
};

// The radius beyond which a channel's light no longer shows: the larger of 30 transport mean free
// paths and 15 diffusion lengths 1/sigma_tr (e^-15 of the diffusion tail; 30 ell alone left a
// visible part of Marble's red light out). Conservative media (sigma_tr = 0): 30 ell.
double profile_extent(const Reduced<double>& m);

// The annuli described above, for a medium.
std::vector<double> reference_annuli(const Medium& medium, std::size_t bins_per_decade = 48);

struct MonteCarloReferenceOptions {
  std::uint64_t photons = 200'000;  // per channel
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: all; never changes the result
};

// The radiative-transfer Monte Carlo solution of the half-space (montecarlo.hpp) for every channel of
// `medium`, binned on `edges` (reference_annuli() of a medium with these channels or more). The
// annuli returned are the tracer's own bins (equal to `edges` up to rounding).
std::vector<AnnularProfile> monte_carlo_annuli(const Medium& medium, const std::vector<double>& edges,
                                               const MonteCarloReferenceOptions& options);

// The radiative-transfer Monte Carlo solution of the half-space (montecarlo.hpp), binned on the annuli.
class MonteCarloReference : public ReferenceProfile {
 public:
  explicit MonteCarloReference(MonteCarloReferenceOptions options) : options_(options) {}
  ReferenceProfiles profiles(const Medium& medium) const override;

 private:
  MonteCarloReferenceOptions options_;
};

// A model as the reference: `exact` (carrying its measured accuracy band from the model registry,
// ModelEntry::reference_accuracy) or, for tests and benches, any model taken as the truth (no band). `registry_band`
// false: no band even for a registry name (a spectral medium's colour model, spectral/colour_medium.hpp, is named after
// the model of its wavelengths but is evaluated at stand-in coefficients).
class ModelReference : public ReferenceProfile {
 public:
  explicit ModelReference(std::shared_ptr<const Model> model, bool registry_band = true)
      : model_(std::move(model)), registry_band_(registry_band) {}
  ReferenceProfiles profiles(const Medium& medium) const override;

 private:
  std::shared_ptr<const Model> model_;
  bool registry_band_ = true;
};

}  // namespace bssrdf
