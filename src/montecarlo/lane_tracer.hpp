// Internal to the Monte Carlo solver: the photon tracer's loop, included by the translation units
// that compile it for an instruction set (tracer.cpp: SSE2, SSE2 with FMA, AVX2; tracer_avx512.cpp:
// AVX-512). Everything here has internal linkage, so each unit keeps its own copy, compiled for its
// own instructions: no copy made for AVX-512 can stand in for another unit's.
// A unit that compiles it under `#pragma GCC target` must include every header below first (the
// pragma then reaches only this file's functions, not the standard library's).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>

#include "bssrdf/check.hpp"
#include "bssrdf/fresnel.hpp"
#include "fastmath.hpp"
#include "tracer.hpp"

namespace bssrdf::mc {
namespace {

// Photons traced side by side on one thread, in lanes (structure of arrays). Each photon's step is
// one long dependency chain (the new direction needs a division and a square root of the old
// one), so a lone photon leaves the processor idle; kLanes independent photons advanced together
// fill it, and the common case (an interaction inside the layer) is straight-line code over the
// lanes that the compiler vectorises (SSE2 suffices). Rare events (interfaces, roulette, the end
// of a photon) are handled lane by lane afterwards. Each lane draws from its own xoshiro256+
// stream, seeded from the batch's generator, and photons are handed to lanes in a fixed order, so
// the result is still a function of (seed, channel, batch) only.
constexpr int kLanes = 8;

struct Xoshiro4 {  // kLanes xoshiro256+ generators, structure of arrays
  alignas(64) std::uint64_t s0[kLanes], s1[kLanes], s2[kLanes], s3[kLanes];

  explicit Xoshiro4(Rng& batch) {
    std::uint64_t sm = batch.next();
    for (int j = 0; j < kLanes; ++j) {
      s0[j] = splitmix64(sm);
      s1[j] = splitmix64(sm);
      s2[j] = splitmix64(sm);
      s3[j] = splitmix64(sm);
    }
  }
  static std::uint64_t step(std::uint64_t& a, std::uint64_t& b, std::uint64_t& c, std::uint64_t& d) {
    const std::uint64_t result = a + d;
    const std::uint64_t t = b << 17;
    c ^= a;
    d ^= b;
    b ^= c;
    a ^= d;
    c ^= t;
    d = (d << 45) | (d >> 19);
    return result;
  }
  // One draw of every lane, as vectors of U (the same steps on each lane as step()): written out
  // because the compiler does not vectorise the scalar loop in every kernel (not for AVX-512).
  template <class U>
  [[gnu::always_inline]] void all(std::uint64_t* out) {
    constexpr int width = sizeof(U) / sizeof(std::uint64_t);
    for (int g = 0; g < kLanes; g += width) {
      U a = load<U>(s0 + g), b = load<U>(s1 + g), c = load<U>(s2 + g), d = load<U>(s3 + g);
      store(out + g, a + d);
      const U t = b << 17;
      c ^= a;
      d ^= b;
      b ^= c;
      a ^= d;
      c ^= t;
      d = (d << 45) | (d >> 19);
      store(s0 + g, a);
      store(s1 + g, b);
      store(s2 + g, c);
      store(s3 + g, d);
    }
  }
  std::uint64_t one(int j) { return step(s0[j], s1[j], s2[j], s3[j]); }
  double uniform(int j) { return static_cast<double>(one(j) >> 11) * 0x1.0p-53; }  // [0, 1), 53 bits
};

// The lanes: one photon each, with the constants of its current layer.
struct Lanes {
  alignas(64) double x[kLanes], y[kLanes], z[kLanes], ux[kLanes], uy[kLanes], uz[kLanes], w[kLanes];
  alignas(64) double tau[kLanes];       // remaining optical depth of the current free path; <= 0: draw
  alignas(64) double absorbed[kLanes];  // weight the photon deposited
  alignas(64) double scatterings[kLanes];
  // Current layer's constants.
  alignas(64) double z_top[kLanes], z_bottom[kLanes], inv_sigma_t[kLanes], absorb[kLanes];
  alignas(64) double hg_a[kLanes], hg_b[kLanes], hg_c[kLanes], hg_2g[kLanes], hg_inv_2g[kLanes], albedo[kLanes];
  // Per step: what happened (set by the vector pass, read by the lane-by-lane pass).
  alignas(64) double dw[kLanes];
  alignas(64) std::int64_t inside[kLanes], absorbed_event[kLanes];
  int layer[kLanes];
  bool active[kLanes];
};

// One batch traced in lanes: the batch's constants, the lanes and the random numbers of a step, with
// the steps of trace_lanes as named functions. Every function is always inlined, so the SSE2 and AVX2
// kernels (target attributes) each compile the whole loop as one function, as before it was split.
template <bool kAnalog, class V>
struct LaneTracer {
  using D = typename V::D;
  using U = typename V::U;
  using I = typename V::I;
  using Madd = typename V::Madd;
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  const ChannelGeometry& geo;
  const TraceSettings& settings;
  BatchTally& tally;
  const LayerCoefficients* const layers;
  const int layer_count;
  const RadialBinning& binning;
  const std::uint64_t photons;
  // Analog absorption never lowers the weight: no roulette.
  const double threshold, survival, inv_survival;
  const std::size_t depth_bins;
  const double inv_dz;
  const double max_interactions;  // exact below 2^53
  const double start_weight;

  Xoshiro4 rng;
  Lanes L;
  std::uint64_t interactions = 0, launched = 0;
  int active = 0;
  // One step's random bits, and what draw_steps derives from them.
  alignas(64) std::uint64_t r_path[kLanes], r_angles[kLanes], r_absorb[kLanes];
  alignas(64) double drawn_tau[kLanes], cos_theta[kLanes], cos_phi[kLanes], sin_phi[kLanes];

  [[gnu::always_inline]] LaneTracer(const ChannelGeometry& geo_, const TraceSettings& settings_, Rng& batch_rng,
                                    std::uint64_t photons_, BatchTally& tally_)
      : geo(geo_),
        settings(settings_),
        tally(tally_),
        layers(geo_.layers.data()),
        layer_count(static_cast<int>(geo_.layers.size())),
        binning(*settings_.binning),
        photons(photons_),
        threshold(kAnalog ? -1.0 : settings_.roulette_threshold),
        survival(settings_.roulette_survival),
        inv_survival(1 / settings_.roulette_survival),
        depth_bins(settings_.depth_bins),
        inv_dz(settings_.inv_depth_width),
        max_interactions(static_cast<double>(settings_.max_interactions)),
        start_weight(1 - geo_.specular),
        rng(batch_rng) {}

  [[gnu::always_inline]] void enter_layer(int j, int index) {
    const LayerCoefficients& l = layers[index];
    L.layer[j] = index;
    L.z_top[j] = l.z_top;
    L.z_bottom[j] = l.z_bottom;
    L.inv_sigma_t[j] = l.inv_sigma_t;
    L.absorb[j] = kAnalog ? 0.0 : l.one_minus_albedo;
    L.albedo[j] = l.albedo;
    L.hg_a[j] = l.hg_a;
    L.hg_b[j] = l.hg_b;
    L.hg_c[j] = l.hg_c;
    L.hg_2g[j] = l.hg_2g;
    L.hg_inv_2g[j] = l.hg_inv_2g;
  }

  [[gnu::always_inline]] void launch(int j) {
    L.x[j] = L.y[j] = 0;
    L.z[j] = geo.start_z;
    L.ux[j] = L.uy[j] = 0;
    L.uz[j] = 1;
    L.w[j] = start_weight;
    L.tau[j] = 0;
    L.absorbed[j] = 0;
    L.scatterings[j] = 0;
    enter_layer(j, static_cast<int>(geo.start_layer));
    ++launched;
  }

  [[gnu::always_inline]] void deposit(double z, double dw) {
    const auto i = static_cast<std::size_t>(z * inv_dz);
    if (i < depth_bins) tally.a_sum[i] += dw;
  }

  // The photon in lane j leaves through the top (reflected) or the bottom (transmitted): tallied once.
  [[gnu::always_inline]] void escape(int j, bool top) {
    const double r = std::sqrt(L.x[j] * L.x[j] + L.y[j] * L.y[j]);
    const std::size_t bin = binning.index(r);
    const double w = L.w[j], w2 = w * w, scatterings = L.scatterings[j];
    if (top) {
      if (settings.record_reflected)
        tally.reflected.push_back({r, static_cast<std::uint32_t>(scatterings), static_cast<float>(w)});
      tally.sum[kR] += w;
      tally.sum_sq[kR] += w2;
      if (scatterings == 1) {
        tally.sum[kRSingle] += w;
        tally.sum_sq[kRSingle] += w2;
      } else if (scatterings == 0) {
        tally.sum[kRUnscattered] += w;
        tally.sum_sq[kRUnscattered] += w2;
      }
      if (bin < binning.bins) {
        tally.r_sum[bin] += w;
        tally.r_sq[bin] += w2;
      } else {
        tally.r_beyond += w;
      }
    } else {
      tally.sum[kT] += w;
      tally.sum_sq[kT] += w2;
      if (scatterings == 0) {
        tally.sum[kTUnscattered] += w;
        tally.sum_sq[kTUnscattered] += w2;
      }
      if (!tally.t_sum.empty() && bin < binning.bins) {
        tally.t_sum[bin] += w;
        tally.t_sq[bin] += w2;
      } else {
        tally.t_beyond += w;
      }
    }
  }

  // The photon in lane j has ended: tally it, then launch the next one or retire the lane.
  [[gnu::always_inline]] void finish(int j) {
    interactions += static_cast<std::uint64_t>(L.scatterings[j]);
    tally.sum[kAbsorbed] += L.absorbed[j];
    tally.sum_sq[kAbsorbed] += L.absorbed[j] * L.absorbed[j];
    if (launched < photons) {
      launch(j);
    } else {
      L.active[j] = false;
      --active;
      launch(j);  // a harmless state for the vector pass, never tallied; no absorption (no denormals)
      L.absorb[j] = 0;
      --launched;
    }
  }

  // The free path of lane j (optical depth L.tau[j]) reaches an interface of its layer: move there
  // and reflect, refract or leave. Returns false when the photon has ended.
  [[gnu::always_inline]] bool cross(int j) {
    BSSRDF_DCHECK(L.layer[j] >= 0 && L.layer[j] < layer_count && L.w[j] >= 0);  // a live lane: in a layer, with weight
    const LayerCoefficients& l = layers[L.layer[j]];
    const double uz = L.uz[j];
    const double to_boundary = uz > 0 ? (l.z_bottom - L.z[j]) / uz : uz < 0 ? (l.z_top - L.z[j]) / uz : kInfinity;
    if (to_boundary == kInfinity) {  // parallel to the interfaces in a clear layer: never arrives
      tally.lost += L.w[j];
      return false;
    }
    L.x[j] += to_boundary * L.ux[j];
    L.y[j] += to_boundary * L.uy[j];
    if (!l.clear) L.tau[j] -= to_boundary * l.sigma_t;
    const bool down = uz > 0;
    L.z[j] = down ? l.z_bottom : l.z_top;
    const int next = down ? L.layer[j] + 1 : L.layer[j] - 1;
    const double n_next = next < 0 ? geo.n_above : next >= layer_count ? geo.n_below : layers[next].n;
    if (n_next != l.n) {
      const double ratio = l.n / n_next;
      const double ci = std::abs(uz);
      const double reflect = fresnel_reflectance(ci, ratio);  // 1 under total internal reflection
      if (reflect >= 1 || rng.uniform(j) < reflect) {
        L.uz[j] = -uz;
        return true;
      }
      const double cos_t = std::sqrt(1 - ratio * ratio * (1 - ci * ci));
      L.ux[j] *= ratio;
      L.uy[j] *= ratio;
      L.uz[j] = down ? cos_t : -cos_t;
    }
    if (next < 0 || next >= layer_count) {
      escape(j, next < 0);  // leaves the stack: tallied once, the photon ends here
      return false;
    }
    enter_layer(j, next);
    return true;
  }

  // The first photon of every lane; lanes beyond the batch's photons start retired.
  [[gnu::always_inline]] void launch_lanes() {
    for (int j = 0; j < kLanes; ++j) {
      launch(j);
      L.active[j] = launched <= photons;
      if (L.active[j]) {
        ++active;
      } else {
        L.absorb[j] = 0;
        --launched;
      }
    }
  }

  // Vector pass, part 1, independent of the photons' state (so the processor can run it ahead): the
  // free path's optical depth, the polar cosine and the azimuth of every lane, from the random bits.
  // The divisions of the logarithm and of the Henyey-Greenstein inverse share one reciprocal of
  // the product of their denominators (2 + f in [1.7, 2.5] and 1 - g + 2 g xi >= 1 - |g| > 0):
  // each quotient within ~3 ulp of the correctly rounded one; in the logarithm that moves the
  // result by a small fraction of an ulp (see log_finish), in the cosine by a few ulp.
  // Bits: the free path takes the top 52 of one draw; the cosine the top 32 of the other and the
  // azimuth its low 32 (xoshiro256+'s weak lowest bits, of low linear complexity, only pick among
  // cells 2^-32 of a turn wide; the quadrant comes from bits 30-31).
  [[gnu::always_inline]] void draw_steps() {
    rng.template all<U>(r_path);
    rng.template all<U>(r_angles);
    if constexpr (kAnalog) rng.template all<U>(r_absorb);
    // V::width lanes at a time as vectors (SSE2 or AVX2), both sides of every choice computed,
    // then selected.
    for (int g = 0; g < kLanes; g += V::width) {
      const U rp = load<U>(r_path + g), ra = load<U>(r_angles + g);
      const D xi = uniform_mid32(ra >> 32);
      const D hg_2g = load<D>(L.hg_2g + g);
      const LogReduced<D> reduced = log_reduce(uniform_open0_52(rp));
      const D den_log = 2.0 + reduced.f;
      const D den_hg = Madd::madd(hg_2g, xi, load<D>(L.hg_c + g));
      const D reciprocal = 1.0 / (den_log * den_hg);
      store(drawn_tau + g, -log_finish<Madd>(reduced, reduced.f * (den_hg * reciprocal)));
      const D t = load<D>(L.hg_b + g) * (den_log * reciprocal);
      D ct = Madd::madd(-t, t, load<D>(L.hg_a + g)) * load<D>(L.hg_inv_2g + g);
      ct = ct < -1.0 ? -1.0 : ct;
      ct = ct > 1.0 ? 1.0 : ct;
      ct = hg_2g == 0 ? 2 * xi - 1 : ct;
      store(cos_theta + g, ct);
      D cp, sp;
      azimuth_cos_sin<Madd>(ra, cp, sp);
      store(cos_phi + g, cp);
      store(sin_phi + g, sp);
    }
  }

  // Vector pass, part 2: every lane takes its free path; where it ends inside the layer the photon
  // interacts (absorption, then the new direction). Lanes whose path leaves the layer only keep the
  // optical depth drawn. Returns whether any lane needs the lane-by-lane pass.
  [[gnu::always_inline]] bool move_absorb_turn() {
    I any_slow = {};
    for (int g = 0; g < kLanes; g += V::width) {
      const D tau_in = load<D>(L.tau + g);
      const D ux = load<D>(L.ux + g), uy = load<D>(L.uy + g), uz = load<D>(L.uz + g);
      const D z = load<D>(L.z + g);
      const D tau = tau_in > 0 ? tau_in : load<D>(drawn_tau + g);
      const D s = tau * load<D>(L.inv_sigma_t + g);  // infinite in a clear layer
      const D z_end = Madd::madd(s, uz, z);
      const I inside = (z_end < load<D>(L.z_bottom + g)) & (z_end > load<D>(L.z_top + g));
      const D ct = load<D>(cos_theta + g), cp = load<D>(cos_phi + g), sp = load<D>(sin_phi + g);
      // MCML's rotation; along the z axis the frame is (x, y, z) itself. k = sin(theta)/sqrt(1-uz^2).
      const D one_minus_uz2 = Madd::madd(-uz, uz, 1.0);
      const I pole = one_minus_uz2 < 1e-12;
      const D k = sqrt_of(Madd::madd(-ct, ct, 1.0) / (pole ? 1.0 : one_minus_uz2));
      const D nux = pole ? k * cp : Madd::madd(k, Madd::madd(ux * uz, cp, -(uy * sp)), ux * ct);
      const D nuy = pole ? k * sp : Madd::madd(k, Madd::madd(uy * uz, cp, ux * sp), uy * ct);
      const D nuz = pole ? (uz > 0 ? ct : -ct) : Madd::madd(-k * one_minus_uz2, cp, uz * ct);
      const D w = load<D>(L.w + g);
      const D dw = inside ? w * load<D>(L.absorb + g) : 0.0;
      const D x = load<D>(L.x + g), y = load<D>(L.y + g);
      store(L.x + g, inside ? Madd::madd(s, ux, x) : x);
      store(L.y + g, inside ? Madd::madd(s, uy, y) : y);
      store(L.z + g, inside ? z_end : z);
      store(L.tau + g, inside ? 0.0 : tau);
      store(L.ux + g, inside ? nux : ux);
      store(L.uy + g, inside ? nuy : uy);
      store(L.uz + g, inside ? nuz : uz);
      const D w_new = w - dw;
      store(L.w + g, w_new);
      store(L.absorbed + g, load<D>(L.absorbed + g) + dw);
      store(L.dw + g, dw);
      const D scatterings = load<D>(L.scatterings + g) + (inside ? 1.0 : 0.0);
      store(L.scatterings + g, scatterings);
      store(L.inside + g, inside);
      I slow = ~inside | (w_new < threshold) | (scatterings >= max_interactions);
      if constexpr (kAnalog) {
        const I absorbed_event = inside & (uniform_open0_52(load<U>(r_absorb + g)) > load<D>(L.albedo + g));
        store(L.absorbed_event + g, absorbed_event);
        slow |= absorbed_event;
      }
      any_slow |= slow;
    }
    std::int64_t any = 0;
    for (int i = 0; i < V::width; ++i) any |= any_slow[i];
    return any != 0;
  }

  // Implicit capture: the weight each interacting lane deposited, by depth.
  [[gnu::always_inline]] void deposit_interactions() {
    for (int j = 0; j < kLanes; ++j)
      if (L.inside[j] && L.active[j]) deposit(L.z[j], L.dw[j]);
  }

  // Lane-by-lane pass: interfaces, absorption (analog), roulette, the end of photons.
  [[gnu::always_inline]] void rare_events() {
    for (int j = 0; j < kLanes; ++j) {
      if (!L.active[j]) continue;
      if (!L.inside[j]) {
        if (!cross(j)) finish(j);
        continue;
      }
      if constexpr (kAnalog) {
        if (L.absorbed_event[j]) {
          L.absorbed[j] += L.w[j];
          if (depth_bins) deposit(L.z[j], L.w[j]);
          finish(j);
          continue;
        }
      }
      if (L.w[j] < threshold) {  // Russian roulette
        if (rng.uniform(j) < survival) {
          L.w[j] *= inv_survival;
        } else {
          finish(j);
          continue;
        }
      }
      if (L.scatterings[j] >= max_interactions) {
        tally.lost += L.w[j];
        finish(j);
      }
    }
  }
};

template <bool kAnalog, class V>
[[gnu::always_inline]] inline void trace_lanes(const ChannelGeometry& geo, const TraceSettings& settings,
                                               Rng& batch_rng, std::uint64_t photons, BatchTally& tally) {
  LaneTracer<kAnalog, V> t(geo, settings, batch_rng, photons, tally);
  t.launch_lanes();
  while (t.active > 0) {
    t.draw_steps();
    const bool slow = t.move_absorb_turn();
    if (t.depth_bins && !kAnalog) t.deposit_interactions();
    if (slow) t.rare_events();
  }
  tally.photons += photons;
  tally.interactions += t.interactions;
}

}  // namespace

}  // namespace bssrdf::mc
