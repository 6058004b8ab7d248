#include "bssrdf/lut/projected_profile.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "bssrdf/cubic_hermite.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/exp_array.hpp"
#include "bssrdf/scalar_math.hpp"

namespace bssrdf {
namespace {

constexpr double kNegligible = -745.0;  // ln of the smallest double: R treated as 0 below

double safe_log(double v) { return v > 0 ? std::log(v) : kNegligible; }

// Catmull-Rom in u on the nodes u0 + j h of f; one-sided (linear) at the ends where a neighbour is missing. Always
// inlined: the tables evaluate it millions of times in their loops (lines, half_plane_integrals).
[[gnu::always_inline]] inline double grid_cubic(const std::vector<double>& f, double u0, double h, double u) {
  const double t = (u - u0) / h;
  const auto n = static_cast<std::ptrdiff_t>(f.size());
  // floor(t) where it matters: truncation differs only for t < 0, which the clamp sends to node 0 either way (and it
  // is an instruction, where std::floor is a library call without SSE4.1).
  auto i = static_cast<std::ptrdiff_t>(t);
  i = std::clamp<std::ptrdiff_t>(i, 0, n - 2);
  return catmull_rom(f.data(), f.size(), static_cast<std::size_t>(i), t - static_cast<double>(i));
}

}  // namespace

ProjectedProfile::ProjectedProfile(const Model& model, const Reduced<double>& m) {
  h_ = std::log(10.0) / 64;
  u0_ = std::log(1e-6 * m.ell);
  // R on the grid until the geometric tail estimate of int 2 pi r^2 R d(ln r) is negligible.
  std::vector<double> R;
  double cum = 0, f_prev = 0;
  const double u_stop = std::log(1e8 * m.ell);
  for (double u = u0_;; u += h_) {
    const double r = std::exp(u);
    const double value = model.reflectance(m, r);
    if (!std::isfinite(value))
      throw InvalidInput("profile", "R(" + format_number(r) + ") = " + format_number(value), "finite");
    R.push_back(value);
    const double f = kTwoPi * r * r * std::max(value, 0.0);
    cum += R.size() == 1 ? 0.5 * f : 0.5 * h_ * (f + f_prev);  // first: the inner disc pi r0^2 R(r0)
    cumulative_.push_back(cum);
    const double q = R.size() > 1 && f_prev > 0 ? f / f_prev : 1;
    f_prev = f;
    if ((r > m.ell && q < 1 && f * h_ * q / (1 - q) < 1e-10 * cum) || u > u_stop) break;
  }
  if (!(cum > 0)) throw InvalidInput("profile", "total " + format_number(cum), "> 0");
  total_ = cum;
  const std::size_t n = R.size();
  r_min_ = std::exp(u0_);
  r_max_ = std::exp(u0_ + h_ * static_cast<double>(n - 1));
  log_R_.resize(n);
  for (std::size_t j = 0; j < n; ++j) log_R_[j] = safe_log(R[j]);
  // line(x_j) = 2 int_0^inf R(x cosh s) x cosh s ds = 2 int_{u_j}^inf G(u) K(u - u_j) du with
  // rho = e^u = x cosh s, G = R e^u and K(D) = 1 / sqrt(1 - e^{-2 D}). A smooth window w(D) (1 below
  // D = 0.5, 0 above 1.5, infinitely differentiable between) splits it in two, each by a rule that is
  // exponentially accurate for its part:
  //  - near the line, w times the integrand in s: even and smooth in s, so the trapezoid with step
  //    hs from s = 0 (half weight there) is the rule on the whole line; the integrable singularity of
  //    K at D = 0 never appears. Every node's samples sit at the same offsets in ln r
  //    (ln(x_j cosh s) = u_j + ln cosh s): each sample's Catmull-Rom stencil and weights in the
  //    (ln r, ln R) table, and its window, are computed once, not once per node.
  //  - the rest, (1 - w) G K, vanishes with every derivative where it starts, so the trapezoid in u on
  //    the grid's own nodes needs no end correction, and its weights h K(m h) (1 - w(m h)) are the
  //    same for every node: a sum of products, no exponential per sample (the rule in s alone
  //    sampled all the way out, one exponential each: 90 % of a projection's cost).
  // The split moves line() by at most 6e-7 relative against the rule in s alone, well inside either's
  // difference from an adaptive integral of the model (up to 3e-4 at 8 materials).
  constexpr double kWindowStart = 0.5, kWindowEnd = 1.5;
  const auto far_share = [&](double d) {  // 1 - w(d): 0 up to the start, 1 from the end on
    const double t = (d - kWindowStart) / (kWindowEnd - kWindowStart);
    if (t <= 0) return 0.0;
    if (t >= 1) return 1.0;
    const double a = std::exp(-1 / t), b = std::exp(-1 / (1 - t));
    return a / (a + b);
  };
  struct Sample {
    double offset;                 // ln cosh s / h: grid positions beyond the node
    std::ptrdiff_t i;              // floor(offset)
    std::array<double, 4> weight;  // of log_R at j + i - 1 .. j + i + 2
    double cosh_s;
    double window;  // w(ln cosh s)
  };
  std::vector<Sample> samples;
  const double hs = h_;
  for (int k = 1;; ++k) {
    const double cosh_s = std::cosh(k * hs), d = std::log(cosh_s), offset = d / h_;
    if (d >= kWindowEnd || offset > static_cast<double>(n)) break;
    const auto i = static_cast<std::ptrdiff_t>(std::floor(offset));
    // Catmull-Rom (as cubic()) written as weights of the four nodes around the interval.
    samples.push_back({offset, i, catmull_rom_weights(offset - static_cast<double>(i)), cosh_s, 1 - far_share(d)});
  }
  std::vector<double> far_weight(n, 0.0), G(n);  // by node distance m; R e^u at each node
  for (std::size_t m = 1; m < n; ++m) {
    const double d = h_ * static_cast<double>(m), share = far_share(d);
    if (share > 0) far_weight[m] = h_ * share / std::sqrt(-std::expm1(-2 * d));
  }
  for (std::size_t j = 0; j < n; ++j) G[j] = std::max(R[j], 0.0) * std::exp(u0_ + h_ * static_cast<double>(j));
  std::vector<double> line(n);
  const auto last = static_cast<std::ptrdiff_t>(n) - 1;
  for (std::size_t j = 0; j < n; ++j) {
    const double x = std::exp(u0_ + h_ * static_cast<double>(j));
    double sum = 0.5 * R[j] * x;
    const auto jj = static_cast<std::ptrdiff_t>(j);
    for (const auto& sample : samples) {
      if (static_cast<double>(jj) + sample.offset > static_cast<double>(last)) break;  // beyond r_end: R = 0
      const double rho = x * sample.cosh_s;
      const std::ptrdiff_t first = jj + sample.i - 1;
      if (first < 0 || first + 3 > last) {  // a one-sided stencil at either end of the table
        sum += sample.window * reflectance(rho) * rho;
        continue;
      }
      const double* f = log_R_.data() + first;
      const double v =
          sample.weight[0] * f[0] + sample.weight[1] * f[1] + sample.weight[2] * f[2] + sample.weight[3] * f[3];
      sum += sample.window * (v <= kNegligible ? 0 : std::exp(v)) * rho;
    }
    double far = 0;
    for (std::size_t m = 1; j + m < n; ++m) far += far_weight[m] * G[j + m];
    line[j] = 2 * hs * sum + 2 * far;
  }
  log_line_.resize(n);
  for (std::size_t j = 0; j < n; ++j) log_line_[j] = safe_log(line[j]);
  // half_plane(x_j) = int_{x_j}^inf line(t) t d(ln t), from the far end (trapezoid in ln t).
  half_plane_.assign(n, 0.0);
  for (std::size_t j = n - 1; j-- > 0;) {
    const double t0 = std::exp(u0_ + h_ * static_cast<double>(j)), t1 = std::exp(u0_ + h_ * static_cast<double>(j + 1));
    half_plane_[j] = half_plane_[j + 1] + 0.5 * h_ * (line[j] * t0 + line[j + 1] * t1);
  }
  // Inside the first node line() is taken as constant.
  half_plane_0_ = half_plane_[0] + std::exp(u0_) * line[0];
  // int_0^{x_j} half_plane: the first node's disc by the midpoint of a linear half_plane there, then
  // trapezoid in ln x.
  half_plane_integral_.assign(n, 0.0);
  half_plane_integral_[0] = std::exp(u0_) * 0.5 * (half_plane_0_ + half_plane_[0]);
  for (std::size_t j = 1; j < n; ++j) {
    const double t0 = std::exp(u0_ + h_ * static_cast<double>(j - 1)), t1 = std::exp(u0_ + h_ * static_cast<double>(j));
    half_plane_integral_[j] = half_plane_integral_[j - 1] + 0.5 * h_ * (half_plane_[j - 1] * t0 + half_plane_[j] * t1);
  }
}

double ProjectedProfile::cubic(const std::vector<double>& f, double u) const { return grid_cubic(f, u0_, h_, u); }

double ProjectedProfile::reflectance(double r) const {
  if (r <= r_min()) return std::exp(log_R_.front());
  if (r >= r_max()) return 0;
  const double v = cubic(log_R_, std::log(r));
  return v <= kNegligible ? 0 : std::exp(v);
}

double ProjectedProfile::line(double x) const {
  x = std::abs(x);
  return line(x, x > r_min() && x < r_max() ? std::log(x) : 0.0);
}

double ProjectedProfile::line(double x, double ln_abs_x) const {
  double out;
  lines(&x, &ln_abs_x, &out, 1);
  return out;
}

void ProjectedProfile::lines(const double* x, const double* ln_x, double* out, std::size_t n) const {
  // ln line(x) first, then every exponential in one vectorised pass (exp_array: 0 at or below kNegligible).
  for (std::size_t k = 0; k < n; ++k) {
    const double a = std::abs(x[k]);
    out[k] = a <= r_min() ? log_line_.front() : a >= r_max() ? kNegligible : grid_cubic(log_line_, u0_, h_, ln_x[k]);
  }
  exp_array(out, out, n);
}

double ProjectedProfile::half_plane(double x) const {
  if (x < 0) return total_ - half_plane(-x);
  if (x <= r_min()) return half_plane_0_ - x * std::exp(log_line_.front());
  if (x >= r_max()) return 0;
  return std::max(0.0, cubic(half_plane_, std::log(x)));
}

double ProjectedProfile::half_plane_integral(double x) const {
  return half_plane_integral(x, x > r_min() && x < r_max() ? std::log(x) : 0.0);
}

double ProjectedProfile::half_plane_integral(double x, double ln_x) const {
  double out;
  half_plane_integrals(&x, &ln_x, &out, 1);
  return out;
}

void ProjectedProfile::half_plane_integrals(const double* x, const double* ln_x, double* out, std::size_t n) const {
  for (std::size_t k = 0; k < n; ++k) {
    if (x[k] <= 0)
      out[k] = 0;
    else if (x[k] <= r_min())
      out[k] = x[k] * 0.5 * (half_plane_0_ + half_plane(x[k]));
    else if (x[k] >= r_max())
      out[k] = half_plane_integral_.back();  // half_plane is 0 beyond
    else
      out[k] = grid_cubic(half_plane_integral_, u0_, h_, ln_x[k]);
  }
}

double ProjectedProfile::radius_for_fraction(double fraction) const {
  if (!(fraction > 0 && fraction < 1)) throw InvalidInput("fraction", format_number(fraction), "0 < fraction < 1");
  const double target = fraction * total_;
  const auto it = std::lower_bound(cumulative_.begin(), cumulative_.end(), target);
  if (it == cumulative_.begin()) return r_min();
  if (it == cumulative_.end()) return r_max();
  const auto j = static_cast<std::size_t>(it - cumulative_.begin());
  const double t = (target - cumulative_[j - 1]) / (cumulative_[j] - cumulative_[j - 1]);
  return std::exp(u0_ + h_ * (static_cast<double>(j - 1) + t));
}

double ProjectedProfile::line_width_for_fraction(double fraction) const {
  if (!(fraction > 0 && fraction < 1)) throw InvalidInput("fraction", format_number(fraction), "0 < fraction < 1");
  // half_plane decreases: bisect in ln x for half_plane(x) = (1 - fraction) total / 2.
  const double target = 0.5 * (1 - fraction) * total_;
  double lo = std::log(r_min()), hi = std::log(r_max());
  if (half_plane(r_min()) <= target) return r_min();
  for (int k = 0; k < 100; ++k) {
    const double mid = 0.5 * (lo + hi);
    (half_plane(std::exp(mid)) > target ? lo : hi) = mid;
  }
  return std::exp(hi);
}

std::vector<std::optional<ProjectedProfile>> project_channels(const Medium& medium, const Model& model) {
  std::vector<std::optional<ProjectedProfile>> out(medium.channels());
  bool any = false;
  for (std::size_t c = 0; c < medium.channels(); ++c)
    if (medium.sigma_s[c] > 0) {
      out[c].emplace(model, medium.reduced(c));
      any = true;
    }
  if (!any)
    throw InvalidInput("profile", "0 in every channel", "a medium that scatters (sigma_s > 0) in at least one channel");
  return out;
}

}  // namespace bssrdf
