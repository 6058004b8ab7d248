#include "bssrdf/exp_array.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

#include "montecarlo/fastmath.hpp"

namespace bssrdf {
namespace {

// ln 2 in two parts (Cody & Waite 1980): k ln2_hi is exact for |k| < 2^11.
constexpr double kLn2Hi = 0.693147180369123816490, kLn2Lo = 1.90821492927058770002e-10;

// e^x = 2^k e^r with k = round(x / ln 2) and r = x - k ln 2 in [-ln 2 / 2, ln 2 / 2]; e^r by its Taylor series to r^13
// (truncation below 1e-17 relative), summed by Horner. 2^k is built from its bits in two halves so that k down to -1075
// (subnormal results) needs no special case.
[[gnu::always_inline]] inline double exp_lane(double x) {
  constexpr double kLog2e = 1.4426950408889634;
  constexpr double kRound = 0x1.8p52;  // adding it rounds to an integer, held in the low bits
  const double clamped = x < -745.5 ? -745.5 : (x > 709.8 ? 709.8 : x);
  const double shifted = clamped * kLog2e + kRound;
  const double k = shifted - kRound;
  const double r = (clamped - k * kLn2Hi) - k * kLn2Lo;
  double p = 1.0 / 6227020800;  // 1/13!
  p = p * r + 1.0 / 479001600;
  p = p * r + 1.0 / 39916800;
  p = p * r + 1.0 / 3628800;
  p = p * r + 1.0 / 362880;
  p = p * r + 1.0 / 40320;
  p = p * r + 1.0 / 5040;
  p = p * r + 1.0 / 720;
  p = p * r + 1.0 / 120;
  p = p * r + 1.0 / 24;
  p = p * r + 1.0 / 6;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // 2^j from the bits of j + kRound (an integer in the low bits, two's complement), for j = k/2 rounded and k - j:
  // only 64-bit additions and a left shift, which SSE2 has (not the arithmetic right shift k >> 1 would need).
  const auto power = [kRound](double j) {
    return std::bit_cast<double>(
        (std::bit_cast<std::uint64_t>(j + kRound) - std::bit_cast<std::uint64_t>(kRound) + std::uint64_t{1023}) << 52);
  };
  const double half = (k * 0.5 + kRound) - kRound;
  const double scale1 = power(half), scale2 = power(k - half);
  const double y = p * scale1 * scale2;
  return x <= -745.0 ? 0.0 : y;
}

// ln x by the Monte Carlo tracer's logarithm (montecarlo/fastmath.hpp: fdlibm's algorithm, branch-free, written for
// vector lanes), here without fused operations (no FMA in the baseline instruction set) and for every double: a
// subnormal x is scaled by 2^52 and its exponent corrected exactly; 0 -> -inf, negative -> NaN, +inf -> +inf, NaN
// stays NaN (every comparison false).
[[gnu::always_inline]] inline double log_lane(double x) {
  const bool subnormal = x < 0x1p-1022;
  mc::LogReduced<double> p = mc::log_reduce(subnormal ? x * 0x1p52 : x);
  p.dk -= subnormal ? 52.0 : 0.0;
  const double y = mc::log_finish<mc::Unfused>(p, p.f / (2.0 + p.f));
  const double ends = x == 0 ? -INFINITY : (x == INFINITY ? INFINITY : NAN);
  return x > 0 && x < INFINITY ? y : ends;
}

}  // namespace

// One copy per vector width, chosen when the program loads: the same operations, so the same bits, on every
// processor (no contraction: -ffp-contract=off).
__attribute__((target_clones("avx512f", "avx2", "default"))) void exp_array(const double* x, double* out,
                                                                            std::size_t n) {
#pragma GCC unroll 2
  for (std::size_t k = 0; k < n; ++k) out[k] = exp_lane(x[k]);
}

__attribute__((target_clones("avx512f", "avx2", "default"))) void log_array(const double* x, double* out,
                                                                            std::size_t n) {
#pragma GCC unroll 2
  for (std::size_t k = 0; k < n; ++k) out[k] = log_lane(x[k]);
}

}  // namespace bssrdf
