// The photon tracer: the inner loop of the Monte Carlo solver. Kept lean on purpose: no
// trigonometry (Henyey-Greenstein cosine by its closed-form inverse, azimuth by the polar method),
// one logarithm per free path, one generator per batch, the photon state in locals.
#include "tracer.hpp"

#include <algorithm>
#include <limits>

#include "bssrdf/fresnel.hpp"

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
}

namespace {

// One photon in flight.
struct Photon {
  double x, y, z, ux, uy, uz, w;
  double tau;       // remaining optical depth of the current free path; <= 0: draw a new one
  double absorbed;  // weight this photon deposited
  std::uint64_t scatterings;
  int layer;
  bool active;
};

// Photons traced side by side on one thread. Each photon's step is one long dependency chain
// (logarithm, division, square root); interleaving independent photons lets the processor overlap
// them. The lanes are visited in a fixed order and draw from the batch's one generator, so the
// result is still a function of (seed, batch) only.
constexpr int kLanes = 4;

}  // namespace

void trace_batch(const ChannelGeometry& geo, const TraceSettings& settings, Rng& rng, std::uint64_t photons,
                 BatchTally& tally) {
  const LayerCoefficients* const layers = geo.layers.data();
  const int layer_count = static_cast<int>(geo.layers.size());
  const RadialBinning& binning = *settings.binning;
  const bool analog = settings.absorption == AbsorptionEstimator::analog;
  const double threshold = settings.roulette_threshold;
  const double survival = settings.roulette_survival, inv_survival = 1 / survival;
  const std::size_t depth_bins = settings.depth_bins;
  const double inv_dz = settings.inv_depth_width;
  const std::uint64_t max_interactions = settings.max_interactions;
  const double start_weight = 1 - geo.specular;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();

  std::uint64_t interactions = 0, launched = 0;
  const auto launch = [&](Photon& p) {
    p = Photon{0, 0, geo.start_z, 0, 0, 1, start_weight, 0, 0, 0, static_cast<int>(geo.start_layer), true};
    ++launched;
  };
  const auto deposit = [&](double z, double dw) {
    if (depth_bins) {
      const auto i = static_cast<std::size_t>(z * inv_dz);
      if (i < depth_bins) tally.a_sum[i] += dw;
    }
  };
  const auto escape = [&](const Photon& p, bool top) {
    const double r = std::sqrt(p.x * p.x + p.y * p.y);
    const std::size_t bin = binning.index(r);
    const double w = p.w, w2 = w * w;
    if (top) {
      tally.sum[kR] += w;
      tally.sum_sq[kR] += w2;
      if (p.scatterings == 1) {
        tally.sum[kRSingle] += w;
        tally.sum_sq[kRSingle] += w2;
      } else if (p.scatterings == 0) {
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
      if (p.scatterings == 0) {
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
  };

  // Advances photon p by one event (an interaction, or reaching an interface). Returns false when
  // the photon has ended (escaped, absorbed, lost to roulette or to max_interactions).
  const auto step = [&](Photon& p) -> bool {
    const LayerCoefficients& l = layers[p.layer];
    if (p.tau <= 0) p.tau = -std::log(rng.uniform_open0());
    const double s = p.tau * l.inv_sigma_t;  // infinite in a clear layer
    const double z_end = p.z + s * p.uz;
    if (z_end < l.z_bottom && z_end > l.z_top) {
      // Interaction inside the layer (no division needed to know it).
      p.x += s * p.ux;
      p.y += s * p.uy;
      p.z = z_end;
      p.tau = 0;
      ++p.scatterings;
      if (analog) {
        if (rng.uniform() >= l.albedo) {
          p.absorbed += p.w;
          deposit(p.z, p.w);
          return false;
        }
      } else {
        const double dw = p.w * l.one_minus_albedo;
        p.w -= dw;
        p.absorbed += dw;
        deposit(p.z, dw);
        if (p.w < threshold) {
          if (rng.uniform() < survival) {
            p.w *= inv_survival;
          } else {
            return false;
          }
        }
      }
      if (p.scatterings >= max_interactions) {
        tally.lost += p.w;
        return false;
      }
      // Henyey-Greenstein polar cosine by its closed-form inverse (no pow, no trigonometry).
      const double xi = rng.uniform();
      double ct;
      if (l.g == 0) {
        ct = 2 * xi - 1;
      } else {
        const double t = l.hg_b / (l.hg_c + l.hg_2g * xi);
        ct = std::clamp((l.hg_a - t * t) * l.hg_inv_2g, -1.0, 1.0);
      }
      // Uniform azimuth by the polar method: for (a, b) uniform in the unit disc, with q = a^2 + b^2,
      // (cos phi, sin phi) = (a^2 - b^2, 2ab) / q exactly, phi uniform.
      double a, b, q;
      do {
        a = 2 * rng.uniform() - 1;
        b = 2 * rng.uniform() - 1;
        q = a * a + b * b;
      } while (q > 1 || q == 0);
      const double c2 = a * a - b * b, s2 = 2 * a * b;  // q cos phi, q sin phi
      const double ux = p.ux, uy = p.uy, uz = p.uz;
      const double one_minus_uz2 = 1 - uz * uz;
      const double one_minus_ct2 = 1 - ct * ct;
      if (one_minus_uz2 < 1e-12) {
        // Along the z axis: the rotation frame is (x, y, z) itself.
        const double k = std::sqrt(one_minus_ct2) / q;
        p.ux = k * c2;
        p.uy = k * s2;
        p.uz = uz > 0 ? ct : -ct;
      } else {
        // MCML's rotation with sin(theta)/sqrt(1 - uz^2) and the 1/q of the azimuth in one
        // square root and one division: k = sin(theta) / (sqrt(1 - uz^2) q).
        const double k = std::sqrt(one_minus_ct2 / one_minus_uz2) / q;
        p.ux = k * (ux * uz * c2 - uy * s2) + ux * ct;
        p.uy = k * (uy * uz * c2 + ux * s2) + uy * ct;
        p.uz = -k * one_minus_uz2 * c2 + uz * ct;
      }
      return true;
    }
    // The free path reaches an interface: move there, keep the rest of the optical depth.
    const double to_boundary = p.uz > 0 ? (l.z_bottom - p.z) / p.uz : p.uz < 0 ? (l.z_top - p.z) / p.uz : kInfinity;
    if (to_boundary == kInfinity) {  // parallel to the interfaces in a clear layer: never arrives
      tally.lost += p.w;
      return false;
    }
    p.x += to_boundary * p.ux;
    p.y += to_boundary * p.uy;
    if (!l.clear) p.tau -= to_boundary * l.sigma_t;
    const bool down = p.uz > 0;
    p.z = down ? l.z_bottom : l.z_top;
    const int next = down ? p.layer + 1 : p.layer - 1;
    const double n_next = next < 0 ? geo.n_above : next >= layer_count ? geo.n_below : layers[next].n;
    if (n_next != l.n) {
      const double ratio = l.n / n_next;
      const double ci = std::abs(p.uz);
      const double reflect = fresnel_reflectance(ci, ratio);  // 1 under total internal reflection
      if (reflect >= 1 || rng.uniform() < reflect) {
        p.uz = -p.uz;
        return true;
      }
      const double cos_t = std::sqrt(1 - ratio * ratio * (1 - ci * ci));
      p.ux *= ratio;
      p.uy *= ratio;
      p.uz = down ? cos_t : -cos_t;
    }
    if (next < 0 || next >= layer_count) {
      escape(p, next < 0);  // leaves the stack: tallied once, the photon ends here
      return false;
    }
    p.layer = next;
    return true;
  };

  Photon lanes[kLanes];
  int active = 0;
  for (Photon& p : lanes) {
    if (launched < photons) {
      launch(p);
      ++active;
    } else {
      p.active = false;
    }
  }
  while (active > 0) {
    for (Photon& p : lanes) {
      if (!p.active) continue;
      if (step(p)) continue;
      interactions += p.scatterings;
      tally.sum[kAbsorbed] += p.absorbed;
      tally.sum_sq[kAbsorbed] += p.absorbed * p.absorbed;
      if (launched < photons) {
        launch(p);
      } else {
        p.active = false;
        --active;
      }
    }
  }
  tally.photons += photons;
  tally.interactions += interactions;
}

}  // namespace bssrdf::mc
