// The library's one bracketed root finder: regula falsi with the Illinois modification (Dowell &
// Jarratt 1971: an end kept twice has its function value halved, so both ends close in superlinearly).
// It never leaves the bracket, so it suits monotone physical relations evaluated only where they are
// defined (a total against an albedo, a measurement against one unknown).
#pragma once

#include <algorithm>
#include <cmath>

namespace bssrdf {

struct BracketedRoot {
  double x = 0;   // the root, or the last bracket's midpoint
  int steps = 0;  // evaluations of f
};

// A root of f in [lo, hi], given f_lo = f(lo) and f_hi = f(hi) of opposite signs (or one of them 0).
// Stops at a point where |f| <= f_tolerance, when the bracket is no wider than
// x_tolerance + relative * max(|lo|, |hi|), or after max_steps evaluations.
template <class F>
BracketedRoot illinois_root(const F& f, double lo, double hi, double f_lo, double f_hi, double x_tolerance,
                            double relative, double f_tolerance = 0, int max_steps = 100) {
  if (f_lo == 0) return {lo, 0};
  if (f_hi == 0) return {hi, 0};
  int replaced = 0;  // +1: hi was replaced last, -1: lo was
  int steps = 0;
  while (steps < max_steps && std::abs(hi - lo) > x_tolerance + relative * std::max(std::abs(lo), std::abs(hi))) {
    const double x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const double f_x = f(x);
    ++steps;
    if (std::abs(f_x) <= f_tolerance) return {x, steps};
    if ((f_x > 0) == (f_hi > 0)) {
      hi = x;
      f_hi = f_x;
      if (replaced == 1) f_lo /= 2;
      replaced = 1;
    } else {
      lo = x;
      f_lo = f_x;
      if (replaced == -1) f_hi /= 2;
      replaced = -1;
    }
  }
  return {0.5 * (lo + hi), steps};
}

}  // namespace bssrdf
