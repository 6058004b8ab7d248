#include "bssrdf/exp_array.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

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

// ln x = k ln 2 + ln(1 + f), 1 + f = x / 2^k in [sqrt(1/2), sqrt(2)), from the bits without a branch: adding
// 1.0's bits less sqrt(1/2)'s carries into the exponent field exactly when the significand is at least sqrt(2)
// (only 64-bit additions, masks and a logical shift, which SSE2 has). Then, as Cody & Waite (1980) and
// fdlibm's log arrange it so that f (exact) carries the result and only small terms are rounded,
//   ln(1 + f) = f - (f^2 / 2 - s (f^2 / 2 + R)),  s = f / (2 + f),  R = 2 (s^2 / 3 + s^4 / 5 + ... + s^18 / 19)
// (ln(1 + f) = 2 atanh s; |s| <= 0.172, so the series' next term is below 3e-17 of the result). Subnormal x
// are scaled by 2^52 first.
[[gnu::always_inline]] inline double log_lane(double x) {
  constexpr double kSmallest = 0x1p-1022, kSqrtHalf = 0.70710678118654752440;
  constexpr std::uint64_t kMantissa = (std::uint64_t{1} << 52) - 1;
  const bool subnormal = x < kSmallest;
  const double scaled = subnormal ? x * 0x1p52 : x;
  const std::uint64_t shift = std::bit_cast<std::uint64_t>(1.0) - std::bit_cast<std::uint64_t>(kSqrtHalf);
  const std::uint64_t u = std::bit_cast<std::uint64_t>(scaled) + shift;
  // The exponent field (0 to 2047) as a double, through the bits of 2^52 + field.
  const double field = std::bit_cast<double>((u >> 52) | std::bit_cast<std::uint64_t>(0x1p52)) - 0x1p52;
  const double k = field - (subnormal ? 1023.0 + 52 : 1023.0);
  const double f = std::bit_cast<double>((u & kMantissa) + std::bit_cast<std::uint64_t>(kSqrtHalf)) - 1;
  const double s = f / (2 + f), z = s * s;
  constexpr double kSeries[] = {2.0 / 19, 2.0 / 17, 2.0 / 15, 2.0 / 13, 2.0 / 11, 2.0 / 9, 2.0 / 7, 2.0 / 5, 2.0 / 3};
  double p = 0;
  for (const double c : kSeries) p = p * z + c;  // Horner, from s^18 / 19 down
  const double r = p * z, half_f2 = 0.5 * f * f;
  const double y = k * kLn2Hi - ((half_f2 - (s * (half_f2 + r) + k * kLn2Lo)) - f);
  // 0 -> -inf, negative -> NaN, +inf -> +inf, NaN stays NaN (every comparison false).
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
