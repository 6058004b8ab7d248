// Internal to the Monte Carlo solver: the random number generator, one channel's geometry in the
// form the inner loop wants, the per-batch tallies and the photon tracer itself.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/montecarlo.hpp"

namespace bssrdf::mc {

inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// xoshiro256+ (Blackman & Vigna), 53-bit doubles from the top bits. Seeded from (seed, stream,
// batch) through splitmix64, so every batch has its own stream whatever thread runs it; the
// tracer seeds its lanes' generators (the same algorithm) from it.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t batch) {
    std::uint64_t sm = seed;
    const std::uint64_t a = splitmix64(sm);
    sm = a ^ (stream * 0xD1B54A32D192ED03ull);
    const std::uint64_t b = splitmix64(sm);
    sm = b ^ (batch * 0xABC98388FB8FAC03ull) ^ 0x8CB92BA72F3D8DD7ull;
    for (auto& s : s_) s = splitmix64(sm);
  }
  std::uint64_t next() {
    const std::uint64_t result = s_[0] + s_[3];
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = (s_[3] << 45) | (s_[3] >> 19);
    return result;
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }              // [0, 1)
  double uniform_open0() { return static_cast<double>((next() >> 11) + 1) * 0x1.0p-53; }  // (0, 1]

 private:
  std::uint64_t s_[4];
};

// One layer of one channel, with the constants the inner loop uses.
struct LayerCoefficients {
  double z_top = 0, z_bottom = 0;  // mm
  double n = 1;
  double sigma_t = 0, inv_sigma_t = 0, albedo = 0, one_minus_albedo = 0;
  double g = 0, hg_a = 1, hg_b = 1, hg_c = 1, hg_2g = 0, hg_inv_2g = 0;  // HG sampling constants
  bool clear = false;
};

struct ChannelGeometry {
  std::vector<LayerCoefficients> layers;
  double n_above = 1, n_below = 1;
  double specular = 0;  // R_sp; photons start with weight 1 - R_sp
  std::size_t start_layer = 0;
  double start_z = 0;
};

ChannelGeometry make_geometry(const LayerStack& stack, std::size_t channel);

struct RadialBinning {
  BinSpacing spacing = BinSpacing::linear;
  std::size_t bins = 0;
  double r_min = 0, r_max = 0, inv_width = 0, inv_log_step = 0;
  std::vector<double> inner, outer, radius;  // edges and representative radius, mm

  RadialBinning(BinSpacing spacing, std::size_t bins, double r_min, double r_max);
  // Bin of radius r, or `bins` when r >= r_max.
  std::size_t index(double r) const {
    double f;
    if (spacing == BinSpacing::linear) {
      f = r * inv_width;
    } else {
      if (r < r_min) return 0;
      f = 1.0 + std::log(r / r_min) * inv_log_step;
    }
    return f < static_cast<double>(bins) ? static_cast<std::size_t>(f) : bins;
  }
};

// Totals tallied per photon (sum and sum of squares give exact per-photon variances).
enum Total : int { kR = 0, kRSingle, kRUnscattered, kT, kTUnscattered, kAbsorbed, kTotals };

struct BatchTally {
  std::uint64_t photons = 0, interactions = 0;
  double sum[kTotals] = {}, sum_sq[kTotals] = {};
  double lost = 0, r_beyond = 0, t_beyond = 0;
  std::vector<double> r_sum, r_sq, t_sum, t_sq, a_sum;
  std::vector<ReflectedPhoton> reflected;  // TraceSettings::record_reflected

  void reset(std::size_t radial_bins, bool transmission, std::size_t depth_bins);
};

// Instruction set of the tracer's vector pass, from the fastest: best (AVX-512F/VL/DQ, all eight lanes
// in one register, where the processor has it), avx2 (AVX2 with FMA), sse2 (SSE2, with FMA where the
// processor has it), unfused (SSE2 without FMA, as on processors that lack it). A level asks for at
// most that kernel; the processor and BSSRDF_MC_SIMD=avx2|sse2|nofma in the environment may restrict
// it further. The fused kernels give bitwise identical results; the unfused one the same statistics,
// other bits (each a b + c rounded twice).
enum class SimdLevel { best, avx2, sse2, unfused };
// The kernel trace_batch runs for `requested` on this processor and in this environment.
SimdLevel kernel_for(SimdLevel requested);

struct TraceSettings {
  const RadialBinning* binning = nullptr;
  bool transmission_bins = false;
  std::size_t depth_bins = 0;
  double inv_depth_width = 0;
  AbsorptionEstimator absorption = AbsorptionEstimator::implicit_capture;
  double roulette_threshold = 1e-4, roulette_survival = 0.1;
  std::uint64_t max_interactions = 0;
  bool record_reflected = false;
  SimdLevel simd = SimdLevel::best;
};

#if defined(__x86_64__) || defined(__i386__)
// The kernel with eight lanes in one AVX-512 register (tracer_avx512.cpp, SimdLevel::best); only on
// processors with AVX-512F, VL and DQ.
template <bool kAnalog>
void trace_avx512(const ChannelGeometry& geometry, const TraceSettings& settings, Rng& rng, std::uint64_t photons,
                  BatchTally& tally);
#endif

void trace_batch(const ChannelGeometry& geometry, const TraceSettings& settings, Rng& rng, std::uint64_t photons,
                 BatchTally& tally);

}  // namespace bssrdf::mc
