// The radial table from the Monte Carlo reference instead of a model, for what diffusion cannot
// describe (albedo below 0.5, thin layers such as a 0.1 mm epidermis, the very forward-scattering
// liquids): R(r) per channel as bin averages on logarithmic bins with their standard errors,
// 2 pi r R(r), the CDF at each bin's outer edge and its inverse. Statistical, not adaptive: each
// value's error is its recorded standard error, not an interpolation tolerance.
//
// Bins: the first [0, r_min), then geometric to r_max, with r_min = 1e-3 and r_max = 30 transport
// mean free paths (the smallest and the largest over layers and channels); light leaving beyond
// r_max is counted in the total and its fraction recorded.
//
//   auto t = build_reference_radial_table(LayerStack::half_space(coke), {});
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf {

struct ReferenceRadialOptions {
  std::uint64_t photons = 1'000'000;  // per channel
  std::uint64_t seed = 1;
  std::size_t bins = 64;
  unsigned threads = 0;  // 0: all; results never depend on it
  // Photons finished and total (all channels), from worker threads, never concurrently. Walks are
  // long where absorption is tiny: Spectralon (alpha' ~ 1 - 1e-5) takes ~5 ms per photon.
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  // A stack whose channels are named by wavelength ("550nm"): the table's channels are R, G, B, per bin and total
  // sum_i w_ci X_i of the wavelengths' estimates with standard errors sqrt(sum_i w_ci^2 se_i^2)
  // (spectral/colour_reference.hpp). nullopt: the stack's own channels.
  std::optional<spectral::ColourSettings> colour{};
};

struct ReferenceRadialTable {
  ReferenceRadialOptions options;
  std::vector<std::string> channel_names;
  std::vector<double> r_inner, r_outer, radius;  // mm; radius: the bin's centre (geometric; r_min/2 for the first)
  std::vector<std::vector<double>> reflectance;  // [channel][bin]: bin average of R, 1/mm^2, per entered flux
  std::vector<std::vector<double>> reflectance_stderr;
  std::vector<std::vector<double>> ring;         // 2 pi radius R
  std::vector<std::vector<double>> cdf;          // at r_outer, over the table (last = 1)
  std::vector<double> u;                         // j / (bins - 1)
  std::vector<std::vector<double>> inverse_cdf;  // radius where the CDF reaches u_j, mm
  std::vector<double> total_reflectance;         // diffuse reflectance, all radii
  std::vector<double> total_stderr;
  std::vector<double> table_reflectance;  // within r_outer.back()

  std::size_t size() const { return radius.size(); }
};

ReferenceRadialTable build_reference_radial_table(const LayerStack& stack, const ReferenceRadialOptions& options);
// The bssrdf:colour of a table built with options.colour: the colour, the integration, and each channel that has a
// negative bin (a colour outside the space far out; its CDF is then not a sampling distribution there).
TableColour reference_table_colour(const ReferenceRadialTable& table, const std::vector<double>& wavelength_nm);

// Channels: R(r) under the channel names, "radius", "r_inner", "r_outer" (unit), "stderr.<c>",
// "ring.<c>", "cdf.<c>", "u", "inverse_cdf.<c>"; attributes record photons, seed, bins and totals.
LookupTable to_lookup_table(const ReferenceRadialTable& table, const TableContext& context);
// A few lines for people: bins, photons and seed, each channel's total with its standard error.
std::string summary(const ReferenceRadialTable& table, const TableContext& context);

}  // namespace bssrdf
