// The photon tracer: the inner loop of the Monte Carlo solver. Eight photons in lanes, advanced
// together by branch-free vector code (SSE2, or AVX2 where the processor has it: same results),
// with their own xoshiro256+ streams; per interaction two 64-bit draws: 52 bits for the free path
// (one logarithm, fastmath.hpp), 32 for the Henyey-Greenstein cosine (closed-form inverse) and 32
// for the azimuth (cos and sin by polynomials, no rejection loop); interfaces, roulette and the
// ends of photons lane by lane. See fastmath.hpp for the accuracy of each piece.
#include "tracer.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string_view>

#include "bssrdf/fresnel.hpp"
#include "lane_tracer.hpp"

namespace bssrdf::mc {

ChannelGeometry make_geometry(const LayerStack& stack, std::size_t c) {
  ChannelGeometry geo;
  geo.n_above = stack.ambient_above;
  geo.n_below = stack.ambient_below;
  double z = 0;
  for (const Layer& layer : stack.layers) {
    LayerCoefficients l;
    l.z_top = z;
    z += layer.thickness;
    l.z_bottom = z;
    l.n = layer.n;
    l.sigma_t = layer.sigma_t(c);
    l.clear = layer.clear(c);
    l.inv_sigma_t = l.clear ? std::numeric_limits<double>::infinity() : 1.0 / l.sigma_t;
    l.albedo = l.clear ? 1.0 : layer.sigma_s[c] / l.sigma_t;
    l.one_minus_albedo = l.clear ? 0.0 : layer.sigma_a[c] / l.sigma_t;
    l.g = layer.g[c];
    l.hg_a = 1 + l.g * l.g;
    l.hg_b = 1 - l.g * l.g;
    l.hg_c = 1 - l.g;
    l.hg_2g = 2 * l.g;
    l.hg_inv_2g = l.g != 0 ? 1 / (2 * l.g) : 0;
    geo.layers.push_back(l);
  }
  // Specular reflection at normal incidence; with a clear top layer (a glass slide) MCML includes
  // its multiple reflections and launches the photon into the second layer. We do the same.
  const auto r_normal = [](double n1, double n2) { return fresnel_reflectance(1.0, n1 / n2); };
  const double n1 = stack.layers[0].n;
  double r1 = r_normal(stack.ambient_above, n1);
  if (geo.layers[0].clear && stack.layers.size() > 1) {
    const double r2 = r_normal(n1, stack.layers[1].n);
    geo.specular = r1 + (1 - r1) * (1 - r1) * r2 / (1 - r1 * r2);
    geo.start_layer = 1;
    geo.start_z = geo.layers[1].z_top;
  } else {
    geo.specular = r1;
  }
  return geo;
}

RadialBinning::RadialBinning(BinSpacing spacing_, std::size_t bins_, double r_min_, double r_max_)
    : spacing(spacing_), bins(bins_), r_min(r_min_), r_max(r_max_) {
  inner.resize(bins);
  outer.resize(bins);
  radius.resize(bins);
  if (spacing == BinSpacing::linear) {
    const double width = r_max / static_cast<double>(bins);
    inv_width = 1 / width;
    for (std::size_t i = 0; i < bins; ++i) {
      inner[i] = width * static_cast<double>(i);
      outer[i] = i + 1 == bins ? r_max : width * static_cast<double>(i + 1);
      radius[i] = 0.5 * (inner[i] + outer[i]);
    }
  } else {
    const double step = std::log(r_max / r_min) / static_cast<double>(bins - 1);
    inv_log_step = 1 / step;
    inner[0] = 0;
    outer[0] = r_min;
    radius[0] = 0.5 * r_min;
    for (std::size_t i = 1; i < bins; ++i) {
      inner[i] = r_min * std::exp(step * static_cast<double>(i - 1));
      outer[i] = i + 1 == bins ? r_max : r_min * std::exp(step * static_cast<double>(i));
      radius[i] = std::sqrt(inner[i] * outer[i]);
    }
  }
}

void BatchTally::reset(std::size_t radial_bins, bool transmission, std::size_t depth_bins) {
  photons = interactions = 0;
  std::fill(std::begin(sum), std::end(sum), 0.0);
  std::fill(std::begin(sum_sq), std::end(sum_sq), 0.0);
  lost = r_beyond = t_beyond = 0;
  r_sum.assign(radial_bins, 0.0);
  r_sq.assign(radial_bins, 0.0);
  t_sum.assign(transmission ? radial_bins : 0, 0.0);
  t_sq.assign(transmission ? radial_bins : 0, 0.0);
  a_sum.assign(depth_bins, 0.0);
  reflected.clear();
}

namespace {

// The same kernel compiled four times, chosen at run time: SSE2 with separate multiply and add
// (every x86-64), SSE2 with FMA, AVX2 with FMA (four lanes per register), and AVX-512 (all eight
// lanes in one register, tracer_avx512.cpp: half the vector instructions; 1.1-1.5 times the photons
// per second of AVX2 on an AMD Zen 5, docs/reference.md). The three fused kernels do the same IEEE operations on every
// lane (the vector width changes nothing but the speed), so their results are bitwise identical on
// every machine with FMA; the unfused one rounds each a b + c twice.
using Kernel = void (*)(const ChannelGeometry&, const TraceSettings&, Rng&, std::uint64_t, BatchTally&);
template <bool kAnalog>
void trace_sse2(const ChannelGeometry& geo, const TraceSettings& settings, Rng& rng, std::uint64_t photons,
                BatchTally& tally) {
  trace_lanes<kAnalog, Sse2>(geo, settings, rng, photons, tally);
}
#if defined(__x86_64__) || defined(__i386__)
template <bool kAnalog>
__attribute__((target("fma"))) void trace_sse2_fma(const ChannelGeometry& geo, const TraceSettings& settings,
                                                   Rng& rng, std::uint64_t photons, BatchTally& tally) {
  trace_lanes<kAnalog, Sse2Fma>(geo, settings, rng, photons, tally);
}
template <bool kAnalog>
__attribute__((target("avx2,fma"))) void trace_avx2(const ChannelGeometry& geo, const TraceSettings& settings,
                                                    Rng& rng, std::uint64_t photons, BatchTally& tally) {
  trace_lanes<kAnalog, Avx2>(geo, settings, rng, photons, tally);
}

// The level BSSRDF_MC_SIMD asks for (to measure a path, or to reproduce a machine without FMA).
SimdLevel simd_from_environment() {
  static const SimdLevel level = [] {
    const char* value = std::getenv("BSSRDF_MC_SIMD");
    const std::string_view forced = value ? value : "";
    return forced == "avx2"    ? SimdLevel::avx2
           : forced == "sse2"  ? SimdLevel::sse2
           : forced == "nofma" ? SimdLevel::unfused
                               : SimdLevel::best;
  }();
  return level;
}
#endif

}  // namespace

SimdLevel kernel_for(SimdLevel requested) {
#if defined(__x86_64__) || defined(__i386__)
  static const bool fma = __builtin_cpu_supports("fma"), avx2 = fma && __builtin_cpu_supports("avx2"),
                    avx512 = avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                           __builtin_cpu_supports("avx512dq");
  const SimdLevel level = std::max(requested, simd_from_environment());  // the more restricted
  if (level == SimdLevel::best && avx512) return SimdLevel::best;
  if (level <= SimdLevel::avx2 && avx2) return SimdLevel::avx2;
  if (level <= SimdLevel::sse2 && fma) return SimdLevel::sse2;
#else
  (void)requested;
#endif
  return SimdLevel::unfused;
}

void trace_batch(const ChannelGeometry& geo, const TraceSettings& settings, Rng& rng, std::uint64_t photons,
                 BatchTally& tally) {
  const bool analog = settings.absorption == AbsorptionEstimator::analog;
  Kernel kernel = analog ? trace_sse2<true> : trace_sse2<false>;
#if defined(__x86_64__) || defined(__i386__)
  switch (kernel_for(settings.simd)) {
    case SimdLevel::best:
      kernel = analog ? trace_avx512<true> : trace_avx512<false>;
      break;
    case SimdLevel::avx2:
      kernel = analog ? trace_avx2<true> : trace_avx2<false>;
      break;
    case SimdLevel::sse2:
      kernel = analog ? trace_sse2_fma<true> : trace_sse2_fma<false>;
      break;
    case SimdLevel::unfused:
      break;
  }
#endif
  kernel(geo, settings, rng, photons, tally);
}

}  // namespace bssrdf::mc
