// Internal to the Monte Carlo solver (log_array, src/exp_array.cpp, takes its logarithm too):
// branch-free logarithm and sine/cosine kernels and the conversions of random bits to uniform doubles,
// written so the compiler can vectorise the photon lanes of the tracer (SSE2 is enough: no calls, no
// table look-ups, no 64-bit integer to double conversion). Accuracy is that of the C library (about
// 1 ulp): they change rounding, not physics.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

// Passing d2 by value to inline functions: the ABI note is irrelevant (nothing crosses a library).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace bssrdf::mc {

// Two, four or eight doubles (or 64-bit integers) as one value, one SSE2, AVX or AVX-512 register: GCC/Clang
// vector extensions. Every operation is the IEEE operation of each element (the compiler contracts
// nothing, -ffp-contract=off; the fused operations are written out, fma_of), so the results do not
// depend on the vector width.
using d2 = double __attribute__((vector_size(16)));
using u2 = std::uint64_t __attribute__((vector_size(16)));
using i2 = std::int64_t __attribute__((vector_size(16)));
using d4 = double __attribute__((vector_size(32)));
using u4 = std::uint64_t __attribute__((vector_size(32)));
using i4 = std::int64_t __attribute__((vector_size(32)));
using d8 = double __attribute__((vector_size(64)));
using u8 = std::uint64_t __attribute__((vector_size(64)));
using i8 = std::int64_t __attribute__((vector_size(64)));

inline d2 load2(const double* p) {
  d2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline u2 load2(const std::uint64_t* p) {
  u2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store2(double* p, d2 v) { std::memcpy(p, &v, sizeof v); }
inline void store2(std::uint64_t* p, u2 v) { std::memcpy(p, &v, sizeof v); }
inline void store2(std::int64_t* p, i2 v) { std::memcpy(p, &v, sizeof v); }
template <class V>
inline V load(const void* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V>
inline void store(void* p, V v) {
  std::memcpy(p, &v, sizeof v);
}

inline double sqrt_of(double x) { return std::sqrt(x); }
inline d2 sqrt_of(d2 x) {
#if defined(__SSE2__)
  return reinterpret_cast<d2>(_mm_sqrt_pd(reinterpret_cast<__m128d>(x)));
#else
  return d2{std::sqrt(x[0]), std::sqrt(x[1])};
#endif
}

// Element by element (the compiler packs it into one vsqrtpd where AVX is enabled).
inline d4 sqrt_of(d4 x) { return d4{std::sqrt(x[0]), std::sqrt(x[1]), std::sqrt(x[2]), std::sqrt(x[3])}; }
[[gnu::always_inline]] inline d8 sqrt_of(d8 x) {
  return d8{std::sqrt(x[0]), std::sqrt(x[1]), std::sqrt(x[2]), std::sqrt(x[3]),
            std::sqrt(x[4]), std::sqrt(x[5]), std::sqrt(x[6]), std::sqrt(x[7])};
}

// a b + c rounded once (IEEE fusedMultiplyAdd), element by element: one instruction in a kernel
// compiled with FMA, the C library's exactly rounded fma elsewhere (tests only).
// These and the kernels below are always inlined: in a kernel compiled with FMA they must take its
// instruction set (an out-of-line copy would be generic code, a library call per fused operation).
inline double fma_of(double a, double b, double c) { return std::fma(a, b, c); }
[[gnu::always_inline]] inline d2 fma_of(d2 a, d2 b, d2 c) {
  return d2{__builtin_fma(a[0], b[0], c[0]), __builtin_fma(a[1], b[1], c[1])};
}
[[gnu::always_inline]] inline d4 fma_of(d4 a, d4 b, d4 c) {
  return d4{__builtin_fma(a[0], b[0], c[0]), __builtin_fma(a[1], b[1], c[1]), __builtin_fma(a[2], b[2], c[2]),
            __builtin_fma(a[3], b[3], c[3])};
}
[[gnu::always_inline]] inline d8 fma_of(d8 a, d8 b, d8 c) {
  return d8{__builtin_fma(a[0], b[0], c[0]), __builtin_fma(a[1], b[1], c[1]), __builtin_fma(a[2], b[2], c[2]),
            __builtin_fma(a[3], b[3], c[3]), __builtin_fma(a[4], b[4], c[4]), __builtin_fma(a[5], b[5], c[5]),
            __builtin_fma(a[6], b[6], c[6]), __builtin_fma(a[7], b[7], c[7])};
}
// A constant stands for the vector of it; a vector for itself.
template <class D, class T>
[[gnu::always_inline]] inline D broadcast(T x) {
  if constexpr (std::is_same_v<T, D>)
    return x;
  else
    return D{} + x;
}

// How a kernel computes a b + c. Fused (one rounding): a polynomial step or a move is one operation
// instead of two, on every x86-64 processor with FMA; these kernels give the same bits on all of
// them. Unfused (two roundings): processors without FMA (and other architectures), where an exactly
// rounded fma is a library routine some 30 times slower than the whole step; the same arithmetic
// otherwise, so the same photons to a tiny fraction of their paths and the same statistics.
struct Fused {
  template <class D, class B, class C>
  [[gnu::always_inline]] static D madd(D a, B b, C c) {
    return fma_of(a, broadcast<D>(b), broadcast<D>(c));
  }
};
struct Unfused {
  template <class D, class B, class C>
  [[gnu::always_inline]] static D madd(D a, B b, C c) {
    return a * b + c;
  }
};

// A kernel's vectors and its a b + c: SSE2 without FMA (every x86-64), SSE2 with FMA (only in
// functions compiled with target("fma")), AVX2 (target("avx2,fma")) and AVX-512 (tracer_avx512.cpp).
struct Sse2 {  // 2 lanes per register
  using D = d2;
  using U = u2;
  using I = i2;
  using Madd = Unfused;
  static constexpr int width = 2;
};
struct Sse2Fma : Sse2 {
  using Madd = Fused;
};
struct Avx2 {  // 4 lanes per register
  using D = d4;
  using U = u4;
  using I = i4;
  using Madd = Fused;
  static constexpr int width = 4;
};
struct Avx512 {  // 8 lanes per register
  using D = d8;
  using U = u8;
  using I = i8;
  using Madd = Fused;
  static constexpr int width = 8;
};

// Integer type of the same shape as D and back: std::uint64_t for double, u2 for d2, u4 for d4, u8 for d8.
template <class D>
struct bits_of {
  using type = std::uint64_t;
};
template <>
struct bits_of<d2> {
  using type = u2;
};
template <>
struct bits_of<d4> {
  using type = u4;
};
template <>
struct bits_of<d8> {
  using type = u8;
};
template <class D>
using bits_t = typename bits_of<D>::type;
template <class U>
struct double_of {
  using type = double;
};
template <>
struct double_of<u2> {
  using type = d2;
};
template <>
struct double_of<u4> {
  using type = d4;
};
template <>
struct double_of<u8> {
  using type = d8;
};
template <class U>
using double_t_of = typename double_of<U>::type;

// The logarithm in two halves around its one division, so a caller can share one reciprocal
// between several divisions: log_reduce gives f = m - 1 and k; the quotient s = f / (2 + f) is the
// caller's; log_finish completes. s enters only through s (f^2/2 + R), a correction of relative
// size below 0.03, so a quotient a few ulp off moves the result by a small fraction of an ulp.
template <class D>
struct LogReduced {
  D f, dk;
};
template <class D>
[[gnu::always_inline]] inline LogReduced<D> log_reduce(D x) {
  using U = bits_t<D>;
  U ix = std::bit_cast<U>(x);
  ix += 0x3ff0000000000000ull - 0x3fe6a09e00000000ull;  // m's threshold sqrt(1/2) moved to 1
  // k as a double without an integer conversion: 2^52 + (k + 1023) has those bits as mantissa.
  const D dk = std::bit_cast<D>((ix >> 52) | 0x4330000000000000ull) - (0x1p52 + 1023.0);
  ix = (ix & 0x000fffffffffffffull) + 0x3fe6a09e00000000ull;
  return {std::bit_cast<D>(ix) - 1.0, dk};
}
template <class M = Fused, class D>
[[gnu::always_inline]] inline D log_finish(LogReduced<D> p, D s) {
  constexpr double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
  constexpr double Lg1 = 6.666666666666735130e-01, Lg2 = 3.999999999940941908e-01, Lg3 = 2.857142874366239149e-01,
                   Lg4 = 2.222219843214978396e-01, Lg5 = 1.818357216161805012e-01, Lg6 = 1.531383769920937332e-01,
                   Lg7 = 1.479819860511658591e-01;
  const D f = p.f, dk = p.dk;
  const D hfsq = 0.5 * f * f;
  const D z = s * s, w = z * z;
  const D t1 = w * M::madd(w, M::madd(w, Lg6, Lg4), Lg2);
  const D t2 = z * M::madd(w, M::madd(w, M::madd(w, Lg7, Lg5), Lg3), Lg1);
  const D r = t2 + t1;
  // dk ln2_hi is exact (ln2_hi's low bits are zero), so fusing it changes nothing there.
  return M::madd(dk, ln2_hi, M::madd(s, hfsq + r, dk * ln2_lo) - hfsq + f);
}

// ln(x) for a positive normal finite x (no checks: the tracer only passes uniforms in (0, 1]).
// fdlibm's e_log algorithm (x = 2^k m, m in [sqrt(1/2), sqrt(2)), s = (m - 1)/(m + 1),
// log m = 2 atanh s with a minimax polynomial of error < 2^-58.45) on its more accurate branch for
// every x: error below 1 ulp.
template <class D>
[[gnu::always_inline]] inline D log_normal(D x) {
  const LogReduced<D> p = log_reduce(x);
  return log_finish(p, p.f / (2.0 + p.f));
}

// Uniform in (0, 1] with the 52 top bits of r: 2 - [1, 2), exact, step 2^-52 (for -log u: free
// paths up to 36 optical depths; the tail beyond, e^-36 = 2e-16, is below double rounding).
template <class U>
[[gnu::always_inline]] inline auto uniform_open0_52(U r) {
  using D = double_t_of<U>;
  return 2.0 - std::bit_cast<D>((r >> 12) | 0x3ff0000000000000ull);
}

// Uniform in (0, 1) from 32 random bits v: the midpoint (v + 1/2) 2^-32 of one of 2^32 equal
// cells. Any smooth function of it has the mean of the continuous uniform to O(2^-64 f'') (the
// midpoint rule), far below double rounding of the results: no bias at any photon count.
template <class U>
[[gnu::always_inline]] inline auto uniform_mid32(U v) {
  using D = double_t_of<U>;
  return (std::bit_cast<D>((v & 0xffffffffull) | 0x4330000000000000ull) - 0x1p52 + 0.5) * 0x1p-32;
}

// cos and sin of a uniform azimuth phi from 32 random bits v: the top two bits pick the quadrant
// q, the other 30 the angle inside it, at the cell midpoint (as uniform_mid32):
// phi = q pi/2 + pi/4 + x, x in (-pi/4, pi/4). cos x and sin x by fdlibm's kernels
// (k_cos, k_sin: minimax, error < 2^-58 on [-pi/4, pi/4]), then the rotations by pi/4 and q pi/2,
// branch-free (a swap and sign flips on the bits). Error ~2e-16.
template <class M = Fused, class U, class D>
[[gnu::always_inline]] inline void azimuth_cos_sin(U v, D& cos_phi, D& sin_phi) {
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03, S3 = -1.98412698298579493134e-04,
                   S4 = 2.75573137070700676789e-06, S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03, C3 = 2.48015872894767294178e-05,
                   C4 = -2.75573143513906633035e-07, C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  constexpr double kHalfPi = 1.57079632679489661923, kSqrtHalf = 0.70710678118654752440;
  const U cell = v & 0x3fffffffull;                                                       // 30 bits
  const D f = (std::bit_cast<D>(cell | 0x4330000000000000ull) - 0x1p52 + 0.5) * 0x1p-30;  // (0, 1)
  const D x = (f - 0.5) * kHalfPi;
  const D z = x * x;
  const D sin_x = M::madd(x * z, M::madd(z, M::madd(z, M::madd(z, M::madd(z, M::madd(z, S6, S5), S4), S3), S2), S1), x);
  const D cos_x =
      M::madd(z * z, M::madd(z, M::madd(z, M::madd(z, M::madd(z, M::madd(z, C6, C5), C4), C3), C2), C1), 1.0 - 0.5 * z);
  const D c = (cos_x - sin_x) * kSqrtHalf;  // cos(pi/4 + x), > 0
  const D s = (cos_x + sin_x) * kSqrtHalf;  // sin(pi/4 + x), > 0
  // Quadrant q: (c, s), (-s, c), (-c, -s), (s, -c).
  const U b0 = (v >> 30) & 1, b1 = (v >> 31) & 1;
  const U swap = 0 - b0;  // all ones when q is odd
  const U cb = std::bit_cast<U>(c), sb = std::bit_cast<U>(s);
  const U first = (cb & ~swap) | (sb & swap), second = (sb & ~swap) | (cb & swap);
  cos_phi = std::bit_cast<D>(first ^ ((b0 ^ b1) << 63));
  sin_phi = std::bit_cast<D>(second ^ (b1 << 63));
}

}  // namespace bssrdf::mc
