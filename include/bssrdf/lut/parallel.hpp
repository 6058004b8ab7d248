// Deterministic parallel loops for the tabulators: items are split into fixed contiguous blocks,
// one per thread, and each item writes only its own output, so results never depend on the thread
// count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace bssrdf {

// threads = 0: all hardware threads. Runs f(i) for i in [0, n).
template <class F>
void parallel_for(std::size_t n, unsigned threads, F&& f) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, n));
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t i = n * t / threads; i < n * (t + 1) / threads; ++i) f(i);
    });
  for (std::size_t i = 0; i < n / threads; ++i) f(i);
  for (auto& th : pool) th.join();
}

}  // namespace bssrdf
