// Monte Carlo reference solver: the ground truth every diffusion model is measured against. It
// solves the radiative transfer equation in a stack of planar layers by tracing photons, with the
// true Henyey-Greenstein phase function (not the similarity-reduced one), unpolarised Fresnel
// reflection and refraction at every interface and total internal reflection.
//
//   MonteCarloOptions options;
//   options.photons = 1'000'000;
//   options.r_max = 5.0;                       // mm
//   auto result = run_monte_carlo(LayerStack::half_space(medium), options);
//   std::cout << result.report();              // what was done, totals with standard errors
//   double rd = result.channels[0].diffuse_reflectance.value;   // per unit INCIDENT flux
//
// Source: a pencil beam at normal incidence on the top surface at r = 0. The specular reflection
// at entry is not traced: it is reported separately (specular_reflectance) and the photon enters
// with weight 1 - R_sp (MCML's convention; with a clear top layer such as a glass slide, R_sp
// includes its multiple reflections, as MCML does).
//
// Estimators (all unbiased):
//  - Absorption: implicit capture ("survival weighting", MCML): at each interaction the weight is
//    multiplied by the albedo sigma_s/sigma_t (the removed weight is the absorbed energy); when it
//    falls below roulette_threshold, Russian roulette: the photon survives with probability
//    roulette_survival and its weight is divided by it. Defaults 0.1 / 0.5 (MCML: 1e-4 / 0.1):
//    measured 1.6-1.9x MCML's figure of merit for R_d, R(r) and absorption, no output worse
//    (tools/bench/bench_montecarlo_estimators). Or analog absorption: the photon is
//    absorbed with probability 1 - albedo and otherwise keeps its weight.
//  - Interfaces: the photon is reflected with probability F_r (unpolarised Fresnel) and transmitted
//    otherwise (MCML's default, all-or-none); every photon therefore leaves the stack at most once,
//    so the per-photon second moments, and the standard errors, are exact.
//  - Steps: free paths -ln(xi)/sigma_t carried across interfaces in optical depth.
// Standard errors are sample standard deviations of the per-photon contributions over sqrt(N)
// (for absorption by depth: of per-batch means, since one photon deposits in many bins).
//
// Determinism: the photons of each channel are split into batches of batch_size photons; batch b
// of channel c draws from its own xoshiro256+ generator seeded by splitmix64 of (seed, c, b); the
// tracer's eight photon lanes each get a stream seeded from it. Random numbers: 52-bit (0, 1]
// uniforms for free paths, 53-bit for roulette and Fresnel, and the HG cosine and the azimuth from
// the two 32-bit halves of one draw, each at its cell's midpoint (a midpoint rule on 2^32 cells:
// O(2^-64) error, no bias at any measurable level; the MCML generator's -0.17 % bias came from its
// lagged-subtractive generator, as measured against exact half-space totals). Threads take batches from an atomic
// counter and the batch tallies are summed in batch order, so the result depends only on (stack, options, seed,
// batch_size), never on the thread count: bitwise identical for 1 or 64 threads. Batches are grouped in chunks of
// 64 (folded in batch order, then the chunks in chunk order), the unit MPI ranks share: bitwise identical for
// any number of ranks too. Across machines: identical on every x86-64 processor with FMA (whichever of the
// fused AVX-512, AVX2 and SSE2 kernels runs); a processor without FMA rounds each a b + c twice, which moves
// photons by ~1e-11 of their paths: the same statistics, possibly other last bits (BSSRDF_MC_SIMD=nofma runs
// that kernel anywhere). A run split across machines of both kinds is therefore not guaranteed bitwise.
//
// Normalisations: every tally is stored per unit INCIDENT flux (specular included in the incident
// flux, as MCML reports). per_entered_flux() divides by (1 - R_sp), the BSSRDF convention.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

enum class BinSpacing { linear, log };
enum class AbsorptionEstimator { implicit_capture, analog };

std::string_view to_string(BinSpacing spacing);
std::string_view to_string(AbsorptionEstimator estimator);

class ProcessGroup;

struct MonteCarloOptions {
  std::uint64_t photons = 1'000'000;  // per channel
  std::uint64_t seed = 1;
  unsigned threads = 0;             // 0: all hardware threads
  std::uint64_t batch_size = 4096;  // part of the inputs: results depend on it (and not on threads)

  // Radial bins for R(r) and T(r), in mm. Linear: `bins` bins of width r_max / bins from 0.
  // Log: the first bin is [0, r_min), then bins - 1 geometric bins from r_min to r_max.
  // r_max <= 0: 10 transport mean free paths, the largest over the scattering layers and channels;
  // r_min <= 0: r_max / 1000.
  double r_max = 0;
  double r_min = 0;
  std::size_t bins = 100;
  BinSpacing spacing = BinSpacing::linear;

  // Absorbed fraction by depth: depth_bins bins of width z_max / depth_bins (mm). 0: off.
  // z_max <= 0: the stack's depth, or 10 transport mean free paths when semi-infinite.
  std::size_t depth_bins = 0;
  double z_max = 0;

  AbsorptionEstimator absorption = AbsorptionEstimator::implicit_capture;
  // Russian roulette for implicit capture: a photon whose weight drops below roulette_threshold
  // survives with probability roulette_survival and has its weight divided by it (unbiased).
  // Defaults chosen by efficiency (1/(variance x time)) of every output, tools/bench/
  // bench_montecarlo_estimators: they raise it for R_d, R(r), A and A(z) and keep it for T_t.
  double roulette_threshold = 0.1;  // MCML: 1e-4
  double roulette_survival = 0.5;   // MCML: 0.1

  // A photon still inside after this many interactions is stopped and its weight counted as lost
  // (reported; nonzero only for nearly non-absorbing media, where it is a bias to watch).
  std::uint64_t max_interactions = 100'000'000;

  // Keep every photon that leaves the top with its radius and number of scatterings
  // (ChannelResult::reflected_photons). With a non-absorbing medium this is "white" Monte Carlo:
  // a photon that scattered k times carries weight albedo^k in a medium of any albedo with the same
  // g (implicit capture multiplies by the albedo at each interaction), so one run gives the
  // profiles of every albedo (tools/exact_table). Memory: 16 bytes per reflected photon.
  bool record_reflected_photons = false;

  // Called from worker threads (never concurrently) with photons finished and total (all channels).
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;

  // Distributed run (process_group.hpp): every rank calls run_monte_carlo with the same options and
  // traces its share of the chunks of batches; rank 0 gets the result, bitwise identical to one
  // process's, and the other ranks a result with gathered = false. Null: this process alone.
  ProcessGroup* group = nullptr;

  void validate() const;  // throws InvalidInput
};

struct Estimate {
  double value = 0;
  double standard_error = 0;
};

// A photon that left the top surface: where, after how many scatterings, with what weight.
struct ReflectedPhoton {
  double radius = 0;  // mm
  std::uint32_t scatterings = 0;
  float weight = 0;  // per unit incident flux
};

// One channel's tallies. Lengths in mm; everything per unit incident flux unless stated.
struct ChannelResult {
  std::string name;
  double specular_reflectance = 0;         // R_sp at entry (not traced)
  Estimate diffuse_reflectance;            // all light re-emerging at the top, minus R_sp
  Estimate single_scattering_reflectance;  // part of it that scattered exactly once
  Estimate unscattered_reflectance;        // part that never scattered (internal interfaces only)
  Estimate total_transmittance;            // all light leaving at the bottom, ballistic included
  Estimate unscattered_transmittance;      // ballistic part of it
  Estimate absorbed;                       // absorbed in the stack
  double lost = 0;                         // weight stopped by max_interactions (should be 0)
  std::vector<double> reflectance;         // R(r), 1/mm^2, one per radial bin
  std::vector<double> reflectance_stderr;
  double reflectance_beyond = 0;      // R from r >= r_max (in diffuse_reflectance, not binned)
  std::vector<double> transmittance;  // T(r), 1/mm^2 (empty for semi-infinite stacks)
  std::vector<double> transmittance_stderr;
  double transmittance_beyond = 0;
  std::vector<double> absorbed_by_depth;  // absorbed fraction per unit depth, 1/mm
  std::vector<double> absorbed_by_depth_stderr;
  std::uint64_t interactions = 0;                  // scattering/absorption events traced
  std::vector<ReflectedPhoton> reflected_photons;  // with options.record_reflected_photons, batch order

  // 1 / (1 - R_sp): multiply per-incident values by this for per-entered ones.
  double entered_scale() const { return 1.0 / (1.0 - specular_reflectance); }
  // The same tallies per unit flux that entered the medium (specular_reflectance kept as is).
  ChannelResult per_entered_flux() const;
};

struct MonteCarloResult {
  LayerStack stack;
  MonteCarloOptions options;                             // as run (defaults resolved, no progress callback)
  std::vector<double> bin_inner, bin_outer, bin_radius;  // mm; radius: linear midpoint / geometric
  std::vector<double> depth_inner, depth_outer;          // mm
  std::vector<ChannelResult> channels;
  unsigned threads = 1;                   // per rank
  int ranks = 1;                          // processes that shared the run (MPI)
  bool gathered = true;                   // false on ranks other than 0 of a distributed run: channels are empty
  std::uint64_t communication_bytes = 0;  // distributed: bytes this rank sent or received
  double communication_seconds = 0;       // and the seconds it spent doing so (waits included)
  double seconds = 0;
  double photons_per_second = 0;  // photon histories per wall-clock second, all channels

  // Ceres-style full report for people: what was run, totals with standard errors in both
  // normalisations, warnings. Lengths in `unit`.
  std::string report(LengthUnit unit = LengthUnit::millimetre) const;
};

// Runs the simulation. Validates the stack and options (InvalidInput).
MonteCarloResult run_monte_carlo(const LayerStack& stack, const MonteCarloOptions& options);

// Machine-readable forms, lengths in `unit` (R(r) in 1/unit^2). JSON: one object per run with
// "channels": [{ "name", "normalization": "per_incident_flux", "specular_reflectance",
// "diffuse_reflectance": {"value","stderr"}, "total_transmittance", "single_scattering_reflectance",
// ..., "radius", "reflectance", "reflectance_stderr", ..., "per_entered_flux": { the same with
// "normalization": "per_entered_flux" } }] and "photons", "seed", "threads", "seconds",
// "photons_per_second". CSV: one row per radial bin, columns per channel and normalisation.
std::string to_json(const MonteCarloResult& result, LengthUnit unit);
std::string to_csv(const MonteCarloResult& result, LengthUnit unit);
std::string to_table(const MonteCarloResult& result, LengthUnit unit);  // = report(unit)

}  // namespace bssrdf
