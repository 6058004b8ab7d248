// The dimensionless albedo x optical-radius table offline renderers build for photon beam
// diffusion (pbrt-v3/v4's BSSRDFTable): for one (g, eta), in optical units sigma_t = 1, rows of
// single-scattering albedo rho, columns of radius r (in mean free paths 1/sigma_t), cells
// 2 pi r R(r) (multiple + single scattering), plus each row's effective albedo
// rho_eff = int 2 pi r R dr and CDF. Renderers scale radii by 1/sigma_t and invert rho_eff to find
// rho from a surface colour (albedo_from_effective_albedo).
//
// Energy: photon beam diffusion's own total is 3-14 % off the radiative-transfer solution (above it
// at g = 0, reaching 1.023 at rho = 1: more light out than in). By default each row is scaled so
// that its integral, the effective albedo, is the radiative-transfer total (transport_total.hpp:
// the exact model's inside its domain, adding-doubling outside): the inversion then finds the rho
// that really gives a surface colour and the profile carries that energy. Only the multiple-
// scattering part is scaled (pbd's single scattering is the exact integral already).
// RowEnergy::model keeps pbrt's construction (the row's own integral).
//
// RowShape::exact fills every row inside the exact model's domain (models/exact.hpp: alpha' 0.001
// to 0.9999 at g 0-0.99, eta 1-1.6) with the exact model's 2 pi r R instead of photon beam
// diffusion's (the radiative-transfer solution; rows outside, rho = 1 and rho near 0 at large g,
// stay pbd scaled to the transport total). Measured against Monte Carlo on pbrt's layout:
// tools/validation/albedo_radius_vs_montecarlo.txt.
//
//   auto t = build_albedo_radius_table(AlbedoRadiusLayout::pbrt(), 0.0, 1.3, {});
//   double rho = t.albedo_from_effective_albedo(0.5);
//
// Speed (what makes it 10x faster than pbrt's construction, see tools/bench/bench_lut.cpp):
// single scattering in optical units is rho times a function of r alone (sigma_t = 1), so it is
// integrated once per column instead of once per cell; the multiple-scattering beam integral uses
// the Gauss-Legendre order that meets the tolerance (photon_beam_diffusion.hpp) instead of 100
// midpoint samples; rows run in parallel (deterministically).
#pragma once

#include <cstdint>
#include <functional>

#include <cstddef>
#include <vector>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/table_context.hpp"

namespace bssrdf {

struct AlbedoRadiusLayout {
  std::vector<double> albedo;  // increasing, in [0, 1]
  std::vector<double> radius;  // increasing, >= 0, mean free paths
  // pbrt's: 100 albedos rho_i = (1 - e^{-8 i/99}) / (1 - e^{-8}); 64 radii r_0 = 0, r_1 = 0.0025,
  // r_j = 1.2 r_{j-1}.
  static AlbedoRadiusLayout pbrt();
  // The same families with n albedos and n radii, the radius ratio chosen to reach r_max.
  static AlbedoRadiusLayout family(std::size_t albedos, std::size_t radii, double r_max = 203.0);
};

enum class RowEnergy { transport, model };
enum class RowShape { pbd, exact };

struct AlbedoRadiusOptions {
  double tolerance = 1e-2;  // quadrature tolerance of the beam integral (relative): 8 points
  RowEnergy energy = RowEnergy::transport;
  RowShape shape = RowShape::pbd;
  unsigned threads = 0;  // 0: all hardware threads; results never depend on it
  // adaptive_albedo_radius_layout: called after each refinement step with (steps done, most steps
  // possible); each axis grows by 25 % a step from 12 to at most 2048 points, so at most 2 x 24 steps.
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
};

struct AlbedoRadiusTable {
  double g = 0, eta = 1;
  AlbedoRadiusLayout layout;
  int quadrature_order = 0;
  double tolerance = 0;         // the quadrature tolerance it was built for
  double seconds = 0;           // time to build
  std::vector<double> profile;  // [i * radii + j]: 2 pi r_j R(r_j) at albedo_i, 1/mfp
  // Per row: the Catmull-Rom integral of the row (as pbrt; consistent with the CDF). With
  // RowEnergy::transport the radiative-transfer total the row was scaled to; with RowEnergy::model
  // the model's own, within 2 % of its total up to rho = 0.999 (above, pbrt's layout, 203 mfp,
  // truncates the profile: -9 %).
  std::vector<double> effective_albedo;
  RowEnergy energy = RowEnergy::model;
  // RowEnergy::transport: the factors applied to the rows' multiple scattering (what the
  // radiative-transfer total leaves after single scattering, over the model's), and the rows left
  // at the model's integral because adding-doubling did not converge there (transport_total.hpp:
  // g near 1 with rho near 0).
  double smallest_scale = 1, largest_scale = 1;
  std::size_t rows_at_model_energy = 0;
  RowShape shape = RowShape::pbd;
  std::size_t exact_rows = 0;  // RowShape::exact: the rows filled from the exact model
  std::vector<double> cdf;     // [i * radii + j]: row CDF, 1 at the last radius

  std::size_t rows() const { return layout.albedo.size(); }
  std::size_t columns() const { return layout.radius.size(); }
  // Catmull-Rom in albedo and radius, as pbrt evaluates the table.
  double interpolate(double albedo, double r) const;
  // The albedo whose (interpolated) effective albedo equals rho_eff; clamped to the table.
  double albedo_from_effective_albedo(double rho_eff) const;
};

AlbedoRadiusTable build_albedo_radius_table(const AlbedoRadiusLayout& layout, double g, double eta,
                                            const AlbedoRadiusOptions& options);

inline constexpr double kAdaptiveTableTolerance = 1e-3;  // the default tolerance of the adaptive layout

// The smallest family layout (pbrt's spacings, sizes grown by 25 % steps, each axis on its own)
// whose Catmull-Rom interpolation stays within `tolerance` of the table's own model, relative to
// each row's peak of 2 pi r R: each axis is sized so that its midpoint error is below a third of
// the tolerance (tests check points off the grid in both axes). Model no more than the case needs.
struct AdaptiveAlbedoRadiusLayout {
  AlbedoRadiusLayout layout;
  double albedo_error = 0, radius_error = 0;  // worst midpoint errors found (<= tolerance / 3)
};
AdaptiveAlbedoRadiusLayout adaptive_albedo_radius_layout(double g, double eta, double tolerance,
                                                         const AlbedoRadiusOptions& options);

// Channels "profile" (2 pi r R), "cdf", "radius", "albedo", "effective_albedo" (per-row values repeated
// along the row); width = radii, height = albedos.
LookupTable to_lookup_table(const AlbedoRadiusTable& table, const TableContext& context,
                            const std::string& layout_name);
// A few lines for people: the grid, the quadrature, the time and the effective-albedo range.
std::string summary(const AlbedoRadiusTable& table, const std::string& layout_name);
// One line on an adaptive layout: the tolerance and the worst midpoint errors found.
std::string summary(const AdaptiveAlbedoRadiusLayout& layout, double table_tolerance);

}  // namespace bssrdf
