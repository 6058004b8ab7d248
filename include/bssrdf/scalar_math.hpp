// Special functions the models need, written once for double and ceres::Jet alike (Jet lacks
// some of them).
#pragma once

#include <cmath>
#include <numbers>

namespace bssrdf {

// The full angle: profiles are integrated over the plane as 2 pi r R(r) dr.
inline constexpr double kTwoPi = 2 * std::numbers::pi;

template <class T>
T inverse_sinh(T x) {
  using std::log;
  using std::sqrt;
  return log(x + sqrt(x * x + T(1)));
}

// The scaled complementary error function e^{x^2} erfc(x) for x >= 0, without overflow: the
// product directly where erfc is representable, the asymptotic series beyond (error < 1e-10).
template <class T>
T erfcx(T x) {
  using std::erfc;
  using std::exp;
  if (x < T(25)) return exp(x * x) * erfc(x);
  const T inv2 = T(1) / (x * x);
  return (T(1) - inv2 * (T(0.5) - inv2 * (T(0.75) - inv2 * T(1.875)))) * std::numbers::inv_sqrtpi / x;
}

}  // namespace bssrdf
