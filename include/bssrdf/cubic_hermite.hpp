// The cubic Hermite interpolant, written once: its basis, and Catmull-Rom (slopes from the
// neighbours) on uniformly spaced values, which the profile tables (exact model, projections) read
// between their nodes. Templated on the scalar so fits may differentiate through it.
#pragma once

#include <array>
#include <cstddef>

namespace bssrdf {

// The basis at t in [0, 1] of an interval of unit length: {h00, h10, h01, h11}, the weights of the
// value and the slope at its start and of the value and the slope at its end.
// Always inlined, as catmull_rom: the tables call them millions of times in their loops, where GCC
// otherwise left them a call each (18 % of the penumbra batch).
template <class T>
[[gnu::always_inline]] inline std::array<T, 4> hermite_basis(T t) {
  const T t2 = t * t, t3 = t2 * t;
  return {T(2) * t3 - T(3) * t2 + T(1), t3 - T(2) * t2 + t, T(-2) * t3 + T(3) * t2, t3 - t2};
}

// Catmull-Rom inside uniformly spaced values, as weights of p[i - 1], p[i], p[i + 1], p[i + 2] at
// p[i] + t (p[i + 1] - p[i]): the slopes (p[i + 1] - p[i - 1]) / 2 and (p[i + 2] - p[i]) / 2.
template <class T>
std::array<T, 4> catmull_rom_weights(T t) {
  const auto [h00, h10, h01, h11] = hermite_basis(t);
  return {T(-0.5) * h10, h00 - T(0.5) * h11, h01 + T(0.5) * h10, T(0.5) * h11};
}

// Catmull-Rom on p[0 .. n), n >= 2, between p[i] and p[i + 1] (i + 1 < n) at fraction t; the slope
// one-sided (p[i + 1] - p[i]) at an end where a neighbour is missing.
template <class T>
[[gnu::always_inline]] inline T catmull_rom(const T* p, std::size_t n, std::size_t i, T t) {
  const T p1 = p[i], p2 = p[i + 1];
  const T m1 = i > 0 ? T(0.5) * (p2 - p[i - 1]) : p2 - p1;
  const T m2 = i + 2 < n ? T(0.5) * (p[i + 2] - p1) : p2 - p1;
  const auto [h00, h10, h01, h11] = hermite_basis(t);
  return h00 * p1 + h10 * m1 + h01 * p2 + h11 * m2;
}

}  // namespace bssrdf
