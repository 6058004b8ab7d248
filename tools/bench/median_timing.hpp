// Median cost of one call of a cheap function over a set of radii: repeated 20 ms timing windows
// (so that clock resolution and loop overhead vanish), the median over `repetitions` windows.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace bssrdf::bench {

inline volatile double sink;  // keeps the timed results alive

template <class F>
double median_ns_per_call(F&& f, const std::vector<double>& radii, int repetitions) {
  std::vector<double> per_call;
  for (int rep = 0; rep < repetitions; ++rep) {
    const auto start = std::chrono::steady_clock::now();
    double acc = 0;
    long calls = 0;
    do {
      for (double r : radii) acc += f(r);
      calls += static_cast<long>(radii.size());
    } while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(20));
    sink = acc;
    per_call.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count() /
                       static_cast<double>(calls));
  }
  std::nth_element(per_call.begin(), per_call.begin() + repetitions / 2, per_call.end());
  return per_call[repetitions / 2];
}

}  // namespace bssrdf::bench
