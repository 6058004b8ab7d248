#include "bssrdf/lut/preintegrated_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/parallel.hpp"

namespace bssrdf {
namespace {

// For each bound b_i (monotone in i, either way): the number of the ascending nodes x below it (x < b_i), or with
// `inclusive` at or below it (x <= b_i), as std::lower_bound / std::upper_bound would count, by one sweep.
std::vector<std::size_t> sweep_counts(const std::vector<double>& x, const std::vector<double>& bound, bool inclusive) {
  const std::size_t n = bound.size();
  std::vector<std::size_t> count(n);
  const bool rising = n < 2 || bound.front() <= bound.back();
  std::size_t m = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = rising ? k : n - 1 - k;  // in increasing bound
    const auto below = [&](std::size_t node) { return inclusive ? x[node] <= bound[i] : x[node] < bound[i]; };
    while (m > 0 && !below(m - 1)) --m;  // a bound out of order by rounding: step back
    while (m < x.size() && below(m)) ++m;
    count[i] = m;
  }
  return count;
}

}  // namespace

void PreintegratedOptions::validate() const {
  if (width < 2 || width > 8192) throw InvalidInput("size", std::to_string(width) + " columns", "2 to 8192");
  if (height < 1 || height > 8192) throw InvalidInput("size", std::to_string(height) + " rows", "1 to 8192");
  if (!(curvature_max >= 0) || !std::isfinite(curvature_max))
    throw InvalidInput("curvature_max", format_number(curvature_max), "> 0 (0: default)");
  if (threads > 4096) throw InvalidInput("threads", std::to_string(threads), "0 (all cores) to 4096");
  if (!(ring_nodes_per_decade >= 4 && ring_nodes_per_decade <= 1024))
    throw InvalidInput("ring_nodes_per_decade", format_number(ring_nodes_per_decade), "4 to 1024");
  if (!(ring_step > 0 && ring_step <= 0.1))
    throw InvalidInput("ring_step", format_number(ring_step), "0 < step <= 0.1");
}

PreintegratedTable build_preintegrated_table(const Medium& medium, const Model& model,
                                             const PreintegratedOptions& options) {
  medium.validate();
  options.validate();
  return build_preintegrated_table(medium, project_channels(medium, model), options);
}

PreintegratedTable build_preintegrated_table(const Medium& medium,
                                             const std::vector<std::optional<ProjectedProfile>>& profiles,
                                             const PreintegratedOptions& options) {
  options.validate();
  PreintegratedTable t;
  t.options = options;
  t.channel_names = medium.channel_names;
  const std::size_t channels = medium.channels(), W = options.width, H = options.height;
  // A channel that does not scatter (sigma_s = 0) keeps the limit of a vanishing profile: D = max(0, N.L).
  double r_min = INFINITY;
  for (const auto& p : profiles) {
    t.scatters.push_back(p.has_value());
    if (!p) continue;
    t.widest_r50 = std::max(t.widest_r50, p->radius_for_fraction(0.5));
    r_min = std::min(r_min, p->r_min());
  }
  if (t.options.curvature_max == 0) t.options.curvature_max = 1 / t.widest_r50;
  for (std::size_t i = 0; i < W; ++i)
    t.n_dot_l.push_back(-1 + 2 * (static_cast<double>(i) + 0.5) / static_cast<double>(W));
  for (std::size_t j = 0; j < H; ++j)
    t.curvature.push_back(t.options.curvature_max * (static_cast<double>(j) + 0.5) / static_cast<double>(H));
  t.value.assign(channels, std::vector<double>(W * H));

  std::vector<double> theta(W);
  for (std::size_t i = 0; i < W; ++i) theta[i] = std::acos(std::clamp(t.n_dot_l[i], -1.0, 1.0));
  // Nodes in x in (0, pi]: geometric from the profile's smallest scale (chord r x) to 0.1 (per row), then uniform
  // (the same in every row: their sines and cosines are computed once).
  const double h = std::log(10.0) / options.ring_nodes_per_decade, ratio = std::exp(h);
  const double step = options.ring_step, pi = std::numbers::pi;
  const auto n_uniform = static_cast<std::size_t>(std::ceil((pi - 0.1) / step));
  std::vector<double> uniform_x, uniform_cos, uniform_sin, uniform_half_sin, uniform_ln_half_sin;
  for (std::size_t k = 0; k <= n_uniform; ++k) {
    const double x = 0.1 + (pi - 0.1) * static_cast<double>(k) / static_cast<double>(n_uniform);
    uniform_x.push_back(x);
    uniform_cos.push_back(std::cos(x));
    uniform_sin.push_back(std::sin(x));
    uniform_half_sin.push_back(std::sin(0.5 * x));
    uniform_ln_half_sin.push_back(std::log(uniform_half_sin.back()));  // ln chord = ln 2r + this
  }
  // The clamps' ranges (below) are bounded by theta_i -+ pi/2 and 3pi/2 - theta_i; theta falls as i grows.
  std::vector<double> below_lit(W), lit_again(W), facing_lo(W), facing_hi(W);
  for (std::size_t i = 0; i < W; ++i) {
    below_lit[i] = pi / 2 - theta[i];
    lit_again[i] = 3 * pi / 2 - theta[i];
    facing_lo[i] = theta[i] - pi / 2;
    facing_hi[i] = theta[i] + pi / 2;
  }
  parallel_for(H, options.threads, [&](std::size_t j) {
    const double radius = 1 / t.curvature[j];
    const double x_lo = std::min(1e-3, r_min / radius);
    thread_local std::vector<double> x, quad, cos_x, sin_x, chord, ln_chord, line, prefix_cos, prefix_sin;
    x.clear();
    for (double v = x_lo; v < 0.1; v *= ratio) x.push_back(v);
    const std::size_t G = x.size();  // geometric nodes
    x.insert(x.end(), uniform_x.begin(), uniform_x.end());
    const std::size_t K = x.size();
    for (auto* v : {&quad, &cos_x, &sin_x, &chord, &ln_chord, &line}) v->resize(K);
    for (std::size_t k = 0; k < K; ++k)  // trapezoid weights; the first also covers (0, x_0] (integrand constant)
      quad[k] = k == 0       ? x[0] + 0.5 * (x[1] - x[0])
                : k + 1 == K ? 0.5 * (x[k] - x[k - 1])
                             : 0.5 * (x[k + 1] - x[k - 1]);
    // The geometric nodes (x < 0.1): sine and cosine by their Taylor series, whose first omitted terms
    // (x^11 / 11!, x^10 / 10!) are below half an ulp there: the same values as the C library's to its
    // rounding, in a loop that vectorises (the library's calls were 11 % of the batch).
    for (std::size_t k = 0; k < G; ++k) {
      const double v = x[k], v2 = v * v, h2 = 0.25 * v2;
      sin_x[k] = v * (1 - v2 / 6 * (1 - v2 / 20 * (1 - v2 / 42 * (1 - v2 / 72 * (1 - v2 / 110)))));
      cos_x[k] = 1 - v2 / 2 * (1 - v2 / 12 * (1 - v2 / 30 * (1 - v2 / 56 * (1 - v2 / 90))));
      chord[k] = 2 * radius * (0.5 * v) * (1 - h2 / 6 * (1 - h2 / 20 * (1 - h2 / 42 * (1 - h2 / 72 * (1 - h2 / 110)))));
    }
    for (std::size_t k = 0; k < G; ++k) ln_chord[k] = std::log(chord[k]);  // once for every channel's profile
    const double ln_diameter = std::log(2 * radius);
    for (std::size_t k = G; k < K; ++k) {
      cos_x[k] = uniform_cos[k - G];
      sin_x[k] = uniform_sin[k - G];
      chord[k] = 2 * radius * uniform_half_sin[k - G];
      ln_chord[k] = ln_diameter + uniform_ln_half_sin[k - G];
    }
    // sum_k w_k [max(0, cos(theta + x_k)) + max(0, cos(theta - x_k))], theta = acos(N.L) in [0, pi],
    // x_k in (0, pi]: each clamp keeps a contiguous range of nodes (cos(theta + x) > 0 for
    // x < pi/2 - theta or x > 3pi/2 - theta; cos(theta - x) > 0 for |x - theta| < pi/2), so
    // prefix sums of w cos x and w sin x give every column in O(1) once the ranges (the same for
    // every channel) are known. The ranges' ends move one way as theta falls: counted by a sweep.
    const auto at_most = sweep_counts(x, below_lit, false);  // nodes < pi/2 - theta
    const auto from = sweep_counts(x, lit_again, true);      // nodes <= 3pi/2 - theta
    const auto lo = sweep_counts(x, facing_lo, true);        // nodes <= theta - pi/2
    const auto hi = sweep_counts(x, facing_hi, false);       // nodes < theta + pi/2
    prefix_cos.assign(K + 1, 0.0);
    prefix_sin.assign(K + 1, 0.0);
    for (std::size_t c = 0; c < channels; ++c) {
      if (!profiles[c]) {
        for (std::size_t i = 0; i < W; ++i) t.value[c][j * W + i] = std::max(0.0, t.n_dot_l[i]);
        continue;
      }
      profiles[c]->lines(chord.data(), ln_chord.data(), line.data(), K);
      double norm = 0;
      for (std::size_t k = 0; k < K; ++k) {
        const double w = quad[k] * line[k];
        norm += w;
        prefix_cos[k + 1] = prefix_cos[k] + w * cos_x[k];
        prefix_sin[k + 1] = prefix_sin[k] + w * sin_x[k];
      }
      const auto sums = [&](std::size_t a, std::size_t b) {
        b = std::max(a, b);
        return std::pair{prefix_cos[b] - prefix_cos[a], prefix_sin[b] - prefix_sin[a]};
      };
      for (std::size_t i = 0; i < W; ++i) {
        const double u = t.n_dot_l[i], s = std::sqrt(std::max(0.0, 1 - u * u));
        const auto [c1, s1] = sums(0, at_most[i]);
        const auto [c2, s2] = sums(from[i], K);
        const auto [c3, s3] = sums(lo[i], hi[i]);
        const double sum = u * (c1 + c2) - s * (s1 + s2) + u * c3 + s * s3;
        t.value[c][j * W + i] = std::clamp(sum / (2 * norm), 0.0, 1.0);
      }
    }
  });
  return t;
}

LookupTable to_lookup_table(const PreintegratedTable& t, const TableContext& context) {
  auto out = described_table("preintegrated", t.options.width, t.options.height, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  out.set("bssrdf:formula",
          std::string("D(theta, r) = int max(0, cos(theta + x)) R_ring(2 r sin(x/2)) dx / int R_ring(2 r sin(x/2)) dx "
                      "over x in [-pi, pi] (Penner 2011); R_ring(d) = int R(sqrt(d^2 + y^2)) dy, the profile's "
                      "cross-section through the ring"));
  out.set("bssrdf:normalization",
          std::string("per channel, int R_ring = 1: D is in [0, 1]; multiply by the diffuse colour"));
  out.set("bssrdf:x_axis",
          std::string(
              "u = N.L in [-1, 1]: column i holds u_i = -1 + 2 (i + 0.5) / width (texture coordinate (u + 1) / 2)"));
  out.set("bssrdf:y_axis", "curvature 1/r in 1/" + u +
                               ": row j holds c_j = curvature_max (j + 0.5) / height (texture coordinate c / "
                               "curvature_max); row 0 is the flattest");
  out.x_axis = {"n_dot_l", t.n_dot_l};
  out.y_axis = {"curvature (1/" + u + ")", {}};
  for (double c : t.curvature) out.y_axis.values.push_back(c * mm);
  out.set("bssrdf:curvature_max", t.options.curvature_max * mm);
  out.set("bssrdf:curvature_unit", "1/" + u);
  out.set("bssrdf:widest_r50", t.widest_r50 / mm);
  out.set("bssrdf:size", std::to_string(t.options.width) + "x" + std::to_string(t.options.height));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    if (t.scatters.size() > c && !t.scatters[c])
      out.set("bssrdf:note." + t.channel_names[c],
              std::string("the channel does not scatter (sigma_s = 0): D = max(0, N.L)"));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    out.add_channel(t.channel_names[c], "pre-integrated diffuse D(N.L, curvature), dimensionless", t.value[c]);
  return out;
}

std::string summary(const PreintegratedTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  const std::size_t W = t.options.width, H = t.options.height;
  std::ostringstream s;
  s << "pre-integrated table: " << W << " N.L x " << H << " curvatures from 0 to "
    << short_number(t.options.curvature_max * mm) << " 1/" << u << " (sphere radius down to "
    << short_number(1 / (t.options.curvature_max * mm)) << ' ' << u << ", the widest channel's r_50), texel centres\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    s << "  " << t.channel_names[c] << ": D at N.L = " << short_number(t.n_dot_l[W / 2]) << ": "
      << short_number(t.value[c][W / 2]) << " (flattest row) to " << short_number(t.value[c][(H - 1) * W + W / 2])
      << " (most curved); at N.L = " << short_number(t.n_dot_l[0]) << ": " << short_number(t.value[c][0]) << " to "
      << short_number(t.value[c][(H - 1) * W]) << '\n';
  return s.str();
}

}  // namespace bssrdf
