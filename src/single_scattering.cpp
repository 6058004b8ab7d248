#include "bssrdf/single_scattering.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>

#include "bssrdf/exp_array.hpp"
#include "bssrdf/fresnel.hpp"
#include "bssrdf/quadrature.hpp"

namespace bssrdf {

namespace {

// The integrand of the single-scattering total in s, mu = mu_c + (1 - mu_c) s^2 (below).
[[gnu::always_inline]] inline double backward_lobe(double s, double mu_c, double g, double eta) {
  const double span = 1 - mu_c, mu = mu_c + span * s * s;
  return 2 * std::numbers::pi * henyey_greenstein(-mu, g) * (1 - fresnel_reflectance(mu, eta)) * mu / (1 + mu) * 2 *
         span * s;
}

// integrate_gauss_legendre(backward_lobe, 0, 1, 32), its 32 evaluations first and then the sum in the same order
// (the same bits): in a copy per vector width the evaluations' square roots and divisions go eight, four or two
// at once.
__attribute__((target_clones("avx512f", "avx2", "default"))) double backward_lobe_total(double mu_c, double g,
                                                                                        double eta) {
  const auto& rule = gauss_legendre(32);
  std::array<double, 32> values;
  for (std::size_t i = 0; i < 32; ++i) values[i] = backward_lobe(0.5 + 0.5 * rule.nodes[i], mu_c, g, eta);
  double sum = 0;
  for (std::size_t i = 0; i < 32; ++i) sum += rule.weights[i] * values[i];
  return sum * 0.5;
}

}  // namespace

double single_scattering_total(double albedo, double g, double eta) {
  // Light leaving with cosine mu below mu_c is totally reflected; substitute mu = mu_c + (1-mu_c)s^2
  // so the square-root onset of transmission at mu_c is smooth for the quadrature.
  const double mu_c = eta > 1 ? std::sqrt(1 - 1 / (eta * eta)) : 0.0;
  // For g >= 0 the backward lobe it integrates is flat: 32 Gauss-Legendre points agree with the adaptive
  // rule (tolerance 1e-12) to 9e-16 at g 0 to 0.999, eta 1 to 3, at a quarter of its evaluations (the
  // exact model's build below its first albedo node computes this once). For g < 0 the lobe peaks
  // at mu = 1 (32 points are 98 % off at g -0.999): adaptive.
  if (g >= 0) return albedo * backward_lobe_total(mu_c, g, eta);
  const auto integrand = [&](double s) { return backward_lobe(s, mu_c, g, eta); };
  return albedo * integrate_adaptive(integrand, 0.0, 1.0, 1e-12).value;
}

namespace {

// std::ceil and std::floor to an integer without the library call (no SSE4.1 in the baseline ISA).
std::ptrdiff_t ceil_to_int(double x) {
  const auto i = static_cast<std::ptrdiff_t>(x);
  return i + (static_cast<double>(i) < x);
}
std::ptrdiff_t floor_to_int(double x) {
  const auto i = static_cast<std::ptrdiff_t>(x);
  return i - (static_cast<double>(i) > x);
}

// The kernel exp(-e^{i h}) at grid indices i = m a + p, each phase p < a stored contiguously in m
// (a radius reads every a-th value), for the last grid seen on this thread: it does not depend on
// the medium, and its exponentials would otherwise cost a third of a profile.
class KernelGrid {
 public:
  // The values of phase p from i = p + a m_first on.
  const double* phase(double h, std::ptrdiff_t a, std::ptrdiff_t i_low, std::ptrdiff_t i_high, std::ptrdiff_t p,
                      std::ptrdiff_t m_first) {
    if (h != h_ || a != a_ || i_low < low_ || i_high > high_)
      fill(h, a, std::min(i_low, h == h_ && a == a_ ? low_ : i_low), i_high);
    return values_.data() + p * per_phase_ + (m_first - m_low_);
  }

 private:
  static std::ptrdiff_t floor_div(std::ptrdiff_t i, std::ptrdiff_t a) { return i >= 0 ? i / a : -((-i + a - 1) / a); }
  void fill(double h, std::ptrdiff_t a, std::ptrdiff_t low, std::ptrdiff_t high) {
    h_ = h;
    a_ = a;
    low_ = low - 32 * a;  // room for smaller radii than this call's
    high_ = high;
    m_low_ = floor_div(low_, a);
    per_phase_ = floor_div(high_, a) - m_low_ + 1;
    values_.assign(static_cast<std::size_t>(a * per_phase_), 1.0);
    for (std::ptrdiff_t p = 0; p < a; ++p)
      for (std::ptrdiff_t m = m_low_; m < m_low_ + per_phase_; ++m)
        values_[static_cast<std::size_t>(p * per_phase_ + m - m_low_)] =
            std::exp(-std::exp(static_cast<double>(m * a + p) * h));
  }
  double h_ = 0;
  std::ptrdiff_t a_ = 0, low_ = 0, high_ = -1, m_low_ = 0, per_phase_ = 0;
  std::vector<double> values_;
};

// f(x) e^tau / x at x = x_c + e^tau, in place of each e^tau: a copy per vector width, in which the
// square roots and divisions (most of its time) go eight, four or two at once (the file is built
// without errno and traps, so the compiler may; the same bits either way).
__attribute__((target_clones("avx512f", "avx2", "default"))) void node_weights(const Reduced<double>& m, double x_c,
                                                                               double* e_tau, std::size_t n) {
  for (std::size_t j = 0; j < n; ++j) {
    const double t = e_tau[j], x = x_c + t;
    e_tau[j] = single_scattering_exit(m, x) * t / x;
  }
}

// sum_j kern[j] w[j] in four partial sums, lane j mod 4, added as (s0 + s1) + (s2 + s3): independent
// additions pipeline, and the order is fixed, so the result does not depend on the instruction set
// (the vector type is two SSE2 registers or one AVX2 register, the same operations either way).
__attribute__((target_clones("avx2", "default"))) double kernel_sum(const double* kern, const double* w,
                                                                    std::ptrdiff_t count) {
  using Lanes = double __attribute__((vector_size(32)));
  Lanes sum{0, 0, 0, 0};
  std::ptrdiff_t j = 0;
#pragma GCC unroll 2
  for (; j + 4 <= count; j += 4) {
    Lanes a, b;
    std::memcpy(&a, kern + j, sizeof a);
    std::memcpy(&b, w + j, sizeof b);
    sum += a * b;
  }
  for (; j < count; ++j) sum[0] += kern[j] * w[j];
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

}  // namespace

std::vector<double> single_scattering_ln_y(const Reduced<double>& m, double ln_r0, double d_ln_r, std::size_t radii) {
  std::vector<double> ln_y(radii);
  if (radii == 0) return ln_y;
  // The trapezoid's step in tau: the largest a d_ln_r / b up to kStep, the grid spacing h = d_ln_r / b.
  // Measured (g 0 to 0.999, eta 1 to 2, 12 radii a decade): relative error 8e-9 at step 0.38, 3e-7 at
  // 0.48, 7e-6 at 0.58; the cost is about proportional to 1 / step.
  constexpr double kStep = 0.5;
  // The sum's ends in s = tau + ln rho. Above ln 40 the kernel is below e^{-40}. Below, the integrand
  // falls as (rho e^tau)^{3/2} where rho e^tau << 1, to e^{-21} of J at s = -14 (rho >= 1); for rho < 1
  // the lower end is tau = -14 itself, where J is within rho of its value at rho = 0.
  constexpr double kLow = -14, kHigh = 3.7;
  std::ptrdiff_t a = 0, b = 1;
  for (std::ptrdiff_t sub = 1; sub <= 8; ++sub) {
    const auto steps = static_cast<std::ptrdiff_t>(kStep * static_cast<double>(sub) / d_ln_r);
    if (steps >= 1 && static_cast<double>(steps * b) > static_cast<double>(a * sub)) {  // a longer step
      a = steps;
      b = sub;
    }
  }
  if (a == 0) {  // radii further apart than 8 steps: one node per grid point
    a = 1;
    b = static_cast<std::ptrdiff_t>(std::ceil(d_ln_r / kStep));
  }
  const double h = d_ln_r / static_cast<double>(b);
  const double step = static_cast<double>(a) * h;
  const double x_c = critical_exit_ratio(m.eta);
  const double ln_rho0 = std::log(m.sigma_t()) + ln_r0;
  // Node j sits at tau_j = j step - ln rho_0, radius k at ln rho_k = ln rho_0 + k b h, so that
  // tau_j + ln rho_k = (j a + k b) h: the kernel's grid index i = j a + k b. Radius k sums nodes
  // j_low(k) to j_high(k).
  const std::ptrdiff_t i_high = floor_to_int(kHigh / h);
  const double i_low_dense = kLow / h;  // where rho >= 1 (the same division as below: the same bits)
  std::vector<std::ptrdiff_t> j_low(radii);
  for (std::size_t k = 0; k < radii; ++k) {
    const double ln_rho = ln_rho0 + static_cast<double>(k) * d_ln_r;
    const double i_low =
        (ln_rho < 0 ? (kLow + ln_rho) / h : i_low_dense) - static_cast<double>(static_cast<std::ptrdiff_t>(k) * b);
    j_low[k] = ceil_to_int(i_low / static_cast<double>(a));
  }
  const auto j_high = [&](std::size_t k) {
    return floor_to_int(static_cast<double>(i_high - static_cast<std::ptrdiff_t>(k) * b) / static_cast<double>(a));
  };
  // The lowest node and kernel index (the largest radius, or the smallest where rho < 1 throughout).
  std::ptrdiff_t j_min = j_low[0], i_min = j_min * a;
  for (std::size_t k = 1; k < radii; ++k) {
    j_min = std::min(j_min, j_low[k]);
    i_min = std::min(i_min, j_low[k] * a + static_cast<std::ptrdiff_t>(k) * b);
  }
  const std::ptrdiff_t j_max = j_high(0);
  // The angular factor once per node, with the Jacobian dx / x = e^tau / (x_c + e^tau) dtau.
  std::vector<double> node(static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, j_max - j_min + 1)));
  const double growth = std::exp(step);
  double t = std::exp(static_cast<double>(j_min) * step - ln_rho0);
  for (double& e_tau : node) {
    e_tau = t;
    t *= growth;
  }
  node_weights(m, x_c, node.data(), node.size());
  thread_local KernelGrid kernel;
  const double ln_front = std::log(2 * std::numbers::pi * m.sigma_s * step);
  // Index i = (low + j) a + k b: phase k b mod a, m = low + j + (k b - phase) / a; k b = whole a + phase,
  // both carried from radius to radius (no integer division per radius).
  std::ptrdiff_t phase = 0, whole = 0;
  for (std::size_t k = 0; k < radii; ++k) {
    const std::ptrdiff_t low = j_low[k], count = j_high(k) - low + 1;
    const double* w = node.data() + (low - j_min);
    const double* kern = kernel.phase(h, a, i_min, i_high, phase, low + whole);
    ln_y[k] = kernel_sum(kern, w, count);
    for (phase += b; phase >= a; phase -= a) ++whole;
  }
  log_array(ln_y.data(), ln_y.data(), radii);  // the sums' logarithms, vectorised
  const double rho_growth = std::exp(d_ln_r);
  double rho = std::exp(ln_rho0);
  for (std::size_t k = 0; k < radii; ++k, rho *= rho_growth)
    ln_y[k] += ln_front + ln_r0 + static_cast<double>(k) * d_ln_r - rho * x_c;
  return ln_y;
}

double single_scattering_singular_coefficient(double g, double eta) {
  // int f dv over the exit angle theta (mu = cos theta = tanh v): x = e^v = cot(theta / 2) and
  // dv = dtheta / sin theta; theta = theta_c (1 - s^2).
  Reduced<double> m{};
  m.g = g;
  m.eta = eta;
  const double theta_c = eta > 1 ? std::asin(1 / eta) : std::numbers::pi / 2;
  const auto integrand = [&](double s) {
    const double theta = theta_c * (1 - s * s);
    return single_scattering_exit(m, 1 / std::tan(theta / 2)) / std::sin(theta) * 2 * theta_c * s;
  };
  return integrate_gauss_legendre(integrand, 0.0, 1.0, 12);
}

}  // namespace bssrdf
