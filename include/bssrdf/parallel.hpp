// The one parallel loop of the library: runs f(i) for i in [0, n) on up to `threads` threads
// (0: all hardware threads), handing out items one at a time from a shared counter, so a slow item
// (a Monte Carlo batch, a material of `lut --all`, a table row) never leaves the other threads idle.
// Results never depend on the thread count as long as each item writes only its own output (or, as
// the Monte Carlo batches do, folds its result in item order under its own lock).
//
// An exception thrown by f stops the loop (no new items start) and is rethrown on the calling thread
// once every running item has finished; when several items throw, the one with the smallest index
// wins, so the error too is independent of the thread count.
//
//   std::vector<double> out(n);
//   parallel_for(n, threads, [&](std::size_t i) { out[i] = expensive(i); });
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace bssrdf {

// The threads a loop of n items uses: `threads` (0: all hardware threads), at most n, at least 1.
inline unsigned worker_count(std::size_t n, unsigned threads) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, n)));
}

template <class F>
void parallel_for(std::size_t n, unsigned threads, F&& f) {
  const unsigned workers = worker_count(n, threads);
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex failure_mutex;
  std::size_t failed_index = n;
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t i; !failed.load(std::memory_order_relaxed) && (i = next.fetch_add(1)) < n;) {
      try {
        f(i);
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (i < failed_index) failed_index = i, failure = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace bssrdf
