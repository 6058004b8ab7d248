// The profile as a sum of 2D Gaussians, R(r) = sum_k w_k G2(v_k, r), G2(v, r) = e^{-r^2/(2v)} / (2 pi v),
// for texture-space diffusion (d'Eon & Luebke, GPU Gems 3 ch. 14) and other sum-of-Gaussians
// renderers. Two sources:
//  - quantized diffusion's own mixture (d'Eon & Irving 2011): exact for that model, a few hundred
//    Gaussians per channel with per-channel variances; sum w = its total reflectance by construction;
//  - fit_gaussians (fit/inverse_fits.hpp): N shared-variance Gaussians with per-channel weights
//    fitted by least squares to any model's profile; sum w is then compared with the model's total
//    reflectance (conservation_error).
//
// Weights are dimensionless (the reflectance each Gaussian carries, per entered flux); variances
// are lengths squared.
#pragma once

#include <string>
#include <vector>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"

namespace bssrdf {

struct GaussianMixtureTable {
  std::string method;
  bool shared_variance = false;
  std::vector<std::string> channel_names;
  std::vector<std::vector<double>> variance;  // [channel][k], mm^2 (all rows equal when shared)
  std::vector<std::vector<double>> weight;    // [channel][k]
  std::vector<double> total_reflectance;      // [channel]: the model's int 2 pi r R dr
  std::vector<double> conservation_error;     // [channel]: sum_k w / total - 1
  std::vector<double> relative_l2_error;      // [channel]: (int r (R - fit)^2 dr / int r R^2 dr)^(1/2); fits only
  double seconds = 0;

  std::size_t count() const;  // the most Gaussians of any channel
};

GaussianMixtureTable quantized_mixture_table(const Medium& medium, const quantized_diffusion::Model& model);
// The mixture of any model that has its own (model_registry.hpp: own_gaussians); InvalidInput if it has none.
GaussianMixtureTable own_mixture_table(const Medium& medium, const Model& model);
// count: 1 to 32; the profile is sampled on `samples` radii (default_radii_mm of profile_report.hpp).
GaussianMixtureTable fitted_mixture_table(const Medium& medium, const Model& model, int count,
                                          std::size_t samples = 128);

// width = count(), height = 1. Shared variances: channels "variance" (unit^2) then one weight
// channel per colour channel (the layout of GPU Gems 3's table). Per-channel variances: for each
// colour channel c, "variance.<c>" and the weights "<c>"; channels with fewer Gaussians are padded
// with weight 0 (their last variance repeated).
LookupTable to_lookup_table(const GaussianMixtureTable& table, const TableContext& context);
// A few lines for people: the method and each channel's variances and conservation error.
std::string summary(const GaussianMixtureTable& table, const TableContext& context);

}  // namespace bssrdf
