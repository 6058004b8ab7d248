// The exact model's interpolation (models/exact.hpp).
#include "bssrdf/models/exact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "bssrdf/cubic_hermite.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/exp_array.hpp"
#include "bssrdf/models/dipole.hpp"
#include "bssrdf/root_finding.hpp"
#include "bssrdf/single_scattering.hpp"

namespace bssrdf {

namespace {

// Interpolation coordinates: the profile changes evenly in these (see the generator's grid).
double albedo_coordinate(double a) { return std::log(a / (1 - a)); }
double g_coordinate(double g) { return -std::log1p(-g); }
// eta itself: adding-doubling totals are smooth (near linear) in eta down to 1 (measured: the
// cosine of the critical angle, which grows as sqrt(eta - 1), interpolated worse).
double eta_coordinate(double eta) { return eta; }

// Cubic Hermite weights on four nodes for x in [x[i], x[i+1]]: slopes at the interval's ends from
// the three-point (non-uniform) difference, or at the ends of the axis the one-sided three-point
// difference (the secant with only two nodes). The slopes at a
// node are the same from both sides, so the interpolant has continuous first derivatives.
struct Weights {
  std::array<std::size_t, 4> node{};
  std::array<double, 4> w{};
  int count = 0;
};

// `axis` holds the nodes, `f` maps them (and `at`) to the interpolation coordinate.
Weights hermite_weights(const std::vector<double>& axis, double (*f)(double), double at_value) {
  Weights out;
  const std::size_t n = axis.size();
  if (n == 1) {
    out.node[0] = 0;
    out.w[0] = 1;
    out.count = 1;
    return out;
  }
  std::size_t i = static_cast<std::size_t>(std::upper_bound(axis.begin(), axis.end(), at_value) - axis.begin());
  i = std::clamp<std::size_t>(i, 1, n - 1) - 1;  // interval [axis[i], axis[i+1]]
  // The four coordinates around it (only those that exist are read).
  double xs[4] = {0, f(axis[i]), f(axis[i + 1]), 0};
  if (i > 0) xs[0] = f(axis[i - 1]);
  if (i + 2 < n) xs[3] = f(axis[i + 2]);
  const double at = f(at_value);
  const auto x = [&](std::size_t j) { return xs[j + 1 - i]; };
  const double h = x(i + 1) - x(i), t = std::clamp((at - x(i)) / h, 0.0, 1.0);
  const double h00 = (2 * t - 3) * t * t + 1, h01 = (3 - 2 * t) * t * t;
  const double h10 = ((t - 2) * t + 1) * t * h, h11 = (t - 1) * t * t * h;
  // Coefficients of f[i-1], f[i], f[i+1], f[i+2].
  double c[4] = {0, h00, h01, 0};
  // Slope at x[i]: secant weights on (f[i+1] - f[i]) / h and, inside, (f[i] - f[i-1]) / h0.
  if (i > 0) {
    const double h0 = x(i) - x(i - 1), a = h / (h0 + h), b = h0 / (h0 + h);  // a: left secant
    c[0] += h10 * (-a / h0);
    c[1] += h10 * (a / h0 - b / h);
    c[2] += h10 * (b / h);
  } else if (i + 2 < n) {
    // First interval: the slope of the parabola through the first three nodes (the secant alone
    // missed a curved end by up to 0.6 % in the total, g between 0 and 0.2).
    const double h2 = x(i + 2) - x(i + 1);
    c[1] += h10 * (-(2 * h + h2) / (h * (h + h2)));
    c[2] += h10 * ((h + h2) / (h * h2));
    c[3] += h10 * (-h / (h2 * (h + h2)));
  } else {
    c[1] += h10 * (-1 / h);
    c[2] += h10 * (1 / h);
  }
  if (i + 2 < n) {
    const double h2 = x(i + 2) - x(i + 1), a = h2 / (h + h2), b = h / (h + h2);  // a: left secant
    c[1] += h11 * (-a / h);
    c[2] += h11 * (a / h - b / h2);
    c[3] += h11 * (b / h2);
  } else if (i > 0) {
    // Last interval: the slope of the parabola through the last three nodes, at the last.
    const double h0 = x(i) - x(i - 1);
    c[0] += h11 * (h / (h0 * (h0 + h)));
    c[1] += h11 * (-(h0 + h) / (h0 * h));
    c[2] += h11 * ((2 * h + h0) / (h * (h0 + h)));
  } else {
    c[1] += h11 * (-1 / h);
    c[2] += h11 * (1 / h);
  }
  for (int k = 0; k < 4; ++k) {
    const std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) - 1 + k;
    if (j < 0 || j >= static_cast<std::ptrdiff_t>(n) || c[k] == 0) continue;
    out.node[out.count] = static_cast<std::size_t>(j);
    out.w[out.count] = c[k];
    ++out.count;
  }
  return out;
}

struct NodeWeights {
  Weights a, g, e;
  Weights e_total;  // on the totals' eta axis (ExactTable::ln_total_eta)
};

NodeWeights weights_at(const ExactTable& table, double albedo_prime, double g, double eta) {
  const ValidityReport outside = exact_domain(table, albedo_prime, g, eta);
  if (!outside.empty()) {
    const ValidityNote& note = outside.front();
    const std::string field = note.code == "exact_albedo" ? "albedo'" : note.code == "exact_g" ? "g" : "eta";
    const double value = note.code == "exact_albedo" ? albedo_prime : note.code == "exact_g" ? g : eta;
    const auto range = note.code == "exact_albedo" ? exact_albedo_range(table)
                       : note.code == "exact_g"    ? exact_g_range(table)
                                                   : exact_eta_range(table);
    throw InvalidInput(field, format_number(value),
                       format_number(range.first) + " to " + format_number(range.second) +
                           " (the exact model's domain; outside it use the Monte Carlo reference: bssrdf reference)");
  }
  // Above the last albedo node the last node's values stand here (AboveLastNode continues them).
  return {hermite_weights(table.albedo_prime, albedo_coordinate, std::min(albedo_prime, table.albedo_prime.back())),
          hermite_weights(table.g, g_coordinate, g), hermite_weights(table.eta, eta_coordinate, eta),
          hermite_weights(table.ln_total_eta(), eta_coordinate, eta)};
}

double interpolated_ln_total(const ExactTable& table, const NodeWeights& w) {
  double sum = 0;
  for (int e = 0; e < w.e_total.count; ++e)
    for (int gi = 0; gi < w.g.count; ++gi)
      for (int a = 0; a < w.a.count; ++a)
        sum += w.e_total.w[e] * w.g.w[gi] * w.a.w[a] *
               table.ln_total[table.node(w.e_total.node[e], w.g.node[gi], w.a.node[a])];
  return sum;
}

// A small tolerance on the domain's ends, so that values printed and read back stay inside (and
// alpha' computed as sigma_s' / sigma_t' may round just above 1).
bool inside(double v, std::pair<double, double> range) {
  const double slack = 1e-9 * std::max(1.0, std::abs(range.second));
  return v >= range.first - slack && v <= range.second + slack;
}

// The medium of reduced albedo alpha' in transport units (sigma_t' = 1).
Reduced<double> transport_medium(double albedo_prime, double g, double eta) {
  return reduce(1 - albedo_prime, albedo_prime / (1 - g), g, eta);
}

// ln y_ss of a medium (transport units) at the radii e^{ln_r0 + k d_ln_r}, k < n, by the log-grid
// integral. -inf where R_ss is below the smallest double (sigma_t r x_c > ~745), as the table
// generator's integral (the 96-point rule in doubles) had it: the table's y holds no single
// scattering there.
std::vector<double> single_scattering_normal(const Reduced<double>& m, double ln_r0, double d_ln_r, std::size_t n) {
  // R_ss < sigma_s / r e^{-sigma_t r x_c}: the radii beyond that bound's underflow need no integral.
  const double x_c = critical_exit_ratio(m.eta);
  const double ln_smallest = std::log(std::numeric_limits<double>::denorm_min());
  const auto ln_r = [&](std::size_t k) { return ln_r0 + d_ln_r * static_cast<double>(k); };
  const double ln_sigma_s = std::log(m.sigma_s), growth = std::exp(d_ln_r);
  std::size_t count = 0;
  for (double r = std::exp(ln_r0); count < n && ln_sigma_s - ln_r(count) - m.sigma_t() * r * x_c >= ln_smallest;
       r *= growth)
    ++count;
  std::vector<double> ln_ss = single_scattering_ln_y(m, ln_r0, d_ln_r, count);
  ln_ss.resize(n, -std::numeric_limits<double>::infinity());
  const double ln_two_pi = std::log(2 * std::numbers::pi);
  for (std::size_t k = 0; k < count; ++k)
    if (ln_ss[k] - ln_two_pi - 2 * ln_r(k) < ln_smallest) ln_ss[k] = -std::numeric_limits<double>::infinity();
  return ln_ss;
}

// The same at the radii e^{ln_r0 + k d_ln_r}, k < n (the table's, or its head's below them), by the log
// grid or (the generator's rule) radius by radius.
std::vector<double> single_scattering_row(double ln_r0, double d_ln_r, std::size_t n, const Reduced<double>& m,
                                          SingleScatteringRadii how) {
  if (how == SingleScatteringRadii::log_grid) return single_scattering_normal(m, ln_r0, d_ln_r, n);
  std::vector<double> ln_ss(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double r = std::exp(ln_r0 + d_ln_r * static_cast<double>(k));
    ln_ss[k] = std::log(2 * std::numbers::pi * r * r * single_scattering_reflectance(m, r, 96));
  }
  return ln_ss;
}

// Below the table's first radius r_0 (0.001 transport mfp) the curve continues as a power of r, which
// is right where single scattering has reached its r -> 0 form there, R_ss ~ 1/r (y_ss ~ r), i.e. where
// sigma_t r_0 x_c << 1. In strongly forward media it has not: their mean free path is about (1 - g)
// transport mfp, so at r_0 single scattering is still attenuated (g 0.998, eta 1.6: sigma_t r_0 x_c = 1.4)
// and the first step's slope (1.55 there) continued below r_0 put R at 1e-4 transport mfp 3.3x under
// single scattering alone (23 against 76 per mfp^2 at alpha' 0.9927, g 0.998, eta 1.604, where fresh
// Monte Carlo's disc r < 0.001 has a mean R of 28.4 +- 3.7, the model 11.0, now 14.7). There the curve
// gains radii below r_0, at the table's step,
// down to where sigma_t r x_c = 0.05 (single scattering within 5 % of its limit form): y = y_ss, exact,
// plus r_0's multiple scattering y - y_ss continued flat in R, y ~ r^2 (its r -> 0 form: multiple
// scattering's R is at most logarithmic there; the first step's slope, noise at these nodes, is not
// trusted below r_0). How many such radii (0 up to g ~ 0.93).
std::size_t head_radii(const Reduced<double>& m, double ln_r0, double d_ln_r) {
  constexpr double kAttenuation = 0.05;
  const double onset = m.sigma_t() * std::exp(ln_r0) * critical_exit_ratio(m.eta) / kAttenuation;
  return onset > 1 ? static_cast<std::size_t>(std::ceil(std::log(onset) / d_ln_r)) : 0;
}

// Prepends `count` radii to ln y (whose first radius is e^{ln_r0}) as head_radii describes. Returns a
// in y = y_first (a x + (1 - a) x^2), x = r / r_first, the curve below the new first radius: single
// scattering's y_ss(r_first) x (q - (q - 1) x), q its r -> 0 limit over its value there (its own form
// is 1 - O(rho ln rho): 17 % under the limit where sigma_t r x_c = 0.05; this is exact at both ends and
// within ~1 % between), and multiple scattering's x^2.
double prepend_head(const Reduced<double>& m, double ln_r0, double d_ln_r, std::size_t count, SingleScatteringRadii how,
                    std::vector<double>& ln_y) {
  const double ln_head0 = ln_r0 - d_ln_r * static_cast<double>(count);
  const std::vector<double> ln_ss = single_scattering_row(ln_head0, d_ln_r, count + 2, m, how);
  // r_0's multiple scattering, flat in R below it (none where single scattering is all of y there).
  const double ms0 = std::max(0.0, std::exp(ln_y[0]) - std::exp(ln_ss[count]));
  std::vector<double> head(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double below = d_ln_r * static_cast<double>(count - k);  // ln(r_0 / r)
    head[k] = std::log(std::exp(ln_ss[k]) + ms0 * std::exp(-2 * below));
  }
  ln_y.insert(ln_y.begin(), head.begin(), head.end());
  const double limit = 2 * std::numbers::pi * m.sigma_s * single_scattering_singular_coefficient(m.g, m.eta) *
                       std::exp(ln_head0);  // y_ss -> this x
  return limit / std::exp(ln_y[0]);
}

// ln y interpolated: the sum over the weights' (eta, g, albedo) nodes of weight x the node's ln y, per
// radius, into `out`. Up to 64 rows are summed (most of a build in the table): a copy per vector width, in
// which each radius adds its rows in the same order, so the result does not depend on the processor.
__attribute__((target_clones("avx2", "default"))) void interpolate_rows(const ExactTable& table, const Weights& we,
                                                                        const Weights& wg, const Weights& wa,
                                                                        std::vector<double>& out) {
  constexpr std::size_t kMostRows = 4 * 4 * 4;  // Weights name at most four nodes on each axis
  std::array<const float*, kMostRows> rows{};
  std::array<double, kMostRows> weights{};
  std::size_t count = 0;
  for (int e = 0; e < we.count; ++e)
    for (int gi = 0; gi < wg.count; ++gi)
      for (int a = 0; a < wa.count; ++a) {
        weights[count] = we.w[e] * wg.w[gi] * wa.w[a];
        rows[count++] = &table.ln_y[table.index(we.node[e], wg.node[gi], wa.node[a], 0)];
      }
  // Four rows a pass (fewer loads and stores of `out`), added one after another as a pass per row would.
  const std::size_t n = table.radii;
  out.assign(n, 0.0);
  std::size_t j = 0;
  for (; j + 4 <= count; j += 4) {
    const float *r0 = rows[j], *r1 = rows[j + 1], *r2 = rows[j + 2], *r3 = rows[j + 3];
    const double w0 = weights[j], w1 = weights[j + 1], w2 = weights[j + 2], w3 = weights[j + 3];
    for (std::size_t k = 0; k < n; ++k) out[k] = (((out[k] + w0 * r0[k]) + w1 * r1[k]) + w2 * r2[k]) + w3 * r3[k];
  }
  for (; j < count; ++j)
    for (std::size_t k = 0; k < n; ++k) out[k] += weights[j] * rows[j][k];
}

// A row of uniformly spaced values p[0..n) read at k + shift for k = 0, 1, ...: Catmull-Rom, linear
// below the first value. The shift is the same for every k, so inside the row the cubic's four
// weights are too: computed once.
class ShiftedRow {
 public:
  ShiftedRow(const std::vector<double>& row, double shift)
      : p_(row.data()),
        n_(static_cast<std::ptrdiff_t>(row.size())),
        shift_(shift),
        base_(static_cast<std::ptrdiff_t>(std::floor(shift))),
        w_(catmull_rom_weights(shift - static_cast<double>(base_))) {}
  double operator()(std::size_t k) const {
    const std::ptrdiff_t i = static_cast<std::ptrdiff_t>(k) + base_;
    if (i >= 1 && i + 2 < n_) return w_[0] * p_[i - 1] + w_[1] * p_[i] + w_[2] * p_[i + 1] + w_[3] * p_[i + 2];
    const double x = static_cast<double>(k) + shift_;  // an end: one-sided slopes, or linear below
    if (x <= 0) return p_[0] + (p_[1] - p_[0]) * x;
    const std::size_t j = std::min(static_cast<std::size_t>(n_ - 2), static_cast<std::size_t>(x));
    return catmull_rom(p_, static_cast<std::size_t>(n_), j, x - static_cast<double>(j));
  }

 private:
  const double* p_;
  std::ptrdiff_t n_;
  double shift_;
  std::ptrdiff_t base_;
  std::array<double, 4> w_;  // of p[i - 1 .. i + 2]
};

// Below the first albedo node (0.001; 8.9e-5 in a version-7 table) down to alpha' = 0 (R = 0): single scattering is the
// exact integral at the medium, and multiple scattering follows from the first two nodes by the order-of-scattering
// series. In units of the medium's own mean free path (rho = sigma_t r) a medium of albedo alpha has y(rho) = sum_k
// alpha^k Y_k(rho), Y_k depending on g and eta only, so at each rho the multiple scattering over alpha^2 is a smooth
// function of alpha, Y_2 + alpha Y_3 + ...: read at the nodes' own rho = sigma_t,j r and continued to the medium's
// alpha (extrapolate). (At g 0.998 the first node's alpha is 0.33 and its radius scale sigma_t 1.5: scaling the node's
// multiple scattering by (alpha / alpha_0)^2 in place, the continuation before this one, missed fresh Monte Carlo
// by 2.9 % in total and 11 % in the far field.)
struct BelowFirstNode {
  Reduced<double> medium;
  std::array<Reduced<double>, 2> node;  // the first two albedo nodes at (g, eta)
  double t;                             // (alpha - alpha_0) / (alpha_1 - alpha_0), negative
  double ss_per_albedo;                 // single-scattering total per unit albedo (g, eta only)
  BelowFirstNode(const ExactTable& table, double albedo_prime, double g, double eta)
      : medium(transport_medium(albedo_prime, g, eta)),
        node{transport_medium(table.albedo_prime[0], g, eta), transport_medium(table.albedo_prime[1], g, eta)},
        t((medium.albedo() - node[0].albedo()) / (node[1].albedo() - node[0].albedo())),
        ss_per_albedo(single_scattering_total(1.0, g, eta)) {}
  // ln of the medium's multiple scattering over alpha^2 from the nodes' (ln_ms0, ln_ms1): linear in
  // alpha through the two (the far field's decay rate is smooth in alpha, so a straight line in the
  // logarithm, not in the value, continues it; near alpha = 0 both tend to ln Y_2). Where the second
  // node's value is not positive (the near field's rounding) the first node's alone.
  double extrapolate(double ln_ms0, double ln_ms1) const {
    return std::isnan(ln_ms1) ? ln_ms0 : (1 - t) * ln_ms0 + t * ln_ms1;
  }
  // The nodes' multiple scattering is their interpolated total less the exact single scattering at
  // the medium's (g, eta). Where that is not positive (a version-7 table's first nodes at moderate g,
  // where multiple scattering is ~1e-4 of the total, below the interpolation's rounding of the single
  // scattering in g and eta), the node holds none measurable, and neither does the medium below it:
  // its total is its single scattering (as the profile's branch for that case).
  double total(const ExactTable& table, NodeWeights w) const {
    std::array<double, 2> ms{};
    for (std::size_t j = 0; j < 2; ++j) {
      w.a = {{j}, {1.0}, 1};
      const double alpha_j = node[j].albedo();
      const double multiple = std::exp(interpolated_ln_total(table, w)) - ss_per_albedo * alpha_j;
      ms[j] = multiple > 0 ? std::log(multiple) - 2 * std::log(alpha_j) : std::numeric_limits<double>::quiet_NaN();
    }
    const double alpha = medium.albedo();
    if (std::isnan(ms[0])) return ss_per_albedo * alpha;
    return ss_per_albedo * alpha + std::exp(extrapolate(ms[0], ms[1])) * alpha * alpha;
  }
  // ln y at the table's radii. At the medium's rho each node's y is read from its row (the table's y
  // at (g, eta)), and its single scattering is alpha_j Y_1(rho) =
  // (alpha_j / alpha) y_ss(r): the split is made in linear terms, so the table's y is met exactly at the first node
  // even where it lies a rounding (or the generator's 96-point rule, ~1e-4 at r = 0.001) below the exact single
  // scattering.
  void profile(const ExactTable& table, const NodeWeights& w, SingleScatteringRadii how,
               std::vector<double>& ln_y) const {
    const std::size_t n = table.radii;
    std::array<std::vector<double>, 2> rows;
    for (std::size_t j = 0; j < 2; ++j) interpolate_rows(table, w.e, w.g, {{j}, {1.0}, 1}, rows[j]);
    // Node j's rho = sigma_t,j r equals the medium's at r sigma_t / sigma_t,j: its row read there.
    const auto read_at_medium_rho = [&](std::size_t j) {
      return ShiftedRow(rows[j], std::log(medium.sigma_t() / node[j].sigma_t()) / table.d_ln_r);
    };
    const std::array<ShiftedRow, 2> node_y{read_at_medium_rho(0), read_at_medium_rho(1)};
    const std::vector<double> ln_ss = single_scattering_row(table.ln_r0, table.d_ln_r, n, medium, how);
    const double alpha = medium.albedo();
    // (alpha_j / alpha): node j's single scattering over the medium's.
    const std::array<double, 2> ss_ratio{node[0].albedo() / alpha, node[1].albedo() / alpha};
    // The multiple scattering over alpha^2, ln-linear in alpha, as a factor on the first node's:
    // MS / MS_0 = (alpha / alpha_0)^2 (MS_1 alpha_0^2 / (MS_0 alpha_1^2))^t.
    const double ln_to_medium = 2 * std::log(1 / ss_ratio[0]);
    const double ln_between = 2 * std::log(ss_ratio[0] / ss_ratio[1]);
    const double ln_alpha = std::log(alpha);
    const std::array<double, 2> ln_alpha_node{std::log(node[0].albedo()), std::log(node[1].albedo())};
    ln_y.resize(n);
    constexpr double kNone = -std::numeric_limits<double>::infinity();
    const auto far = [&](std::size_t k) { return ln_ss[k] == kNone; };  // no single scattering left
    // The exponentials in two vectorised passes (exp_array). First, in units of the first node's y at
    // each radius (the two nodes' y differ by a few e-folds where single scattering has not
    // underflowed): the medium's single scattering u = y_ss / y_0 and the second node's d = y_1 / y_0.
    std::vector<double> v0(n), u(n), d(n);
    for (std::size_t k = 0; k < n; ++k) {
      v0[k] = node_y[0](k);
      const double v1 = node_y[1](k);
      if (far(k))  // far out the nodes' tails differ by more than a double's range: in logarithms
        ln_y[k] = extrapolate(v0[k] - 2 * ln_alpha_node[0], v1 - 2 * ln_alpha_node[1]) + 2 * ln_alpha;
      u[k] = far(k) ? 0.0 : ln_ss[k] - v0[k];
      d[k] = far(k) ? 0.0 : v1 - v0[k];
    }
    exp_array(u.data(), u.data(), n);
    exp_array(d.data(), d.data(), n);
    // Then each node's multiple scattering over y_0, m_j = y_j / y_0 - (alpha_j / alpha) u, and the
    // medium's, m_0 (m_1 alpha_0^2 / (m_0 alpha_1^2))^t (alpha / alpha_0)^2: its exponent into d.
    // (Logarithms, too, in vectorised passes: m_1 / m_0 into d, NaN where the second node's is not positive.)
    for (std::size_t k = 0; k < n; ++k) {
      const double m0 = 1 - ss_ratio[0] * u[k], m1 = d[k] - ss_ratio[1] * u[k];
      d[k] = m0 > 0 && m1 > 0 && std::isfinite(m1) ? m1 / m0 : std::numeric_limits<double>::quiet_NaN();
    }
    log_array(d.data(), d.data(), n);
    for (std::size_t k = 0; k < n; ++k)  // the second node's not positive: the first's alone
      d[k] = std::isnan(d[k]) ? ln_to_medium : t * (d[k] + ln_between) + ln_to_medium;
    exp_array(d.data(), d.data(), n);
    const double ratio = 1 / ss_ratio[0];
    for (std::size_t k = 0; k < n; ++k) {
      const double m0 = 1 - ss_ratio[0] * u[k];
      // Where the first node is all single scattering within rounding (the near field), its y scaled,
      // y = y_ss (1 - alpha / alpha_0) + (alpha / alpha_0)^2 y_0, which meets it at alpha_0.
      u[k] = m0 > 0 ? m0 * d[k] + u[k] : u[k] * (1 - ratio) + ratio * ratio;
    }
    log_array(u.data(), u.data(), n);
    for (std::size_t k = 0; k < n; ++k)
      if (!far(k)) ln_y[k] = v0[k] + u[k];
  }
};

// Above the last albedo node (0.9999) up to 1 the model continues with diffusion where diffusion
// is exact, the far field of a nearly conservative medium: R(r) is the last node's times the
// classical dipole's ratio R_d(r; alpha') / R_d(r; alpha'_0), which is 1 in the near field (the
// transport there does not see absorption of 1e-4) and the ratio of diffusion's tails far out
// (sigma_tr = sqrt(3 (1 - alpha')) in transport units; the exact asymptotic decay rate differs from it
// by a relative O(1 - alpha') < 1e-4). The total follows the half-space's albedo problem near
// conservative scattering, 1 - T = c1 s + c2 s^2 in s = sqrt(1 - alpha'), through the last two nodes'
// totals to T = 1 at alpha' = 1, where no light is absorbed and a half-space returns all that entered.
struct AboveLastNode {
  Reduced<double> medium, node;  // transport units
  double s, s_last, s_before;    // sqrt(1 - alpha') of the medium, the last node and the one before it
  AboveLastNode(const ExactTable& table, double albedo_prime, double g, double eta)
      : medium(transport_medium(albedo_prime, g, eta)),
        node(transport_medium(table.albedo_prime.back(), g, eta)),
        s(std::sqrt(std::max(0.0, 1 - albedo_prime))),
        s_last(std::sqrt(1 - table.albedo_prime.back())),
        s_before(std::sqrt(1 - table.albedo_prime[table.albedo_prime.size() - 2])) {}
  // c1, c2 of 1 - T = c1 s + c2 s^2 from the totals at the last two nodes.
  static std::pair<double, double> coefficients(double s1, double t1, double s0, double t0) {
    const double c2 = ((1 - t0) / s0 - (1 - t1) / s1) / (s0 - s1);
    return {(1 - t1) / s1 - c2 * s1, c2};
  }
  double total(double t_last, double t_before) const {
    const auto [c1, c2] = coefficients(s_last, t_last, s_before, t_before);
    return 1 - (c1 + c2 * s) * s;
  }
  // The alpha' whose total is `total` (between the last node's and 1).
  double albedo_prime_for(double total, double t_last, double t_before) const {
    const auto [c1, c2] = coefficients(s_last, t_last, s_before, t_before);
    const double loss = std::max(0.0, 1 - total);
    const double root = c2 != 0 ? (-c1 + std::sqrt(c1 * c1 + 4 * c2 * loss)) / (2 * c2) : loss / c1;
    return 1 - root * root;
  }
  void continue_profile(const ExactTable& table, std::vector<double>& ln_y) const {
    const auto sm = classical_dipole::sources(medium), sn = classical_dipole::sources(node);  // once, not per radius
    std::vector<double> ratio(ln_y.size());
    for (std::size_t k = 0; k < ln_y.size(); ++k) {
      const double r = table.radius(k);
      ratio[k] = classical_dipole::reflectance(sm, medium.albedo_prime, r) /
                 classical_dipole::reflectance(sn, node.albedo_prime, r);
    }
    log_array(ratio.data(), ratio.data(), ratio.size());  // the logarithms in one vectorised pass
    for (std::size_t k = 0; k < ln_y.size(); ++k) ln_y[k] += ratio[k];
  }
};

// The last two albedo nodes' totals at the weights' g and eta (AboveLastNode's fit).
std::pair<double, double> last_totals(const ExactTable& table, NodeWeights w) {
  const std::size_t last = table.albedo_prime.size() - 1;
  w.a = {{last}, {1.0}, 1};
  const double t_last = std::exp(interpolated_ln_total(table, w));
  w.a = {{last - 1}, {1.0}, 1};
  return {t_last, std::exp(interpolated_ln_total(table, w))};
}

}  // namespace

std::pair<double, double> exact_albedo_range(const ExactTable&) { return {0.0, 1.0}; }
std::pair<double, double> exact_g_range(const ExactTable& table) { return {table.g.front(), table.g.back()}; }
std::pair<double, double> exact_eta_range(const ExactTable& table) { return {table.eta.front(), table.eta.back()}; }

ValidityReport exact_domain(const ExactTable& table, double albedo_prime, double g, double eta) {
  ValidityReport report;
  const auto check = [&](const char* code, const char* name, double v, std::pair<double, double> range) {
    if (!inside(v, range))
      report.push_back({Severity::invalid, code,
                        std::string(name) + " = " + format_number(v) + " is outside the exact model's domain (" +
                            format_number(range.first) + " to " + format_number(range.second) + ")"});
  };
  // Below the first albedo node the model continues exactly (BelowFirstNode), down to 0; above the
  // last, by diffusion (AboveLastNode), up to 1; in g the table's nodes reach 0.999.
  check("exact_albedo", "alpha'", albedo_prime, exact_albedo_range(table));
  check("exact_g", "g", g, exact_g_range(table));
  check("exact_eta", "eta", eta, exact_eta_range(table));
  return report;
}

double exact_total(const ExactTable& table, double albedo_prime, double g, double eta) {
  const NodeWeights w = weights_at(table, albedo_prime, g, eta);
  if (albedo_prime > table.albedo_prime.back()) {
    const auto [t_last, t_before] = last_totals(table, w);
    return AboveLastNode(table, albedo_prime, g, eta).total(t_last, t_before);
  }
  if (albedo_prime == 0) return 0;
  if (albedo_prime < table.albedo_prime.front()) return BelowFirstNode(table, albedo_prime, g, eta).total(table, w);
  return std::exp(interpolated_ln_total(table, w));
}

double exact_albedo_prime_from_total(const ExactTable& table, double total, double g, double eta) {
  const double lo_a = table.albedo_prime.front(), hi_a = table.albedo_prime.back();
  const double lo_t = exact_total(table, lo_a, g, eta), hi_t = exact_total(table, hi_a, g, eta);
  if (!(total >= lo_t && total <= 1))
    throw InvalidInput("total_reflectance", format_number(total),
                       "[" + format_number(lo_t) + ", 1] for the exact model at g = " + format_number(g) +
                           ", eta = " + format_number(eta) + " (alpha' " + format_number(lo_a) + " to 1)");
  if (total > hi_t) {  // above the last node: the continuation's own inverse
    const auto [t_last, t_before] = last_totals(table, weights_at(table, hi_a, g, eta));
    return AboveLastNode(table, hi_a, g, eta).albedo_prime_for(total, t_last, t_before);
  }
  // ln T is smooth and increasing in u = logit(alpha'): a handful of evaluations.
  const auto from = [](double u) { return 1 / (1 + std::exp(-u)); };
  const double target = std::log(total);
  const auto residual = [&](double u) {
    return std::log(exact_total(table, std::clamp(from(u), lo_a, hi_a), g, eta)) - target;
  };
  const double u = illinois_root(residual, albedo_coordinate(lo_a), albedo_coordinate(hi_a), std::log(lo_t) - target,
                                 std::log(hi_t) - target, 1e-13, 0.0, 1e-13)
                       .x;
  return std::clamp(from(u), lo_a, hi_a);
}

ExactProfile::ExactProfile(const ExactTable& table, double albedo_prime, double g, double eta,
                           SingleScatteringRadii single_scattering)
    : albedo_prime_(albedo_prime), g_(g), eta_(eta), ln_r0_(table.ln_r0), d_ln_r_(table.d_ln_r) {
  const NodeWeights w = weights_at(table, albedo_prime, g, eta);
  if (albedo_prime == 0) return;  // nothing scatters: R = 0, total() = 0
  std::optional<BelowFirstNode> below;
  if (albedo_prime < table.albedo_prime.front()) {
    below.emplace(table, albedo_prime, g, eta);
    below->profile(table, w, single_scattering, ln_y_);
  } else {
    interpolate_rows(table, w.e, w.g, w.a, ln_y_);
  }
  std::optional<AboveLastNode> above;
  if (albedo_prime > table.albedo_prime.back()) {
    above.emplace(table, albedo_prime, g, eta);
    above->continue_profile(table, ln_y_);
  }
  const Reduced<double> medium = transport_medium(albedo_prime, g, eta);
  if (const std::size_t head = head_radii(medium, ln_r0_, d_ln_r_); head > 0) {
    head_linear_ = prepend_head(medium, ln_r0_, d_ln_r_, head, single_scattering, ln_y_);
    ln_r0_ -= d_ln_r_ * static_cast<double>(head);
  }
  const std::size_t radii = ln_y_.size();
  // Below the first radius y = 2 pi r^2 R continues as a power of r, beyond the last as an exponential
  // tail in r: both with the slope of the curve's end. The power is at least 1: as r -> 0 single
  // scattering's R ~ 1/r is the strongest singularity (multiple scattering's is at most logarithmic,
  // y ~ r^2), so y falls at least as fast as r. Nodes whose first radii hold Monte Carlo noise
  // (g 0.995, 0.999: 7 % at the first radius) gave first-step slopes down to 0.48, and the disc
  // r < 0.001 twice its energy (alpha' 0.1375, g 0.997: 1.77 times the Monte Carlo's mean R there).
  head_slope_ = std::max(1.0, (ln_y_[1] - ln_y_[0]) / d_ln_r_);
  const double r_last = std::exp(ln_r0_ + d_ln_r_ * static_cast<double>(radii - 1));
  const double r_before = std::exp(ln_r0_ + d_ln_r_ * static_cast<double>(radii - 2));
  tail_slope_ = std::min(-1e-3, (ln_y_[radii - 1] - ln_y_[radii - 2]) / (r_last - r_before));

  // Normalise to the interpolated adding-doubling total: integrate y over ln r (Simpson on four
  // sub-intervals per radius step, plus the head and tail in closed form).
  // Every exponential at once (exp_array, vectorised): y at the radii, then at the steps' quarters.
  std::vector<double> y(4 * radii - 3);
  std::copy(ln_y_.begin(), ln_y_.end(), y.begin());
  for (std::size_t k = 0; k + 1 < radii; ++k)
    for (std::size_t j = 1; j < 4; ++j)
      y[radii + 3 * k + j - 1] = catmull_rom(ln_y_.data(), radii, k, 0.25 * static_cast<double>(j));
  exp_array(y.data(), y.data(), y.size());
  cumulative_.assign(radii, 0.0);
  double sum = y[0] * head_energy(1.0);
  cumulative_[0] = sum;
  const double h = d_ln_r_ / 4;
  for (std::size_t k = 0; k + 1 < radii; ++k) {
    const double* quarter = &y[radii + 3 * k];
    sum += (y[k] + 4 * quarter[0] + 2 * quarter[1] + 4 * quarter[2] + y[k + 1]) * h / 3;
    cumulative_[k + 1] = sum;
  }
  // Tail: int_{r_N}^inf y_N e^{b (r - r_N)} dr / r <= y_N / (|b| r_N); the table ends far out
  // (99.9 % of the energy inside), so the bound is the value.
  sum += std::exp(ln_y_[radii - 1]) / (-tail_slope_ * r_last);
  total_ = std::exp(interpolated_ln_total(table, w));
  if (below) total_ = below->total(table, w);
  if (above) {
    const auto [t_last, t_before] = last_totals(table, w);
    total_ = above->total(t_last, t_before);
  }
  const double scale = total_ / sum, ln_scale = std::log(scale);
  for (auto& v : ln_y_) v += ln_scale;
  for (auto& c : cumulative_) c *= scale;
}

double ExactProfile::head_ln_shape(double ln_x) const {
  if (head_linear_ == 0) return head_slope_ * ln_x;
  const double x = std::exp(ln_x);
  return std::log(x * (head_linear_ + (1 - head_linear_) * x));
}

double ExactProfile::head_energy(double x) const {
  if (head_linear_ == 0) return std::pow(x, head_slope_) / head_slope_;
  return x * (head_linear_ + (1 - head_linear_) * x / 2);
}

double ExactProfile::ln_y(double ln_r) const {
  if (ln_y_.empty()) return -std::numeric_limits<double>::infinity();  // alpha' = 0
  const double f = (ln_r - ln_r0_) / d_ln_r_;
  const std::size_t n = ln_y_.size();
  if (f <= 0) return ln_y_[0] + head_ln_shape(ln_r - ln_r0_);
  if (f >= static_cast<double>(n - 1)) {
    const double r_last = std::exp(ln_r0_ + d_ln_r_ * static_cast<double>(n - 1));
    return ln_y_[n - 1] + tail_slope_ * (std::exp(ln_r) - r_last);
  }
  const auto i = static_cast<std::size_t>(f);
  return catmull_rom(ln_y_.data(), n, i, f - static_cast<double>(i));
}

double ExactProfile::reflectance(double r) const {
  if (ln_y_.empty()) return 0;  // alpha' = 0
  if (!(r > 0)) return r == 0 ? std::numeric_limits<double>::infinity() : 0.0;
  return std::exp(ln_y(std::log(r))) / (2 * std::numbers::pi * r * r);
}

double ExactProfile::cumulative(double r) const {
  if (!(r > 0) || ln_y_.empty()) return 0;
  const double ln_r = std::log(r);
  const double f = (ln_r - ln_r0_) / d_ln_r_;
  const std::size_t n = ln_y_.size();
  if (f <= 0) return std::exp(ln_y_[0]) * head_energy(std::exp(ln_r - ln_r0_));
  if (f >= static_cast<double>(n - 1)) {
    // Tail from the last radius: the closed form of the normalising bound, less what lies beyond r.
    const double r_last = std::exp(ln_r0_ + d_ln_r_ * static_cast<double>(n - 1));
    const double beyond_last = std::exp(ln_y_[n - 1]) / (-tail_slope_ * r_last);
    const double beyond_r = std::exp(ln_y(ln_r)) / (-tail_slope_ * r);
    return std::min(total_, cumulative_[n - 1] + std::max(0.0, beyond_last - beyond_r));
  }
  const auto i = static_cast<std::size_t>(f);
  const double x0 = ln_r0_ + d_ln_r_ * static_cast<double>(i), span = ln_r - x0;
  // Three-point Gauss-Legendre over the part of the step: the integrand is smooth there.
  static constexpr double kNodes[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
  static constexpr double kWeights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double s = 0;
  for (int j = 0; j < 3; ++j) s += kWeights[j] * std::exp(ln_y(x0 + 0.5 * span * (1 + kNodes[j])));
  return cumulative_[i] + 0.5 * span * s;
}

}  // namespace bssrdf
