#include "bssrdf/lut/radial_table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/parallel.hpp"
#include "bssrdf/scalar_math.hpp"

namespace bssrdf {
namespace {

struct Probe {
  double total = 0, r_lo = 0, r_hi = 0;
  double decay_length = 0;                // -1 / (d ln R / dr) at r_hi
  std::vector<double> log_r, cumulative;  // for the inner disc below the table
  // A channel without scattering (sigma_s = 0) reflects nothing: no range, no grid, R = 0.
  bool scatters() const { return total > 0; }
};

// R on a geometric grid of 16 points per decade from 1e-5 ell until the tail beyond is negligible;
// trapezoid in ln r of f = 2 pi r^2 R.
Probe probe(const Model& model, const Reduced<double>& m, double energy, std::size_t& evaluations) {
  const double h = std::log(10.0) / 16;
  Probe p;
  double u = std::log(1e-5 * m.ell);
  double f_prev = kTwoPi * std::exp(2 * u) * model.reflectance(m, std::exp(u));
  double cum = f_prev;  // inner disc: exact for R ~ 1/r, negligible anyway
  p.log_r.push_back(u);
  p.cumulative.push_back(cum);
  const double u_stop = std::log(1e8 * m.ell);
  double f_max = f_prev;
  while (u < u_stop) {
    u += h;
    const double f = kTwoPi * std::exp(2 * u) * model.reflectance(m, std::exp(u));
    ++evaluations;
    cum += 0.5 * h * (f + f_prev);
    p.log_r.push_back(u);
    p.cumulative.push_back(cum);
    f_max = std::max(f_max, f);
    // Past the peak and decaying: a geometric tail estimate bounds what is left.
    const double q = f / f_prev;
    f_prev = f;
    if (std::exp(u) > m.ell && q < 1 && f * h * q / (1 - q) < 1e-7 * cum) break;
    if (!std::isfinite(f) || f_max == 0) break;
  }
  p.total = cum;
  const auto radius_at = [&](double target) {
    const auto it = std::lower_bound(p.cumulative.begin(), p.cumulative.end(), target);
    if (it == p.cumulative.begin()) return std::exp(p.log_r.front());
    if (it == p.cumulative.end()) return std::exp(p.log_r.back());
    const std::size_t j = static_cast<std::size_t>(it - p.cumulative.begin());
    const double t = (target - p.cumulative[j - 1]) / (p.cumulative[j] - p.cumulative[j - 1]);
    return std::exp(p.log_r[j - 1] + t * (p.log_r[j] - p.log_r[j - 1]));
  };
  p.r_lo = radius_at(0.5 * (1 - energy) * p.total);
  p.r_hi = radius_at(0.5 * (1 + energy) * p.total);
  // Local decay length of R at r_hi, from two probe points around it.
  const double a = p.r_hi / 1.2, b = p.r_hi * 1.2;
  const double slope = (std::log(model.reflectance(m, b)) - std::log(model.reflectance(m, a))) / (b - a);
  evaluations += 2;
  p.decay_length = slope < 0 && std::isfinite(slope) ? -1 / slope : p.r_hi;
  return p;
}

double cumulative_from_probe(const Probe& p, double r) {
  const double u = std::log(r);
  if (u <= p.log_r.front()) return p.cumulative.front() * std::exp(u - p.log_r.front());
  return interpolate(p.log_r, p.cumulative, u, Interpolation::linear);
}

// The grid coordinate x = ln r + r / L: logarithmic where r << L (the near field, R ~ 1/r) and
// linear where r >> L (the exponential far field), so neither end is oversampled.
struct GridMap {
  double L;
  double x(double r) const { return std::log(r) + r / L; }
  double r(double x_value) const {  // Newton on ln r + r/L = x, from the larger of the two asymptotes
    // Both asymptotes overestimate r; Newton on the convex f(y) = y + e^y / L then descends monotonically.
    double y = x_value;
    if (x_value > std::log(L)) y = std::min(y, std::log(L * (x_value - std::log(L))));
    for (int i = 0; i < 60; ++i) {
      const double e = std::exp(y), f = y + e / L - x_value, step = f / (1 + e / L);
      y -= step;
      if (std::abs(step) < 1e-15 * std::max(1.0, std::abs(y))) break;
    }
    return std::exp(y);
  }
  double dr_dx(double r) const { return r * L / (L + r); }
};

// Values at the nodes and at the two check points of every interval, for all channels.
struct GridValues {
  std::vector<double> log_r;                     // holds x: the grid coordinate
  std::vector<std::vector<double>> node, check;  // [channel][j], check: [channel][2 j + k]
};

std::vector<double> uniform_grid(double u0, double u1, std::size_t n) {
  std::vector<double> x;
  const double h = (u1 - u0) / static_cast<double>(n - 1);
  for (std::size_t j = 0; j < n; ++j) x.push_back(j + 1 == n ? u1 : u0 + h * static_cast<double>(j));
  return x;
}

// A dense stand-in for the model while the table size is searched: the model on M nodes uniform in
// x, interpolated by 6-point Lagrange in ln R (nearly linear in x at both ends: -ln r near 0, -r/L
// in the tail). M doubles, reusing every value, until the coarser grid predicts the new midpoints
// to `accuracy`; at the final spacing the error is then about 2^-6 of that.
struct DenseProfile {
  double x0 = 0, h = 0;
  std::vector<std::vector<double>> log_value;  // [channel][i]
  double error = 0;                            // the last midpoint prediction error (relative)

  double value(std::size_t c, double x) const {
    const auto& f = log_value[c];
    const double s = (x - x0) / h;
    const auto start = std::clamp<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(std::floor(s)) - 2, 0,
                                                  static_cast<std::ptrdiff_t>(f.size()) - 6);
    const double t = s - static_cast<double>(start);
    static constexpr double kDenominator[6] = {-120, 24, -12, 12, -24, 120};
    double sum = 0;
    for (int k = 0; k < 6; ++k) {
      double w = 1 / kDenominator[k];
      for (int m = 0; m < 6; ++m)
        if (m != k) w *= t - m;
      sum += w * f[static_cast<std::size_t>(start + k)];
    }
    return std::exp(sum);
  }
};

DenseProfile dense_profile(const Model& model, const std::vector<Reduced<double>>& media,
                           const std::vector<Probe>& probes, const GridMap& map, double u0, double u1, double accuracy,
                           std::size_t max_nodes, unsigned threads, std::size_t& evaluations) {
  const std::size_t channels = media.size();
  DenseProfile d;
  d.x0 = u0;
  std::size_t n = 65;
  d.h = (u1 - u0) / static_cast<double>(n - 1);
  d.log_value.assign(channels, std::vector<double>(n));
  const auto log_R = [&](std::size_t c, double x) {
    if (!probes[c].scatters()) return -745.0;
    const double R = model.reflectance(media[c], map.r(x));
    return R > 0 ? std::log(R) : -745.0;  // below the smallest double: treated as zero
  };
  parallel_for(channels * n, threads, [&](std::size_t item) {
    d.log_value[item / n][item % n] = log_R(item / n, u0 + d.h * static_cast<double>(item % n));
  });
  evaluations += channels * n;
  for (;;) {
    // The midpoints: evaluated, and predicted from the current nodes.
    std::vector<std::vector<double>> mid(channels, std::vector<double>(n - 1));
    parallel_for(channels * (n - 1), threads, [&](std::size_t item) {
      const std::size_t c = item / (n - 1), j = item % (n - 1);
      mid[c][j] = log_R(c, u0 + d.h * (static_cast<double>(j) + 0.5));
    });
    evaluations += channels * (n - 1);
    d.error = 0;
    for (std::size_t c = 0; c < channels; ++c) {
      if (!probes[c].scatters()) continue;
      const double lo = map.x(probes[c].r_lo), hi = map.x(probes[c].r_hi);
      for (std::size_t j = 0; j + 1 < n; ++j) {
        const double x = u0 + d.h * (static_cast<double>(j) + 0.5);
        if (x < lo || x > hi) continue;
        d.error = std::max(d.error, std::abs(d.value(c, x) / std::exp(mid[c][j]) - 1));
      }
    }
    for (std::size_t c = 0; c < channels; ++c) {
      std::vector<double> merged(2 * n - 1);
      for (std::size_t j = 0; j < n; ++j) merged[2 * j] = d.log_value[c][j];
      for (std::size_t j = 0; j + 1 < n; ++j) merged[2 * j + 1] = mid[c][j];
      d.log_value[c] = std::move(merged);
    }
    n = 2 * n - 1;
    d.h /= 2;
    if (d.error <= accuracy) return d;
    if (n > max_nodes)
      throw InvalidInput("tolerance", format_number(accuracy * 4),
                         "reachable: the profile is not smooth enough to tabulate (interpolation error " +
                             format_number(d.error) + " at " + std::to_string(n) + " radii)");
  }
}

// The grid of n nodes with the values of `f(c, x)` at its nodes and check points.
template <class F>
GridValues evaluate(std::size_t channels, double u0, double u1, std::size_t n, unsigned threads, F&& f) {
  GridValues g;
  g.log_r = uniform_grid(u0, u1, n);
  g.node.assign(channels, std::vector<double>(n));
  g.check.assign(channels, std::vector<double>(2 * (n - 1)));
  parallel_for(channels * n, threads, [&](std::size_t item) {
    const std::size_t c = item / n, j = item % n;
    g.node[c][j] = f(c, g.log_r[j]);
    if (j + 1 < n)
      for (int k = 0; k < 2; ++k)
        g.check[c][2 * j + k] = f(c, g.log_r[j] + kCheckPoint[k] * (g.log_r[j + 1] - g.log_r[j]));
  });
  return g;
}

// Worst relative interpolation error at the check points inside each channel's own range. For
// linear interpolation the error t(1 - t) peaks at the midpoint, 1.5x its value at the check points.
double worst_error(const GridValues& g, const std::vector<Probe>& probes, const GridMap& map, Interpolation scheme) {
  double worst = 0;
  const std::size_t n = g.log_r.size();
  const double scale = scheme == Interpolation::linear ? 1.5 : 1.0;
  for (std::size_t c = 0; c < g.node.size(); ++c) {
    if (!probes[c].scatters()) continue;
    const double lo = map.x(probes[c].r_lo), hi = map.x(probes[c].r_hi);
    for (std::size_t j = 0; j + 1 < n; ++j)
      for (int k = 0; k < 2; ++k) {
        const double u = g.log_r[j] + kCheckPoint[k] * (g.log_r[j + 1] - g.log_r[j]);
        if (u < lo || u > hi) continue;
        const double exact = g.check[c][2 * j + k];
        const double approx = interpolate(g.log_r, g.node[c], u, scheme);
        const double error = std::abs(approx - exact) / std::max(std::abs(exact), 1e-300);
        worst = std::max(worst, scale * error);
      }
  }
  return worst;
}

}  // namespace

void RadialTableOptions::validate() const {
  if (!(tolerance > 0 && tolerance < 1)) throw InvalidInput("tolerance", format_number(tolerance), "0 < tolerance < 1");
  if (!(energy > 0 && energy < 1)) throw InvalidInput("energy", format_number(energy), "0 < energy < 1");
  if (max_size < 4) throw InvalidInput("max table size", std::to_string(max_size), ">= 4");
}

double RadialTable::grid_coordinate(double r) const { return std::log(r) + r / decay_length; }

double RadialTable::interpolate(std::size_t channel, double r) const {
  if (!(r >= radius.front() && r <= radius.back())) return 0;
  std::vector<double> x(radius.size());
  for (std::size_t j = 0; j < radius.size(); ++j) x[j] = grid_coordinate(radius[j]);
  return bssrdf::interpolate(x, reflectance[channel], grid_coordinate(r), options.interpolation);
}

RadialTable build_radial_table(const Medium& medium, const Model& model, const RadialTableOptions& options) {
  options.validate();
  medium.validate();
  RadialTable table;
  table.options = options;
  table.channel_names = medium.channel_names;
  const std::size_t channels = medium.channels();
  std::vector<Reduced<double>> media;
  for (std::size_t c = 0; c < channels; ++c) media.push_back(medium.reduced(c));

  std::vector<Probe> probes(channels);
  std::vector<std::size_t> probe_evaluations(channels, 0);
  parallel_for(channels, options.threads,
               [&](std::size_t c) { probes[c] = probe(model, media[c], options.energy, probe_evaluations[c]); });
  for (auto e : probe_evaluations) table.evaluations += e;
  double r_min = INFINITY, r_max = 0, L = 0;
  for (const auto& p : probes) {
    table.total_reflectance.push_back(p.total);
    table.range_min.push_back(p.scatters() ? p.r_lo : 0);
    table.range_max.push_back(p.scatters() ? p.r_hi : 0);
    if (!p.scatters()) continue;
    r_min = std::min(r_min, p.r_lo);
    r_max = std::max(r_max, p.r_hi);
    L = std::max(L, p.decay_length);
  }
  if (r_max == 0)
    throw InvalidInput("profile", "0 in every channel", "a medium that scatters (sigma_s > 0) in at least one channel");
  const GridMap map{L};
  table.decay_length = L;
  const double u0 = map.x(r_min), u1 = map.x(r_max);

  // The size is searched against a dense stand-in for the model (accurate to about 1/256 of the
  // tolerance), so the search costs no model evaluations beyond the stand-in's; the model is then
  // evaluated at the chosen nodes only. The stand-in's own error is kept out of the budget.
  const DenseProfile dense = dense_profile(model, media, probes, map, u0, u1, options.tolerance / 4,
                                           8 * options.max_size + 1, options.threads, table.evaluations);
  const double target = options.tolerance - dense.error / 16;
  const auto stand_in = [&](std::size_t c, double x) { return dense.value(c, x); };

  // Smallest N meeting the target (to within 3 %). The interpolation error falls as a power of
  // the spacing, e(N) ~ C (N - 1)^-p, so each next size is predicted from the last two trials
  // (regula falsi in log-log; p from the interpolation order before there are two): grow to the
  // predicted size until one passes, then test the size predicted between the last failure and the
  // first success, or, once that lies within 3 % of the success, the size 3 % below it, which
  // settles the search when it fails.
  const double order = options.interpolation == Interpolation::linear ? 2.0 : 3.0;
  const auto trial = [&](std::size_t n) {
    auto g = evaluate(channels, u0, u1, n, options.threads, stand_in);
    const double e = worst_error(g, probes, map, options.interpolation);
    return std::pair{std::move(g), e};
  };
  // The size where the error reaches `target`, from (n_a, e_a) and the exponent p.
  const auto predict = [](std::size_t n_a, double e_a, double p, double target) {
    return 1 + static_cast<double>(n_a - 1) * std::pow(e_a / target, 1 / p);
  };
  const auto exponent = [&](std::size_t n_a, double e_a, std::size_t n_b, double e_b) {
    const double p = std::log(e_a / e_b) / std::log(static_cast<double>(n_b - 1) / static_cast<double>(n_a - 1));
    return std::isfinite(p) ? std::clamp(p, 1.0, 8.0) : order;
  };
  const double guess = 64 * std::pow(1e-3 / options.tolerance, 1 / 2.5);
  std::size_t fail = 1,
              n = std::min(options.max_size, std::max<std::size_t>(16, static_cast<std::size_t>(std::ceil(guess))));
  double fail_error = 0;
  auto [best, best_error] = trial(n);
  while (best_error > target) {
    const double p = fail > 1 ? exponent(fail, fail_error, n, best_error) : order;
    fail = n;
    fail_error = best_error;
    if (n >= options.max_size)
      throw InvalidInput("tolerance", format_number(options.tolerance),
                         "reachable with at most " + std::to_string(options.max_size) + " radii (error " +
                             format_number(best_error) + " there)");
    const double next = std::min(predict(n, best_error, p, 0.95 * target), 1 + 8.0 * static_cast<double>(n - 1));
    n = std::min(options.max_size, std::max(n + 1, static_cast<std::size_t>(std::ceil(next))));
    std::tie(best, best_error) = trial(n);
  }
  std::size_t pass = n;
  while (pass - fail > std::max<std::size_t>(1, pass / 32)) {
    const std::size_t gap = std::max<std::size_t>(1, pass / 32);
    const double p = fail > 1 ? exponent(fail, fail_error, pass, best_error) : order;
    const double star = predict(pass, best_error, p, target);
    std::size_t mid = star >= static_cast<double>(pass - gap) ? pass - gap : static_cast<std::size_t>(std::ceil(star));
    mid = std::clamp(mid, fail + 1, pass - 1);
    auto [g, e] = trial(mid);
    if (e <= target) {
      pass = mid;
      best = std::move(g);
      best_error = e;
    } else {
      fail = mid;
      fail_error = e;
    }
  }
  // The model at the chosen nodes (the check points keep the stand-in's values). A reference, as
  // lambdas capture structured bindings only from C++20 compilers newer than clang 14.
  auto& chosen = best;
  parallel_for(channels * pass, options.threads, [&](std::size_t item) {
    const std::size_t c = item / pass, j = item % pass;
    chosen.node[c][j] = probes[c].scatters() ? model.reflectance(media[c], map.r(chosen.log_r[j])) : 0.0;
  });
  table.evaluations += channels * pass;
  best_error = worst_error(best, probes, map, options.interpolation) + dense.error / 16;
  table.max_error = best_error;

  const std::size_t N = best.log_r.size();
  for (double x : best.log_r) table.radius.push_back(map.r(x));
  table.radius.front() = r_min;
  table.radius.back() = r_max;
  for (std::size_t j = 0; j < N; ++j) table.u.push_back(static_cast<double>(j) / static_cast<double>(N - 1));
  for (std::size_t c = 0; c < channels; ++c) {
    const auto& R = best.node[c];
    std::vector<double> ring(N), cum(N);
    for (std::size_t j = 0; j < N; ++j) ring[j] = kTwoPi * table.radius[j] * R[j];
    // 2-point Gauss-Legendre per interval in x (the check points), fourth order.
    cum[0] = cumulative_from_probe(probes[c], table.radius[0]);
    for (std::size_t j = 0; j + 1 < N; ++j) {
      const double du = best.log_r[j + 1] - best.log_r[j];
      double piece = 0;
      for (int k = 0; k < 2; ++k) {
        const double r = map.r(best.log_r[j] + kCheckPoint[k] * du);
        piece += 0.5 * du * kTwoPi * r * map.dr_dx(r) * best.check[c][2 * j + k];
      }
      cum[j + 1] = cum[j] + piece;
    }
    const double in_table = cum.back();
    std::vector<double> cdf(N);
    if (!probes[c].scatters()) {  // the limit of a vanishing profile: all of it at r = 0
      table.reflectance.push_back(R);
      table.ring.push_back(std::move(ring));
      table.cdf.push_back(std::vector<double>(N, 1.0));
      table.inverse_cdf.push_back(std::vector<double>(N, 0.0));
      table.table_reflectance.push_back(0);
      continue;
    }
    for (std::size_t j = 0; j < N; ++j) cdf[j] = cum[j] / in_table;
    auto inverse = inverse_cdf(
        cdf, table.radius, best.log_r, [&](double x) { return map.r(x); }, table.u);
    table.reflectance.push_back(R);
    table.ring.push_back(std::move(ring));
    table.cdf.push_back(std::move(cdf));
    table.inverse_cdf.push_back(std::move(inverse));
    table.table_reflectance.push_back(in_table);
  }
  return table;
}

LookupTable to_lookup_table(const RadialTable& t, const TableContext& context) {
  auto out = described_table("radial", t.size(), 1, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  const auto scaled = [](const std::vector<double>& v, double s) {
    std::vector<double> o(v);
    for (auto& x : o) x *= s;
    return o;
  };
  out.set("bssrdf:distance", "radius r on the surface from the point of incidence, in " + u);
  out.set("bssrdf:normalization", std::string("per_entered_flux: R(r) is the exitance at r from a normally incident "
                                              "pencil beam per unit flux that entered the medium"));
  out.set("bssrdf:grid",
          "uniform in x = ln(r / " + u +
              ") + r / L, L = bssrdf:decay_length (logarithmic near 0, linear in the exponential tail): x_j = x(r_min) "
              "+ (x(r_max) - x(r_min)) j / (N - 1), j = 0 .. N - 1; the radius channel holds r_j");
  out.set("bssrdf:decay_length", t.decay_length / mm);
  out.set("bssrdf:size", static_cast<int>(t.size()));
  out.set("bssrdf:r_min", t.radius.front() / mm);
  out.set("bssrdf:r_max", t.radius.back() / mm);
  out.set("bssrdf:interpolation", std::string(to_string(t.options.interpolation)) + " in x");
  out.set("bssrdf:tolerance", t.options.tolerance);
  out.set("bssrdf:max_error", t.max_error);
  out.set("bssrdf:energy", t.options.energy);
  out.set(
      "bssrdf:cdf",
      std::string(
          "cdf.<c>(r_j) = int_0^{r_j} 2 pi r R dr / int_0^{r_max} 2 pi r R dr; inverse_cdf.<c> at u_j = j / (N - 1)"));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    const auto& name = t.channel_names[c];
    out.set("bssrdf:total_reflectance." + name, t.total_reflectance[c]);
    out.set("bssrdf:table_reflectance." + name, t.table_reflectance[c]);
    out.set("bssrdf:range." + name,
            t.range_max[c] > 0
                ? format_number(t.range_min[c] / mm) + " to " + format_number(t.range_max[c] / mm) + " " + u
                : std::string("none: the channel does not scatter (total reflectance 0); R = 0, cdf = 1 and "
                              "inverse_cdf = 0 (all at r = 0)"));
  }
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    out.add_channel(t.channel_names[c], "R(r), 1/" + u + "^2 per unit entered flux", scaled(t.reflectance[c], mm * mm));
  out.add_channel("radius", "r, " + u, scaled(t.radius, 1 / mm));
  add_sampling_channels(out, t.channel_names, t.ring, t.cdf, t.u, t.inverse_cdf, "CDF of 2 pi r R(r) over [0, r_max]",
                        context.unit);
  return out;
}

void add_sampling_channels(LookupTable& out, const std::vector<std::string>& channel_names,
                           const std::vector<std::vector<double>>& ring, const std::vector<std::vector<double>>& cdf,
                           const std::vector<double>& u, const std::vector<std::vector<double>>& inverse_cdf,
                           const std::string& cdf_description, LengthUnit unit) {
  const double mm = millimetres_per(unit);
  const std::string symbol_u(symbol(unit));
  const auto scaled = [](std::vector<double> v, double s) {
    for (auto& x : v) x *= s;
    return v;
  };
  for (std::size_t c = 0; c < channel_names.size(); ++c)
    out.add_channel("ring." + channel_names[c], "2 pi r R(r), 1/" + symbol_u, scaled(ring[c], mm));
  for (std::size_t c = 0; c < channel_names.size(); ++c)
    out.add_channel("cdf." + channel_names[c], cdf_description, cdf[c]);
  out.add_channel("u", "CDF value u_j = j / (N - 1) of the inverse_cdf channels", u);
  for (std::size_t c = 0; c < channel_names.size(); ++c)
    out.add_channel("inverse_cdf." + channel_names[c], "radius r with cdf(r) = u_j, " + symbol_u,
                    scaled(inverse_cdf[c], 1 / mm));
}

std::string summary(const RadialTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  s << "radial table: " << t.size() << " radii from " << short_number(t.radius.front() / mm) << " to "
    << short_number(t.radius.back() / mm) << ' ' << u << ", uniform in ln r + r/" << short_number(t.decay_length / mm)
    << " (" << to_string(t.options.interpolation) << "; worst error " << short_number(t.max_error) << " <= tolerance "
    << short_number(t.options.tolerance) << " over the range holding " << short_number(t.options.energy)
    << " of each channel's total; " << t.evaluations << " model evaluations)\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    if (t.range_max[c] == 0)
      s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): R = 0, all of its CDF at r = 0\n";
    else
      s << "  " << t.channel_names[c] << ": total reflectance " << short_number(t.total_reflectance[c]) << ", range "
        << short_number(t.range_min[c] / mm) << " to " << short_number(t.range_max[c] / mm) << ' ' << u << '\n';
  return s.str();
}

}  // namespace bssrdf
