// Generates the exact model's table (data/exact/exact_profile.bin): the radiative-transfer solution
// R(r) of a semi-infinite Henyey-Greenstein medium, normal pencil beam, smooth boundary, per unit
// entered flux, over (alpha', g, eta) and radii in transport mean free paths.
//
//   generate_exact_table run   --state DIR [--photons N] [--chunk N] [--hours H]   (resumable)
//                              [--runs 0.01,1] [--g-min G] [--g-max G] [--eta-min E] [--eta-max E]
//                              (top up only those runs)
//   generate_exact_table build --state DIR --out data/exact/exact_profile.bin
//                              [--base TABLE]   (the (g, eta) nodes TABLE holds are copied from it,
//                              the others built from DIR: how a table grows new eta or g nodes; a
//                              copied node whose non-absorbing run DIR holds has the albedo nodes that
//                              run serves rebuilt from it)
//
// Each part is exact or validated:
//  - multiple scattering (two or more scatterings): the project's Monte Carlo (run_monte_carlo,
//    validated to 0.1-0.3 % against MCML, adding-doubling and independent Monte Carlo), run once
//    per (g, eta) in a NON-absorbing medium of sigma_t = 1 that records every reflected photon's
//    radius and number of scatterings k ("white" Monte Carlo). A medium of albedo alpha and the
//    same g has the same photon paths with weight alpha^k (implicit capture multiplies the weight by
//    the albedo at each interaction), so one run gives every albedo node: radius r (in mfp) maps to
//    r (1 - alpha g) transport mfp. Low albedos come from absorbing runs at a few base albedos
//    instead (weight (alpha / alpha_base)^k), which sample the rare photons that turn round in a few
//    scatterings at far less cost (Grid::base_albedo_prime). Photons are stopped after K = 6 / (1 - alpha_max)
//    scatterings, where the largest albedo's weight is below e^-6 = 0.25 % and the photons still inside (P(k > K) ~
//    K^-1/2, under 1 %) carry a fraction of the total of order 1e-5 (the lost part is reported);
//  - where a run leaves the near field noisy (its first bin measured within 2 % 8 or more radii out:
//    strongly forward, nearly non-absorbing nodes), one Poisson fit of a cubic in ln r over those bins
//    (near_field_fit.hpp; version 10), its chi2 and bias check in the provenance;
//  - single scattering: the exact integral (single_scattering.hpp), evaluated at each node radius;
//  - the total: adding-doubling of the semi-infinite medium where it is the more precise; the Monte
//    Carlo multiple-scattering part is scaled to (adding-doubling total - exact single-scattering
//    total), and the scale's deviation from 1, in standard errors, is recorded for every node as a
//    check of both (at low albedo, where multiple scattering is ~0.1 % of the total, the Monte Carlo
//    is the more precise and its own total stands).
// Resumable: every (g, eta) node keeps its sums in DIR/node_G_E.bin, rewritten atomically after
// each chunk of photons; `run` continues until every node has --photons photons (or --hours pass),
// in passes of one chunk per node, so an interrupted run still leaves a complete, evenly sampled
// grid (--runs, --g-min and --g-max top up only some runs: RunFocus). Chunk c of node (g, eta) uses seed splitmix(seed,
// g, eta, c): results do not depend on how often the run was interrupted nor on the thread count.
// Under `mpirun -np N` (or srun) the nodes of each pass are dealt to the ranks (docs/mpi.md): the same
// state files, bitwise, for any N; a rank that dies stops the run, and `run` again resumes it.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/models/exact_table.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/parallel.hpp"
#include "bssrdf/reduced.hpp"
#include "bssrdf/single_scattering.hpp"
#include "launched_process_group.hpp"
#include "near_field_continuation.hpp"
#include "near_field_fit.hpp"

namespace {

using namespace bssrdf;

constexpr int kGeneratorVersion = 10;
constexpr int kSmoothingHalf = 3;  // radial smoothing window (smooth_radially): 7 bins, 0.58 decades
constexpr int kSmoothingWide = 5;  // where a bin's error exceeds 3 %: 11 bins
// The near-field fit (near_field_fit.hpp): where the first bin measured within 2 % is this many
// bins out or more (2/3 of a decade), the bins inside are fitted up to it, but over 2.5 decades at
// most, and the last 2 x kNearFitBlend bins of the range blend into the smoothed ones. A cubic in
// ln r: a quadratic over 2.5 decades was biased (the pooled tally of the first half decade 1.0
// standard errors below it, averaged over the g 0.995 and 0.999 nodes at alpha' 0.99-1; a cubic
// 0.15, as is a quadratic over 1.5 decades, with a larger error at the first radii). The fit's
// chi2 and this bias check are in the provenance.
constexpr std::size_t kNearFitFirst = 8, kNearFitLast = 30, kNearFitBlend = 6;

// ---- the grid ---------------------------------------------------------------------------------
// alpha': uniform in logit(alpha') from 0.001 to 0.9999 (41 nodes, step 0.40): the profile's
// shape changes with ln(1 - alpha') near 1 (sigma_tr ~ sqrt(1 - alpha')) and with ln alpha' near 0.
// Version 7: six more nodes below 0.001 on the same lattice, down to 8.9e-5. Below the first node
// the model continues in the single albedo alpha from the first two nodes (models/exact.cpp); at
// g 0.999 alpha' 0.001 is alpha 0.50, too far from 0 for that continuation (2.5 % in total, 9 % in
// the far field at alpha' 4.6e-4 against fresh Monte Carlo), while 8.9e-5 is alpha 0.08, where
// g 0.99's first node (alpha 0.09) is validated. The base-0.01 runs serve them.
// g: denser towards 1, where the near field changes fastest (version 6: 0.995 and 0.999, whose runs
// are in data/exact/state/, not yet in the shipped table: data/exact/README.md); eta: every 0.15 to
// 1.6, with one more node at 1.05 where the boundary's effect on the near field changes fastest,
// then every 0.2 to 2 (generator version 4: glass, gems; the profile's shape changes slowly there;
// the Monte Carlo cost is per (g, eta) node, so eta nodes are few).
// Radii: 12 per decade from 1e-3 transport mfp to 2154 (beyond the radius that holds 99.9 % of the
// energy at alpha' = 0.9999, eta = 1.6: checked by `build`).
struct Grid {
  std::vector<double> albedo_prime, g, eta;
  double ln_r0 = std::log(1e-3), d_ln_r = std::numbers::ln10 / 12;
  std::size_t radii = 77;

  static constexpr int kLowNodes = 6;  // below 0.001 (version 7)
  static constexpr int kVersion6Albedos = 41;
  Grid() {
    const double lo = std::log(0.001 / 0.999), hi = std::log(0.9999 / 0.0001);
    const int n = kVersion6Albedos;
    for (int i = -kLowNodes; i < n; ++i) {
      const double u = lo + (hi - lo) * i / (n - 1);
      albedo_prime.push_back(i == 0 ? 0.001 : i == n - 1 ? 0.9999 : 1 / (1 + std::exp(-u)));
    }
    g = {0.0, 0.2, 0.4, 0.55, 0.7, 0.8, 0.87, 0.92, 0.95, 0.97, 0.98, 0.99, 0.995, 0.999};
    eta = {1.0, 1.05, 1.15, 1.3, 1.45, 1.6, 1.8, 2.0};
    // The totals' eta axis (adding-doubling only, cheap): the total bends sharply within a few
    // hundredths above 1, where total internal reflection sets in.
    total_eta = {1.0,  1.0025, 1.005, 1.0075, 1.01, 1.015, 1.02, 1.025, 1.03, 1.04, 1.05, 1.06,
                 1.07, 1.08,   1.1,   1.12,   1.15, 1.2,   1.25, 1.3,   1.35, 1.4,  1.45, 1.5,
                 1.55, 1.6,    1.65,  1.7,    1.75, 1.8,   1.85, 1.9,   1.95, 2.0};
  }
  std::vector<double> total_eta;
  // Monte Carlo runs per (g, eta): a non-absorbing ("white") one, index kWhite, and absorbing ones
  // at these base alpha'. Node alpha' is taken from the run with the smallest base >= alpha' and
  // reweighted by (alpha / alpha_base)^k <= 1: a low albedo's multiple scattering comes from the
  // few photons that turn round in a few scatterings (rare when g is near 1), which an absorbing
  // run samples at a fraction of the white run's cost per photon, so it gets more photons.
  std::vector<double> base_albedo_prime = {0.01, 0.1, 0.5, 0.9, 0.99};
  std::vector<std::uint64_t> base_photon_factor = {512, 512, 128, 32, 8};
  std::size_t runs() const { return base_albedo_prime.size() + 1; }
  std::size_t white() const { return base_albedo_prime.size(); }
  double run_albedo_prime(std::size_t b) const { return b == white() ? 1.0 : base_albedo_prime[b]; }
  std::uint64_t run_factor(std::size_t b) const { return b == white() ? 1 : base_photon_factor[b]; }
  std::size_t run_for(double albedo_prime) const {
    for (std::size_t b = 0; b < base_albedo_prime.size(); ++b)
      if (albedo_prime <= base_albedo_prime[b]) return b;
    return white();
  }
  bool serves_low_nodes(std::size_t run) const { return run == run_for(albedo_prime.front()); }
  // Tally bins per albedo: [0] inside the first edge, [1..radii] one per node radius (edges at the
  // geometric midpoints), [radii + 1] beyond the last edge.
  std::size_t bins() const { return radii + 2; }
  double ln_first_edge() const { return ln_r0 - 0.5 * d_ln_r; }
};

double single_albedo(double albedo_prime, double g) { return albedo_from_reduced(albedo_prime, g); }

// The exact single-scattering total per entered flux at a node (transport units), for the coarse
// totals and the fine eta axis alike.
double node_single_scattering(double albedo_prime, double g, double eta) {
  return single_scattering_total(single_albedo(albedo_prime, g), g, eta);
}

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// ---- one (g, eta) node's running sums ------------------------------------------------------------
struct NodeSums {
  std::uint64_t photons = 0, chunks = 0, interactions = 0;
  double seconds = 0, lost = 0, specular = 0;
  std::vector<double> bin_sum, bin_sq;  // [albedo][bin], multiple scattering, per entered flux
  std::vector<double> ms_sum, ms_sq;    // [albedo] multiple-scattering total
  std::vector<double> ss_sum, ss_sq;    // [albedo] single-scattering total (a check of the exact one)

  void resize(std::size_t albedos, std::size_t bins) {
    bin_sum.assign(albedos * bins, 0.0);
    bin_sq.assign(albedos * bins, 0.0);
    ms_sum.assign(albedos, 0.0);
    ms_sq.assign(albedos, 0.0);
    ss_sum.assign(albedos, 0.0);
    ss_sq.assign(albedos, 0.0);
  }
};

constexpr char kStateMagic[8] = {'E', 'X', 'S', 'T', 'A', 'T', 'E', '1'};

std::filesystem::path node_path(const std::filesystem::path& dir, const Grid& grid, std::size_t gi, std::size_t ei,
                                std::size_t run) {
  const std::string base = run == grid.white() ? "" : "_base" + std::to_string(run);
  return dir / ("node_g" + std::to_string(gi) + "_eta" + std::to_string(ei) + base + ".bin");
}

void write_vector(std::ofstream& f, const std::vector<double>& v) {
  f.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(double)));
}
// Reads `count` doubles into v from element `first` on (a version-6 file's rows land above the new
// low-albedo rows: load).
void read_doubles(std::ifstream& f, std::vector<double>& v, std::size_t first, std::size_t count) {
  f.read(reinterpret_cast<char*>(v.data() + first), static_cast<std::streamsize>(count * sizeof(double)));
}

void save(const NodeSums& s, const std::filesystem::path& path) {
  const auto temporary = path.string() + ".partial";
  {
    std::ofstream f(temporary, std::ios::binary | std::ios::trunc);
    f.write(kStateMagic, 8);
    const std::uint64_t sizes[3] = {s.photons, s.chunks, s.interactions};
    f.write(reinterpret_cast<const char*>(sizes), sizeof sizes);
    const double scalars[3] = {s.seconds, s.lost, s.specular};
    f.write(reinterpret_cast<const char*>(scalars), sizeof scalars);
    for (const auto* v : {&s.bin_sum, &s.bin_sq, &s.ms_sum, &s.ms_sq, &s.ss_sum, &s.ss_sq}) write_vector(f, *v);
    if (!f) throw std::runtime_error("cannot write " + temporary);
  }
  std::filesystem::rename(temporary, path);
}

// A state file holds every albedo node's sums: magic, 3 counts, 3 scalars, then bin_sum and bin_sq
// ([albedo][bin]) and ms_sum, ms_sq, ss_sum, ss_sq ([albedo]). One written by version 6 (41 nodes from
// 0.001) is read into this grid's rows from 0.001 on, the six lower rows empty, except that of a run
// serving those rows (base 0.01): it reads as not run, and `run` traces it again from its first chunk,
// with the same seeds (the same photons: its rows from 0.001 on come out as before if the tracer is
// unchanged).
bool load(NodeSums& s, const std::filesystem::path& path, const Grid& grid, bool serves_low_nodes) {
  const std::size_t albedos = grid.albedo_prime.size(), bins = grid.bins();
  s = NodeSums{};
  s.resize(albedos, bins);
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  const auto bytes = [&](std::size_t rows) {
    return sizeof kStateMagic + 3 * sizeof(std::uint64_t) + (3 + 2 * rows * bins + 4 * rows) * sizeof(double);
  };
  const std::uintmax_t size = std::filesystem::file_size(path);
  const bool version6 = size == bytes(Grid::kVersion6Albedos);
  if (version6 && serves_low_nodes) return false;
  if (!version6 && size != bytes(albedos))
    throw std::runtime_error(path.string() + ": wrong size for this grid (" + std::to_string(size) + " bytes; " +
                             std::to_string(bytes(albedos)) + ", or " + std::to_string(bytes(Grid::kVersion6Albedos)) +
                             " from generator version 6)");
  char magic[8];
  f.read(magic, 8);
  if (!f || std::memcmp(magic, kStateMagic, 8) != 0) throw std::runtime_error(path.string() + ": not a state file");
  std::uint64_t sizes[3];
  double scalars[3];
  f.read(reinterpret_cast<char*>(sizes), sizeof sizes);
  f.read(reinterpret_cast<char*>(scalars), sizeof scalars);
  s.photons = sizes[0];
  s.chunks = sizes[1];
  s.interactions = sizes[2];
  s.seconds = scalars[0];
  s.lost = scalars[1];
  s.specular = scalars[2];
  const std::size_t rows = version6 ? Grid::kVersion6Albedos : albedos, low = albedos - rows;
  for (auto* v : {&s.bin_sum, &s.bin_sq}) read_doubles(f, *v, low * bins, rows * bins);
  for (auto* v : {&s.ms_sum, &s.ms_sq, &s.ss_sum, &s.ss_sq}) read_doubles(f, *v, low, rows);
  if (!f || f.peek() != EOF) throw std::runtime_error(path.string() + ": wrong size for this grid");
  return true;
}

// ---- run: one chunk of photons for one (g, eta) node ----------------------------------------------
void run_chunk(const Grid& grid, std::size_t gi, std::size_t ei, std::size_t run, std::uint64_t photons,
               std::uint64_t seed, NodeSums& sums) {
  const double g = grid.g[gi], eta = grid.eta[ei];
  const std::size_t albedos = grid.albedo_prime.size(), bins = grid.bins();
  const double alpha_max = single_albedo(grid.albedo_prime.back(), g);
  MonteCarloOptions options;
  options.photons = photons;
  options.seed = splitmix(splitmix(splitmix(seed ^ gi) ^ (ei << 20)) ^ sums.chunks);
  if (run != grid.white()) options.seed = splitmix(options.seed ^ ((run + 1) << 40));
  const double base_alpha = run == grid.white() ? 1.0 : single_albedo(grid.run_albedo_prime(run), g);
  options.batch_size = 256;
  options.bins = 2;
  options.r_max = 1;
  options.record_reflected_photons = true;
  options.max_interactions = static_cast<std::uint64_t>(std::ceil(6 / (1 - alpha_max)));
  const MonteCarloResult result =
      run_monte_carlo(LayerStack::half_space(Medium::single_channel(1 - base_alpha, base_alpha, g, eta)), options);
  const ChannelResult& channel = result.channels[0];
  const double entered = 1 / (1 - channel.specular_reflectance);

  // Only the albedos this run serves (alpha' <= its base): the reweighting factor stays <= 1.
  std::size_t served = 0;
  while (served < albedos && grid.albedo_prime[served] <= grid.run_albedo_prime(run)) ++served;
  std::vector<double> ln_alpha(albedos), ln_scale(albedos);
  for (std::size_t a = 0; a < albedos; ++a) {
    const double alpha = single_albedo(grid.albedo_prime[a], g);
    ln_alpha[a] = std::log(alpha) - std::log(base_alpha);  // the weight already carries base_alpha^k
    ln_scale[a] = std::log(1 - alpha * g);                 // sigma_t' / sigma_t: mfp -> transport mfp
  }
  const double first = grid.ln_first_edge(), inv_step = 1 / grid.d_ln_r;
  for (const ReflectedPhoton& p : channel.reflected_photons) {
    const double w0 = p.weight * entered;
    const double k = p.scatterings;
    if (p.scatterings == 1) {
      for (std::size_t a = 0; a < served; ++a) {
        const double w = w0 * std::exp(ln_alpha[a]);
        sums.ss_sum[a] += w;
        sums.ss_sq[a] += w * w;
      }
      continue;
    }
    if (p.scatterings < 2) continue;
    const double ln_r = std::log(p.radius);
    for (std::size_t a = 0; a < served; ++a) {
      const double w = w0 * std::exp(k * ln_alpha[a]);
      if (w == 0) continue;
      const double f = (ln_r + ln_scale[a] - first) * inv_step;
      const std::size_t bin = f < 0 ? 0 : std::min(bins - 1, static_cast<std::size_t>(f) + 1);
      sums.bin_sum[a * bins + bin] += w;
      sums.bin_sq[a * bins + bin] += w * w;
      sums.ms_sum[a] += w;
      sums.ms_sq[a] += w * w;
    }
  }
  sums.photons += photons;
  sums.chunks += 1;
  sums.interactions += channel.interactions;
  sums.seconds += result.seconds;
  sums.lost += channel.lost * static_cast<double>(photons);
  sums.specular = channel.specular_reflectance;
}

std::string describe_node(const Grid& grid, std::size_t gi, std::size_t ei) {
  char text[64];
  std::snprintf(text, sizeof text, "g %.3f eta %.2f", grid.g[gi], grid.eta[ei]);
  return text;
}

// What one `run` tops up: by default every run of every node; --runs (base alpha' values, 1 for the
// non-absorbing run) and --g-min / --g-max focus the photons where the table is noisiest (the
// non-absorbing runs serve alpha' > 0.99, the base-0.01 runs the lowest albedos). Chunk seeds depend
// only on the chunk's index, so a focused run gives the same sums as an unfocused one reaching the
// same counts.
struct RunFocus {
  std::vector<double> runs;  // empty: all
  double g_min = 0, g_max = 1, eta_min = 0, eta_max = 10;
  bool includes(const Grid& grid, std::size_t gi, std::size_t ei, std::size_t b) const {
    if (grid.g[gi] < g_min || grid.g[gi] > g_max) return false;
    if (grid.eta[ei] < eta_min || grid.eta[ei] > eta_max) return false;
    return runs.empty() || std::find(runs.begin(), runs.end(), grid.run_albedo_prime(b)) != runs.end();
  }
};

int run(const std::filesystem::path& dir, std::uint64_t target, std::uint64_t chunk, double hours, std::uint64_t seed,
        const RunFocus& focus) {
  const Grid grid;
  std::filesystem::create_directories(dir);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed_hours = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 3600;
  };
  // Under mpirun or srun the nodes of a pass are dealt to the ranks in turn (node k to rank
  // k % ranks); each node's file is written by one rank only, and its chunks and seeds are the ones a
  // single process would run, so the state and the table are bitwise identical whatever the ranks.
  ProcessGroup* group = launched_process_group();
  const std::size_t ranks = group ? static_cast<std::size_t>(group->size()) : 1;
  const std::size_t rank = group ? static_cast<std::size_t>(group->rank()) : 0;
  const auto any_rank = [&](bool value) { return group ? group->any(value) : value; };
  for (;;) {
    bool any = false, time_up = false;
    std::size_t item = 0;
    for (std::size_t ei = 0; ei < grid.eta.size() && !time_up; ++ei) {
      for (std::size_t gi = 0; gi < grid.g.size() && !time_up; ++gi) {
        for (std::size_t b = 0; b < grid.runs() && !time_up; ++b) {
          if (!focus.includes(grid, gi, ei, b)) continue;
          if (item++ % ranks != rank) continue;
          NodeSums sums;
          const auto path = node_path(dir, grid, gi, ei, b);
          load(sums, path, grid, grid.serves_low_nodes(b));
          const std::uint64_t run_target = target * grid.run_factor(b);
          if (sums.photons >= run_target) continue;
          any = true;
          if (elapsed_hours() > hours) {
            time_up = true;
            break;
          }
          const std::uint64_t n = std::min(chunk * grid.run_factor(b), run_target - sums.photons);
          const auto t0 = std::chrono::steady_clock::now();
          run_chunk(grid, gi, ei, b, n, seed, sums);
          save(sums, path);
          std::cerr << describe_node(grid, gi, ei) << " base alpha' " << grid.run_albedo_prime(b) << ": "
                    << sums.photons << " photons, "
                    << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s, "
                    << static_cast<double>(sums.interactions) / static_cast<double>(sums.photons)
                    << " scatterings/photon, lost " << sums.lost / static_cast<double>(sums.photons) << "\n";
        }
      }
    }
    // Every rank ends the pass here: all stop when any ran out of time, all go on while any has work.
    if (any_rank(time_up)) {
      std::cerr << "stopped after " << hours << " h (run again to continue)\n";
      return 0;
    }
    if (!any_rank(any)) break;
  }
  std::cerr << "every node in focus has " << target << " photons\n";
  return 0;
}

// ---- radial smoothing of the multiple-scattering tallies -------------------------------------------
// Where a node's runs had few photons (the non-absorbing runs at alpha' > 0.99, 2.5-5e4 photons), a
// bin's mean is noisy (3-6 % in the near field) while the profile itself is smooth in ln y over
// ln r. Each bin's ln mean is replaced by a local quadratic fit over the well-measured bins within
// `half` bins of it (Savitzky-Golay, unweighted: the bins of a window have similar noise, and
// weights from the noisy standard errors themselves would bias). The fit's value at the bin is a
// linear combination sum L_j ln mean_j, so its standard error is exactly sqrt(sum L_j^2 rel_j^2);
// ln mean_j + rel_j^2 / 2 removes the second-order bias of the logarithm. The quadratic's bias is
// the profile's fourth derivative times sum L_j j^4 d_ln_r^4 / 24: measured on well-sampled nodes
// by `build` (provenance "radial_smoothing").
struct Smoothed {
  std::vector<double> mean, se;
  std::vector<double> own_weight;  // L_k of the bin's own mean (0: left as it was)
};
Smoothed smooth_radially(const std::vector<double>& mean, const std::vector<double>& se, const std::vector<bool>& good,
                         int half) {
  Smoothed out{mean, se, std::vector<double>(mean.size(), 0.0)};
  const auto n = static_cast<std::ptrdiff_t>(mean.size());
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    if (!good[static_cast<std::size_t>(k)]) continue;
    // Normal equations of z_j = c0 + c1 x + c2 x^2, x = j - k, over the window's good bins.
    double m[3][3] = {}, count = 0;
    std::vector<std::ptrdiff_t> bins;
    for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(0, k - half); j <= std::min(n - 1, k + half); ++j) {
      if (!good[static_cast<std::size_t>(j)]) continue;
      bins.push_back(j);
      const double x = static_cast<double>(j - k), p[3] = {1, x, x * x};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) m[a][b] += p[a] * p[b];
      count += 1;
    }
    if (count < 5) continue;  // a quadratic through fewer points would follow the noise
    // Row 0 of the inverse (cofactors): c0 = sum_j (inv[0] . p_j) z_j.
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    const double inv0[3] = {(m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det,
                            -(m[0][1] * m[2][2] - m[0][2] * m[2][1]) / det,
                            (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det};
    double z = 0, variance = 0;
    for (std::ptrdiff_t j : bins) {
      const double x = static_cast<double>(j - k);
      const double weight = inv0[0] + inv0[1] * x + inv0[2] * x * x;
      if (j == k) out.own_weight[static_cast<std::size_t>(k)] = weight;
      const std::size_t u = static_cast<std::size_t>(j);
      const double rel = se[u] / mean[u];
      z += weight * (std::log(mean[u]) + 0.5 * rel * rel);
      variance += weight * weight * rel * rel;
    }
    const std::size_t u = static_cast<std::size_t>(k);
    out.mean[u] = std::exp(z);
    out.se[u] = out.mean[u] * std::sqrt(variance);
  }
  return out;
}

// ---- build: the table from the sums ---------------------------------------------------------------
std::string git_revision() {
  std::string out;
  if (FILE* p = popen("git rev-parse --short HEAD 2>/dev/null", "r")) {
    char buffer[64];
    while (std::fgets(buffer, sizeof buffer, p)) out += buffer;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out.empty() ? "unknown" : out;
}

// The semi-infinite medium's total diffuse reflectance per unit entered flux by adding-doubling,
// in transport units, and the exact single-scattering total beside it.
struct AddingDoublingTotal {
  double total = 0, error_estimate = 0, single_scattering = 0;
  // Converged: its own error estimate (from doubling the angles) within 2e-4 of the total. With g
  // near 1 and low albedo delta-M with 128 angles does not converge (even negative totals at
  // alpha' 0.001, g 0.99).
  bool converged() const { return total > single_scattering && error_estimate <= 2e-4 * total; }
};
// One adding-doubling solve of the node's semi-infinite medium (transport units) with these options.
AddingDoublingTotal solve_half_space(double albedo_prime, double g, double eta, const adding_doubling::Options& ad) {
  const Reduced<double> m = reduce(1 - albedo_prime, albedo_prime / (1 - g), g, eta);
  const auto totals =
      adding_doubling::solve(adding_doubling::half_space(m), adding_doubling::Incidence::collimated, ad);
  return AddingDoublingTotal{totals.diffuse_reflectance * totals.entered_scale(), totals.error_estimate,
                             node_single_scattering(albedo_prime, g, eta)};
}
AddingDoublingTotal adding_doubling_total(double albedo_prime, double g, double eta) {
  adding_doubling::Options ad;
  ad.tolerance = 1e-5 * albedo_prime;  // relative to R_d, which is of order alpha' at low albedo
  AddingDoublingTotal t = solve_half_space(albedo_prime, g, eta, ad);
  // At high eta the total is a small fraction of alpha' (0.016 at alpha' 0.16, g 0.95, eta 1.8), so
  // that tolerance stops short of the convergence test; once more with a tolerance of half the test's
  // bound (generator version 5: there the Monte Carlo total, 0.56 % noisy, had stood and the
  // interpolated total was 0.67 % off).
  if (!t.converged() && t.total > t.single_scattering) {
    ad.tolerance = 1e-4 * t.total;
    t = solve_half_space(albedo_prime, g, eta, ad);
  }
  return t;
}

// The node's total where 128 angles fall short of the convergence test but not far (within 1 %):
// 256 and 512 angles, the second standing with the change between them as its error estimate
// (version 8). At g 0.995 and 0.999 with mid albedo 128 angles are 0.04-0.2 % from convergence;
// 256 -> 512 changes the total by ~0.01 % (alpha' 0.16, g 0.995, eta 1.45: 0.0038071, 0.0038039,
// 0.0038035 at 128, 256, 512), and there the Monte Carlo totals had stood, 0.2-0.5 % above it;
// fresh Monte Carlo at the node (2e10 scatterings) sides with adding-doubling. Not for the fine eta
// axis: its bend comes from 128 angles' shape (add_fine_totals), where the errors cancel.
AddingDoublingTotal refined_adding_doubling_total(double albedo_prime, double g, double eta, AddingDoublingTotal t) {
  if (t.converged() || !(t.total > t.single_scattering) || t.error_estimate > 1e-2 * t.total) return t;
  adding_doubling::Options ad;
  ad.points = 256;
  const double t256 = solve_half_space(albedo_prime, g, eta, ad).total;
  ad.points = 512;
  const double t512 = solve_half_space(albedo_prime, g, eta, ad).total;
  return AddingDoublingTotal{t512, std::abs(t512 - t256), t.single_scattering};
}

// Adding-doubling's shape in eta is trusted where its error estimate is within 1 % of the total
// (looser than a total it is to stand for: only its bend between eta nodes is used).
bool usable_shape(const AddingDoublingTotal& t) {
  return t.total > t.single_scattering && t.error_estimate <= 1e-2 * t.total;
}

// The totals on the fine eta axis: the coarse totals' interpolation times adding-doubling's own
// ratio of its value to its interpolation from the coarse eta nodes (1 at those nodes, so the node
// totals stand; between them it restores the bend the coarse nodes miss). Where adding-doubling's
// shape is not usable at every eta of a (g, alpha') (low albedo with g near 1, where single
// scattering is most of the total), the row's fine total is the exact single-scattering total at
// that eta plus the coarse multiple-scattering totals' interpolation: the bend of the larger part
// is then exact too. `coarse_ad` holds adding-doubling and single scattering at the coarse nodes
// ([eta][g][albedo]). Returns how many (g, alpha') rows took single scattering + interpolation.
std::size_t add_fine_totals(const Grid& grid, ExactTable& table, const std::vector<AddingDoublingTotal>& coarse_ad) {
  table.prepare();
  ExactTable shape = table;  // adding-doubling at the coarse nodes, for its own interpolation
  for (std::size_t i = 0; i < shape.total.size(); ++i)
    shape.total[i] = usable_shape(coarse_ad[i]) ? coarse_ad[i].total : table.total[i];
  shape.prepare();
  ExactTable multiple = table;  // the coarse multiple-scattering totals, for rows without a usable shape
  for (std::size_t i = 0; i < multiple.total.size(); ++i)
    multiple.total[i] = table.total[i] - coarse_ad[i].single_scattering;
  multiple.prepare();
  const std::size_t albedos = grid.albedo_prime.size(), rows = grid.g.size() * albedos;
  std::vector<double> fine(grid.total_eta.size() * rows);
  std::vector<char> plain(rows, 0);
  parallel_for(rows, 0, [&](std::size_t row) {
    const std::size_t gi = row / albedos, a = row % albedos;
    const double ap = grid.albedo_prime[a], g = grid.g[gi];
    bool usable = true;
    for (std::size_t e = 0; e < grid.eta.size(); ++e) usable = usable && usable_shape(coarse_ad[table.node(e, gi, a)]);
    std::vector<double> ratio(grid.total_eta.size(), 1.0);
    for (std::size_t e = 0; e < grid.total_eta.size() && usable; ++e) {
      const AddingDoublingTotal t = adding_doubling_total(ap, g, grid.total_eta[e]);
      usable = usable_shape(t);
      ratio[e] = t.total / exact_total(shape, ap, g, grid.total_eta[e]);
    }
    for (std::size_t e = 0; e < grid.total_eta.size(); ++e) {
      const double eta = grid.total_eta[e];
      fine[table.node(e, gi, a)] = usable ? exact_total(table, ap, g, eta) * ratio[e]
                                          : node_single_scattering(ap, g, eta) + exact_total(multiple, ap, g, eta);
    }
    plain[row] = !usable;
  });
  table.total_eta = grid.total_eta;
  table.fine_total = std::move(fine);
  table.prepare();
  return static_cast<std::size_t>(std::count(plain.begin(), plain.end(), 1));
}

int build(const std::filesystem::path& dir, const std::string& out_path, std::uint64_t seed,
          const std::string& base_path) {
  const Grid grid;
  // A build takes minutes: refuse an output folder that is not there before, not after.
  const auto out_dir = std::filesystem::absolute(out_path).parent_path();
  if (!std::filesystem::is_directory(out_dir))
    throw std::runtime_error("--out " + out_path + ": the folder " + out_dir.string() + " does not exist");
  // --base: a table whose nodes are copied (its radius axis must be this grid's, its alpha' axis this
  // grid's or its part from 0.001 on, its g and eta nodes a subset of this grid's: how a table grows
  // new eta nodes (version 5), new g nodes (version 6) and new albedo nodes below 0.001 (version 7,
  // from the state's base-0.01 runs at every (g, eta))).
  std::optional<ExactTable> base;
  struct BaseNode {
    std::size_t g, eta;
  };
  std::vector<std::optional<BaseNode>> base_node(grid.g.size() * grid.eta.size());
  const auto from_base = [&](std::size_t gi, std::size_t ei) -> const std::optional<BaseNode>& {
    return base_node[ei * grid.g.size() + gi];
  };
  if (!base_path.empty()) {
    base = read_exact_table(base_path, TableErrors::read);
    const auto subset = [](const std::vector<double>& part, const std::vector<double>& whole) {
      return std::all_of(part.begin(), part.end(),
                         [&](double v) { return std::find(whole.begin(), whole.end(), v) != whole.end(); });
    };
    const bool albedo_suffix =
        base->albedo_prime.size() <= grid.albedo_prime.size() &&
        std::equal(base->albedo_prime.begin(), base->albedo_prime.end(),
                   grid.albedo_prime.end() - static_cast<std::ptrdiff_t>(base->albedo_prime.size()));
    if (!albedo_suffix || base->radii != grid.radii || base->ln_r0 != grid.ln_r0 || base->d_ln_r != grid.d_ln_r ||
        !subset(base->g, grid.g) || !subset(base->eta, grid.eta))
      throw std::runtime_error(base_path +
                               ": its alpha' or radius axis is not this grid's, or it has g or eta "
                               "nodes this grid lacks");
    for (std::size_t bg = 0; bg < base->g.size(); ++bg)
      for (std::size_t be = 0; be < base->eta.size(); ++be) {
        const auto gi = std::find(grid.g.begin(), grid.g.end(), base->g[bg]) - grid.g.begin();
        const auto ei = std::find(grid.eta.begin(), grid.eta.end(), base->eta[be]) - grid.eta.begin();
        base_node[static_cast<std::size_t>(ei) * grid.g.size() + static_cast<std::size_t>(gi)] = BaseNode{bg, be};
      }
  }
  // A node the base table holds whose non-absorbing run is in DIR too (version 10: g 0.99, its near
  // field measured again) has its albedo nodes served by that run rebuilt from it; the rest copied.
  std::vector<bool> white_rebuilt_at(grid.g.size() * grid.eta.size(), false);
  for (std::size_t ei = 0; ei < grid.eta.size(); ++ei)
    for (std::size_t gi = 0; gi < grid.g.size(); ++gi)
      white_rebuilt_at[ei * grid.g.size() + gi] =
          from_base(gi, ei) && std::filesystem::exists(node_path(dir, grid, gi, ei, grid.white()));
  const auto white_rebuilt = [&](std::size_t gi, std::size_t ei) { return white_rebuilt_at[ei * grid.g.size() + gi]; };
  const std::size_t albedos = grid.albedo_prime.size(), bins = grid.bins(), radii = grid.radii;
  // Base albedo nodes below the base table's first (version 7's low nodes) come from the state.
  const std::size_t first_copied = base ? albedos - base->albedo_prime.size() : albedos;
  const auto copied_node = [&](std::size_t gi, std::size_t ei, std::size_t a) {
    return from_base(gi, ei) && a >= first_copied &&
           !(white_rebuilt(gi, ei) && grid.run_for(grid.albedo_prime[a]) == grid.white());
  };
  ExactTable table;
  table.albedo_prime = grid.albedo_prime;
  table.g = grid.g;
  table.eta = grid.eta;
  table.ln_r0 = grid.ln_r0;
  table.d_ln_r = grid.d_ln_r;
  table.radii = radii;
  table.ln_y.assign(table.nodes() * radii, 0.0f);
  table.relative_error.assign(table.nodes() * radii, 0);
  table.total.assign(table.nodes(), 0.0);

  std::uint64_t min_photons = UINT64_MAX, max_photons = 0, interactions = 0, photons = 0;
  // Photons per run and g (the fewest over eta): `run --runs --g-min --g-max` tops up unevenly.
  std::vector<std::vector<std::uint64_t>> run_photons(grid.runs(),
                                                      std::vector<std::uint64_t>(grid.g.size(), UINT64_MAX));
  double cpu_seconds = 0, worst_scale_sigma = 0, worst_ss_sigma = 0, worst_lost = 0, largest_r999 = 0;
  std::string worst_scale_at, worst_ss_at;
  std::size_t extrapolated = 0, monte_carlo_totals = 0;
  std::vector<double> near_slopes;    // the near-field continuation's slope per node that has one
  std::vector<double> near_fit_chi2;  // the near-field fit's chi2 per degree of freedom per node fitted
  std::size_t near_fit_failed = 0;    // nodes whose fit did not converge (left to smoothing and continuation)
  double near_fit_z[3] = {}, near_fit_groups[3] = {};  // its bias check: (fit - tally) / se pooled over 6 bins
  const int smoothing_half = kSmoothingHalf, wide_half = kSmoothingWide;
  double smoothing_chi2 = 0, wide_chi2 = 0, smoothing_bins = 0;
  nlohmann::json scale_check = nlohmann::json::array();
  // Adding-doubling at every node on every core: 128 angles' totals (coarse_ad) give the fine eta
  // axis its shape; a node not copied from the base takes the refined total (node_ad).
  std::vector<AddingDoublingTotal> coarse_ad(table.nodes()), node_ad(table.nodes());
  std::atomic<std::size_t> solved{0};  // progress: 5.5 min for version 7's 5264 nodes on 2 idle cores
  std::mutex progress;
  parallel_for(table.nodes(), 0, [&](std::size_t i) {
    const std::size_t a = i % albedos, gi = i / albedos % grid.g.size(), ei = i / albedos / grid.g.size();
    coarse_ad[i] = adding_doubling_total(grid.albedo_prime[a], grid.g[gi], grid.eta[ei]);
    node_ad[i] = copied_node(gi, ei, a)
                     ? coarse_ad[i]
                     : refined_adding_doubling_total(grid.albedo_prime[a], grid.g[gi], grid.eta[ei], coarse_ad[i]);
    const std::size_t done = ++solved;
    if (done % 500 == 0 || done == table.nodes()) {
      const std::lock_guard<std::mutex> lock(progress);
      std::cerr << "adding-doubling totals: " << done << " of " << table.nodes() << " nodes\n";
    }
  });
  for (std::size_t ei = 0; ei < grid.eta.size(); ++ei) {
    for (std::size_t gi = 0; gi < grid.g.size(); ++gi) {
      const auto& copy = from_base(gi, ei);
      const auto copied = [&](std::size_t a) { return copied_node(gi, ei, a); };
      for (std::size_t a = first_copied; copy && a < albedos; ++a) {  // from --base: profiles, errors, totals stand
        if (!copied(a)) continue;
        const std::size_t from = base->node(copy->eta, copy->g, a - first_copied), to = table.node(ei, gi, a);
        table.total[to] = base->total[from];
        for (std::size_t k = 0; k < radii; ++k) {
          table.ln_y[to * radii + k] = base->ln_y[from * radii + k];
          table.relative_error[to * radii + k] = base->relative_error[from * radii + k];
        }
      }
      if (copy && first_copied == 0 && !white_rebuilt(gi, ei)) continue;
      std::vector<NodeSums> runs(grid.runs());
      for (std::size_t b = 0; b < grid.runs(); ++b) {
        bool needed = false;  // the runs serving the nodes not copied
        for (std::size_t a = 0; a < albedos; ++a)
          needed = needed || (!copied(a) && grid.run_for(grid.albedo_prime[a]) == b);
        if (!needed) continue;
        NodeSums& s = runs[b];
        if (!load(s, node_path(dir, grid, gi, ei, b), grid, grid.serves_low_nodes(b)) || s.photons == 0)
          throw std::runtime_error("no Monte Carlo for " + describe_node(grid, gi, ei) + " base alpha' " +
                                   format_number(grid.run_albedo_prime(b)) + ": run first");
        if (b == grid.white()) {
          min_photons = std::min(min_photons, s.photons);
          max_photons = std::max(max_photons, s.photons);
        }
        run_photons[b][gi] = std::min(run_photons[b][gi], s.photons);
        photons += s.photons;
        interactions += s.interactions;
        cpu_seconds += s.seconds;
        worst_lost = std::max(worst_lost, s.lost / static_cast<double>(s.photons));
      }
      const double g = grid.g[gi], eta = grid.eta[ei];
      for (std::size_t a = 0; a < albedos; ++a) {
        if (copied(a)) continue;
        const NodeSums& s = runs[grid.run_for(grid.albedo_prime[a])];
        const double n = static_cast<double>(s.photons);
        const double ap = grid.albedo_prime[a];
        // Transport units: sigma_t' = 1.
        const Reduced<double> m = reduce(1 - ap, ap / (1 - g), g, eta);
        const AddingDoublingTotal& totals = node_ad[table.node(ei, gi, a)];
        const double ad_total = totals.total;
        const double ss_total = totals.single_scattering;
        const auto mean_se = [n](double sum, double sq) {
          const double mean = sum / n;
          return std::pair{mean, std::sqrt(std::max(0.0, (sq / n - mean * mean) / (n - 1)))};
        };
        const auto [ms_mc, ms_se] = mean_se(s.ms_sum[a], s.ms_sq[a]);
        const auto [ss_mc, ss_se] = mean_se(s.ss_sum[a], s.ss_sq[a]);
        // The multiple-scattering total from the more precise solver. Adding-doubling where it has
        // converged (its error estimate, from doubling the angles, within 2e-4 of the total) and
        // that estimate is under a quarter of the Monte Carlo's standard error: at low albedo the
        // multiple scattering is ~0.1 % of the total, so 2e-4 of the total is up to 4 % of it, and
        // the estimate can understate the error (alpha' 0.001, g 0.8, eta 1.3: 0.24 % estimated,
        // 2.8 % from a Monte Carlo precise to 0.29 %). Elsewhere the Monte Carlo total stands
        // (exact single scattering + multiple scattering; delta-M with 128 angles does not
        // converge at all with g near 1 and low albedo: negative totals at alpha' 0.001, g 0.99).
        const bool ad_converged = totals.converged();
        const bool ad_used = ad_converged && totals.error_estimate <= 0.25 * ms_se;
        const double ms_exact = ad_used ? ad_total - ss_total : ms_mc;
        const double total = ss_total + ms_exact;
        const double scale = ms_mc > 0 ? ms_exact / ms_mc : 0.0;
        char where[96];
        std::snprintf(where, sizeof where, "alpha' %.6g, g %.3f, eta %.2f", ap, g, eta);
        if (ad_used && ms_se > 0) {
          const double scale_sigma = (ms_mc - ms_exact) / ms_se;
          if (std::abs(scale_sigma) > std::abs(worst_scale_sigma)) {
            worst_scale_sigma = scale_sigma;
            worst_scale_at = where;
          }
        } else {
          ++monte_carlo_totals;
        }
        const double ss_sigma = ss_se > 0 ? (ss_mc - ss_total) / ss_se : 0;
        if (std::abs(ss_sigma) > std::abs(worst_ss_sigma)) {
          worst_ss_sigma = ss_sigma;
          worst_ss_at = where;
        }
        scale_check.push_back({ap, g, eta, ms_mc, ms_se, ad_converged ? ad_total - ss_total : NAN,
                               totals.error_estimate, ad_used ? "adding-doubling" : "monte-carlo"});
        table.total[table.node(ei, gi, a)] = total;

        // Multiple scattering per node radius: bin means of dE/d ln r, scaled to the exact total.
        std::vector<double> mean(radii), se(radii), y_ms(radii, 0.0), y_ss(radii);
        for (std::size_t k = 0; k < radii; ++k) {
          const auto [v, e] = mean_se(s.bin_sum[a * bins + k + 1], s.bin_sq[a * bins + k + 1]);
          mean[k] = v * scale / grid.d_ln_r;
          se[k] = e * scale / grid.d_ln_r;
          const double r = std::exp(grid.ln_r0 + grid.d_ln_r * static_cast<double>(k));
          y_ss[k] = 2 * std::numbers::pi * r * r * single_scattering_reflectance(m, r, 96);
        }
        // A bin mean is the average of y over the bin in ln r; the node value differs by the
        // curvature: y(node) = mean - (mean[k-1] - 2 mean[k] + mean[k+1]) / 24 (fourth order).
        std::vector<bool> good(radii), continued(radii, false);
        for (std::size_t k = 0; k < radii; ++k) good[k] = mean[k] > 0 && se[k] < 0.3 * mean[k];
        if (std::none_of(good.begin(), good.end(), [](bool b) { return b; }))
          for (std::size_t k = 0; k < radii; ++k) good[k] = mean[k] > 0;  // noisy: relative errors say so
        const std::vector<double> tallied = mean, tallied_se = se;  // before smoothing: the near field's pooled energy
        {                                                           // radial smoothing (smooth_radially)
          std::vector<bool> smoothable(radii);
          for (std::size_t k = 0; k < radii; ++k) smoothable[k] = good[k] && se[k] < 0.3 * mean[k];
          const Smoothed smooth = smooth_radially(mean, se, smoothable, smoothing_half);
          const Smoothed wide = smooth_radially(mean, se, smoothable, wide_half);
          // The bias check: on well-sampled bins (within 0.5 %), where a bias would stand out of
          // the noise, the change in units of the bin's own error has E[d^2] = 1 - L_k if the fit
          // is unbiased.
          for (std::size_t k = 0; k < radii; ++k) {
            if (smooth.own_weight[k] == 0 || wide.own_weight[k] == 0 || !(se[k] < 0.005 * mean[k])) continue;
            smoothing_chi2 += std::pow((smooth.mean[k] - mean[k]) / se[k], 2) / (1 - smooth.own_weight[k]);
            wide_chi2 += std::pow((wide.mean[k] - mean[k]) / se[k], 2) / (1 - wide.own_weight[k]);
            smoothing_bins += 1;
          }
          // Bins measured within 0.5 % keep their value: there the smoothing's bias (above) would
          // be comparable to their noise.
          for (std::size_t k = 0; k < radii; ++k)
            if (!(se[k] < 0.005 * mean[k])) {
              const Smoothed& use = se[k] > 0.03 * mean[k] ? wide : smooth;
              mean[k] = use.mean[k];
              se[k] = use.se[k];
            }
        }
        {  // a near field noisy over more than 2/3 of a decade: one fit over it (near_field_fit.hpp)
          std::size_t measured = 0;  // the first bin measured within 2 %
          while (measured < radii && !(tallied[measured] > 0 && tallied_se[measured] < 0.02 * tallied[measured]))
            ++measured;
          if (measured >= kNearFitFirst && measured < radii) {
            const std::size_t last = std::min<std::size_t>(measured, kNearFitLast);
            const exact_table::NearFieldFit fit = exact_table::fit_near_field(tallied, tallied_se, last, grid.d_ln_r);
            near_fit_failed += !fit.converged;
            if (fit.converged) {
              near_fit_chi2.push_back(fit.chi2_per_dof);
              // The bias check: the fit against the tally pooled over 6 bins (half a decade), in
              // units of the pooled standard error, per group inside the range the fit alone covers.
              for (std::size_t group = 0; (group + 1) * 6 + 2 * kNearFitBlend <= last + 1 && group < 3; ++group) {
                double tally = 0, variance = 0, fitted = 0;
                for (std::size_t k = group * 6; k < group * 6 + 6; ++k) {
                  tally += tallied[k];
                  variance += tallied_se[k] * tallied_se[k];
                  fitted += fit.mean[k];
                }
                if (variance > 0) {
                  near_fit_z[group] += (fitted - tally) / std::sqrt(variance);
                  near_fit_groups[group] += 1;
                }
              }
              // The fit alone up to 12 bins (one decade) inside its last; then to 6 bins inside, a
              // blend in ln y with the smoothed bins (the fit's end is its least certain part).
              for (std::size_t k = 0; k + kNearFitBlend <= last; ++k) {
                const double w = std::clamp(static_cast<double>(last - kNearFitBlend - k) / kNearFitBlend, 0.0, 1.0);
                const bool smoothed = good[k] && mean[k] > 0;
                const double wf = smoothed ? w : 1.0;
                mean[k] = std::exp(wf * std::log(fit.mean[k]) + (1 - wf) * std::log(mean[k] > 0 ? mean[k] : 1.0));
                se[k] = wf * fit.se[k] + (1 - wf) * se[k];
                good[k] = true;
              }
            }
          }
        }
        const bool any_ms = std::any_of(good.begin(), good.end(), [](bool b) { return b; });
        std::size_t first_good = 0, last_good = radii - 1;
        if (any_ms) {
          while (!good[first_good]) ++first_good;
          while (!good[last_good]) --last_good;
          for (std::size_t k = 0; k < radii; ++k) {
            y_ms[k] = std::max(0.0, mean[k]);
            if (k > 0 && k + 1 < radii && good[k - 1] && good[k] && good[k + 1])
              y_ms[k] = mean[k] - (mean[k - 1] - 2 * mean[k] + mean[k + 1]) / 24;
          }
          // Near field below the first well-measured radius: y_ms ~ r^s, s in [1, 2] holding the
          // energy the run tallied there (near_field_continuation.hpp). At g 0.995 the table's first
          // radius is 0.2 mfp, and there a reference of 10^6 photons (alpha' 0.9953, eta 1.787) has
          // R ~ 1/r from 0.001 to 0.007 transport mfp, 2.5 times version 8's flat continuation.
          const std::size_t fg = first_good;
          double pooled = 0, pooled_variance = 0;
          for (std::size_t k = 0; k < fg; ++k) {
            pooled += std::max(0.0, tallied[k]);
            pooled_variance += tallied_se[k] * tallied_se[k];
          }
          const double slope =
              exact_table::near_field_slope(y_ms[fg], pooled, std::sqrt(pooled_variance), fg, grid.d_ln_r);
          if (fg > 0) near_slopes.push_back(slope);
          for (std::size_t k = 0; k < fg; ++k) {
            y_ms[k] = exact_table::near_field_continued(y_ms[fg], slope, k, fg, grid.d_ln_r);
            continued[k] = true;
          }
          // Between well-measured radii, a bin without photons takes the log-linear interpolation
          // of its neighbours.
          for (std::size_t k = first_good; k <= last_good; ++k) {
            if (y_ss[k] + y_ms[k] > 0) continue;
            std::size_t lo = k, hi = k;
            while (lo > first_good && !(y_ss[lo] + y_ms[lo] > 0)) --lo;
            while (hi < last_good && !(y_ss[hi] + y_ms[hi] > 0)) ++hi;
            const double t = static_cast<double>(k - lo) / static_cast<double>(hi - lo);
            y_ms[k] = std::exp((1 - t) * std::log(y_ss[lo] + y_ms[lo]) + t * std::log(y_ss[hi] + y_ms[hi])) - y_ss[k];
            continued[k] = true;
          }
        } else {
          // No multiple scattering tallied at all: the profile is the exact single scattering,
          // down to where it underflows.
          last_good = 0;
          while (last_good + 1 < radii && y_ss[last_good + 1] > 1e-250) ++last_good;
        }
        std::vector<double> ln_y(radii);
        for (std::size_t k = 0; k <= last_good; ++k) {
          ln_y[k] = std::log(y_ss[k] + y_ms[k]);
          const double relative = any_ms ? se[k] / (y_ss[k] + y_ms[k]) : 0.0;
          table.relative_error[table.index(ei, gi, a, k)] =
              continued[k] ? ExactTable::kExtrapolated
                           : static_cast<std::uint16_t>(std::min(65534.0, std::round(relative * 1e4)));
        }
        // The far tail past the last well-measured radius: ln y continues linearly in r (an
        // exponential tail) with the slope of the last well-measured decade.
        if (last_good + 1 < radii) {
          const std::size_t from = last_good >= first_good + 12 ? last_good - 12 : first_good;
          const double r1 = std::exp(grid.ln_r0 + grid.d_ln_r * static_cast<double>(from));
          const double r2 = std::exp(grid.ln_r0 + grid.d_ln_r * static_cast<double>(last_good));
          const double slope = from < last_good ? std::min(-1e-3, (ln_y[last_good] - ln_y[from]) / (r2 - r1)) : -1.0;
          for (std::size_t k = last_good + 1; k < radii; ++k) {
            const double r = std::exp(grid.ln_r0 + grid.d_ln_r * static_cast<double>(k));
            ln_y[k] = ln_y[last_good] + slope * (r - r2);
            table.relative_error[table.index(ei, gi, a, k)] = ExactTable::kExtrapolated;
          }
        }
        double energy = 0, cumulative = 0;
        for (std::size_t k = 0; k < radii; ++k) energy += std::exp(ln_y[k]);
        for (std::size_t k = 0; k < radii; ++k) {
          cumulative += std::exp(ln_y[k]);
          if (cumulative >= 0.999 * energy) {
            largest_r999 = std::max(largest_r999, std::exp(grid.ln_r0 + grid.d_ln_r * static_cast<double>(k)));
            break;
          }
        }
        for (std::size_t k = 0; k < radii; ++k) {
          table.ln_y[table.index(ei, gi, a, k)] = static_cast<float>(ln_y[k]);
          if (table.relative_error[table.index(ei, gi, a, k)] == ExactTable::kExtrapolated) ++extrapolated;
        }
      }
    }
  }
  const std::size_t interpolated_rows = add_fine_totals(grid, table, coarse_ad);
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  nlohmann::json p;
  p["generator"] = "tools/exact_table/generate_exact_table";
  p["generator_version"] = kGeneratorVersion;
  p["source_revision"] = git_revision();
  p["built"] = date;
  p["method"] =
      "multiple scattering: project Monte Carlo, a non-absorbing run and absorbing runs per (g, eta) reweighted by "
      "albedo^k, scaled to the multiple-scattering total (see totals); single scattering: exact integral";
  p["photons_per_g_eta_node_white_run"] = {{"min", min_photons}, {"max", max_photons}};
  p["absorbing_runs"] = {{"base_albedo_prime", grid.base_albedo_prime}, {"photon_factor", grid.base_photon_factor}};
  nlohmann::json per_g = {{"g", grid.g}};
  for (std::size_t b = 0; b < grid.runs(); ++b) {
    char label[32];
    std::snprintf(label, sizeof label, "base alpha' %g", grid.run_albedo_prime(b));
    per_g[b == grid.white() ? std::string("non-absorbing") : std::string(label)] = run_photons[b];
  }
  p["photons_per_node_fewest_over_eta"] = per_g;
  p["photons_total"] = photons;
  p["scatterings_total"] = interactions;
  p["monte_carlo_seconds"] = cpu_seconds;
  p["seed"] = seed;
  p["seed_rule"] =
      "chunk c of node (g index, eta index): s = splitmix(splitmix(splitmix(seed ^ g) ^ (eta << 20)) ^ c); "
      "absorbing run b: splitmix(s ^ ((b + 1) << 40))";
  p["adding_doubling_tolerance"] = "1e-5 alpha' absolute";
  p["totals"] =
      "multiple scattering from adding-doubling (its total minus exact single scattering) where its error estimate is "
      "within 2e-4 of the total and under a quarter of the Monte Carlo's standard error, else from the Monte Carlo";
  p["monte_carlo_totals"] = monte_carlo_totals;
  p["fine_totals"] = {{"total_eta", grid.total_eta},
                      {"source",
                       "the coarse totals interpolated in eta, times adding-doubling's ratio of its value "
                       "to its own interpolation from the coarse eta nodes (where its error estimate is "
                       "within 1 % at every eta of that g, alpha'; else the exact single-scattering total "
                       "at that eta plus the coarse multiple-scattering totals interpolated in eta)"},
                      {"single_scattering_plus_interpolation_g_albedo_rows", interpolated_rows}};
  p["worst_total_check_sigma"] = {{"value", worst_scale_sigma},
                                  {"at", worst_scale_at},
                                  {"meaning", "(Monte Carlo - exact) multiple-scattering total / its standard error"}};
  p["worst_single_scattering_check_sigma"] = {{"value", worst_ss_sigma}, {"at", worst_ss_at}};
  p["largest_lost_fraction"] = worst_lost;
  p["largest_radius_999"] = largest_r999;
  p["extrapolated_entries"] = extrapolated;
  {
    std::sort(near_slopes.begin(), near_slopes.end());
    p["near_field_continuation"] = {
        {"rule",
         "y_ms ~ r^s below the first radius measured within 30 %, s in [1, 2] holding the pooled tally there "
         "where that is measured within 30 %, else s = 2"},
        {"nodes", near_slopes.size()},
        {"slope_1", std::count(near_slopes.begin(), near_slopes.end(), 1.0)},
        {"slope_2", std::count(near_slopes.begin(), near_slopes.end(), 2.0)},
        {"median_slope", near_slopes.empty() ? 2.0 : near_slopes[near_slopes.size() / 2]}};
  }
  {
    std::sort(near_fit_chi2.begin(), near_fit_chi2.end());
    const double median = near_fit_chi2.empty() ? NAN : near_fit_chi2[near_fit_chi2.size() / 2];
    const double largest = near_fit_chi2.empty() ? NAN : near_fit_chi2.back();
    std::array<double, 3> mean_z{};
    for (std::size_t group = 0; group < 3; ++group)
      mean_z[group] = near_fit_z[group] / std::max(1.0, near_fit_groups[group]);
    p["near_field_fit"] = {
        {"rule",
         "where the first bin measured within 2 % is 8 or more bins out: ln y_ms a cubic in ln r over the bins "
         "up to it (30 at most), Poisson maximum likelihood; the fit alone up to 12 bins inside its last, blended "
         "in ln y into the smoothed bins over the next 6"},
        {"nodes", near_fit_chi2.size()},
        {"nodes_not_converged", near_fit_failed},
        {"median_chi2_per_dof", median},
        {"largest_chi2_per_dof", largest},
        {"bias_check_mean_z_bins_0_5_6_11_12_17", mean_z},
        {"bias_check_meaning",
         "per node, (fit - tally) / standard error with both summed over 6 bins (half a decade), averaged over the "
         "nodes; 0 within about 1 / sqrt(independent runs) when the fit adds no bias (nodes of one run share "
         "its photons)"}};
    std::cerr << "near-field fit: " << near_fit_chi2.size() << " nodes (" << near_fit_failed
              << " not converged), chi2/dof median " << median << ", largest " << largest << "; bias check mean z "
              << mean_z[0] << ", " << mean_z[1] << ", " << mean_z[2] << "\n";
  }
  p["radial_smoothing"] = {
      {"method",
       "multiple scattering: ln of each bin mean measured worse than 0.5 % replaced by a local quadratic fit over "
       "+-half bins (+-wide_half where worse than 3 %), over bins measured within 30 %"},
      {"half", smoothing_half},
      {"wide_half", wide_half},
      {"bias_check_chi2_per_bin", smoothing_bins > 0 ? smoothing_chi2 / smoothing_bins : NAN},
      {"bias_check_chi2_per_bin_wide", smoothing_bins > 0 ? wide_chi2 / smoothing_bins : NAN},
      {"bias_check_bins", smoothing_bins},
      {"bias_check_meaning",
       "well-sampled bins (within 0.5 %): (smoothed - raw)^2 / (se^2 (1 - L_k)), "
       "1 when the smoothing adds no bias"}};
  std::cerr << "radial smoothing +-" << smoothing_half << " (+-" << wide_half << ") bins: bias check chi2/bin "
            << smoothing_chi2 / std::max(1.0, smoothing_bins) << " (" << wide_chi2 / std::max(1.0, smoothing_bins)
            << ") over " << smoothing_bins << " bins\n";
  if (base) {
    nlohmann::json copied = nlohmann::json::array();
    for (std::size_t ei = 0; ei < grid.eta.size(); ++ei)
      for (std::size_t gi = 0; gi < grid.g.size(); ++gi)
        if (from_base(gi, ei)) copied.push_back({grid.g[gi], grid.eta[ei]});
    nlohmann::json rebuilt = nlohmann::json::array();
    for (std::size_t ei = 0; ei < grid.eta.size(); ++ei)
      for (std::size_t gi = 0; gi < grid.g.size(); ++gi)
        if (white_rebuilt(gi, ei)) rebuilt.push_back({grid.g[gi], grid.eta[ei]});
    p["base_table"] = {{"g_eta_nodes_copied", copied},
                       {"g_eta_nodes_non_absorbing_run_rebuilt", rebuilt},
                       {"rebuilt_meaning",
                        "at these copied nodes the albedo nodes above 0.99 (served by the non-absorbing run) come "
                        "from this build's state instead"},
                       {"albedo_prime_nodes_copied_from", base->albedo_prime.front()},
                       {"note",
                        "the Monte Carlo figures above are this build's state only (the other (g, eta) nodes, and "
                        "at the copied ones the albedo nodes below the base table's first); the base table's "
                        "provenance follows"},
                       {"provenance", nlohmann::json::parse(base->provenance)}};
  }
  table.provenance = p.dump();
  write_exact_table(table, out_path);
  std::cout << p.dump(2) << "\n";
  // The per-node check, for the record (data/exact/total_check.tsv; a build with --base writes only its own nodes:
  // append them).
  std::ofstream check(std::filesystem::path(out_path).parent_path() / "total_check.tsv");
  check << "# alpha'\tg\teta\tms_monte_carlo\tms_stderr\tms_adding_doubling(total - exact single scattering; null: "
           "not converged)\tadding_doubling_error_estimate\tms_total_used\n";
  for (const auto& row : scale_check) {
    for (std::size_t i = 0; i < row.size(); ++i) check << (i ? "\t" : "") << row[i].dump();
    check << '\n';
  }
  return 0;
}

}  // namespace

// A flag's number, or an error naming the flag and the text (std::stod alone says only "stod").
double number(const std::string& flag, const std::string& text, double lo, double hi) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(value >= lo && value <= hi)) {
    std::ostringstream message;
    message << flag << ": " << text << ": accepted range is " << lo << " to " << hi;
    throw std::invalid_argument(message.str());
  }
  return value;
}

int main(int argc, char** argv) {
  prepare_launched_process();  // under mpirun or srun, rank 0 alone speaks (docs/mpi.md)
  try {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || (args[0] != "run" && args[0] != "build")) {
      std::cerr
          << "usage: generate_exact_table run --state DIR [--photons N] [--chunk N] [--hours H] [--seed S]\n"
             "                                [--runs A,B,...] [--g-min G] [--g-max G] [--eta-min E] [--eta-max E]\n"
             "       generate_exact_table build --state DIR --out FILE [--seed S] [--base TABLE]\n";
      return 2;
    }
    std::string state, out, base;
    std::uint64_t photons = 1'000'000, chunk = 16384, seed = 20261201;
    double hours = 1e9;
    RunFocus focus;
    for (std::size_t i = 1; i + 1 < args.size(); i += 2) {
      if (args[i] == "--state")
        state = args[i + 1];
      else if (args[i] == "--out")
        out = args[i + 1];
      else if (args[i] == "--photons")
        photons = static_cast<std::uint64_t>(number("--photons", args[i + 1], 1, 1e15));
      else if (args[i] == "--chunk")
        chunk = static_cast<std::uint64_t>(number("--chunk", args[i + 1], 1, 1e12));
      else if (args[i] == "--hours")
        hours = number("--hours", args[i + 1], 0, 1e9);
      else if (args[i] == "--seed")
        seed = static_cast<std::uint64_t>(number("--seed", args[i + 1], 0, 9e15));
      else if (args[i] == "--runs") {
        std::stringstream list(args[i + 1]);
        const Grid grid;
        for (std::string item; std::getline(list, item, ',');) {
          const double run = number("--runs", item, 0, 1);
          bool known = run == 1;
          for (std::size_t b = 0; b < grid.base_albedo_prime.size(); ++b)
            known = known || run == grid.run_albedo_prime(b);
          if (!known) {
            std::ostringstream accepted;
            for (double a : grid.base_albedo_prime) accepted << a << ", ";
            throw std::invalid_argument("--runs: " + item + ": accepted are the base albedos " + accepted.str() +
                                        "and 1 (non-absorbing)");
          }
          focus.runs.push_back(run);
        }
      } else if (args[i] == "--g-min")
        focus.g_min = number("--g-min", args[i + 1], 0, 1);
      else if (args[i] == "--g-max")
        focus.g_max = number("--g-max", args[i + 1], 0, 1);
      else if (args[i] == "--eta-min")
        focus.eta_min = number("--eta-min", args[i + 1], 1, 10);
      else if (args[i] == "--eta-max")
        focus.eta_max = number("--eta-max", args[i + 1], 1, 10);
      else if (args[i] == "--base")
        base = args[i + 1];
      else
        throw std::invalid_argument("unknown option " + args[i]);
    }
    if (state.empty()) throw std::invalid_argument("--state DIR is required");
    if (args[0] == "run") return run(state, photons, chunk, hours, seed, focus);
    if (out.empty()) throw std::invalid_argument("--out FILE is required");
    if (ProcessGroup* group = launched_process_group(); group && group->rank() != 0) return 0;  // rank 0 builds
    return build(state, out, seed, base);
  } catch (const std::exception& e) {
    std::cerr << "generate_exact_table: " << e.what() << "\n";
    return 2;
  }
}
