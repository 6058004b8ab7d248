// Long runs from Python: the work runs on its own thread with the GIL released while the calling
// (main) thread wakes every 50 ms to deliver signals (Ctrl-C) and the caller's progress callback.
// A KeyboardInterrupt or an exception from the callback sets `stop`; the work's own progress hook
// then throws, the library's parallel loop stops taking items (parallel.hpp), and the exception is
// raised in Python once the running items have finished: no thread is left running.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <future>
#include <thread>

#include "bindings.hpp"

namespace bssrdf::python {

struct Stopped : std::exception {
  const char* what() const noexcept override { return "stopped"; }
};

// `work(progress)` gets the hook to hand to the library: it records (done, total) and throws Stopped once asked to.
template <class Result>
Result run_interruptibly(const std::function<Result(const std::function<void(std::uint64_t, std::uint64_t)>&)>& work,
                         const py::object& progress) {
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> done{0}, total{0};
  const std::function<void(std::uint64_t, std::uint64_t)> hook = [&](std::uint64_t d, std::uint64_t t) {
    done = d;
    total = t;
    if (stop) throw Stopped();
  };
  std::packaged_task<Result()> task([&] { return work(hook); });
  auto future = task.get_future();
  std::thread worker;
  {
    py::gil_scoped_release release;
    worker = std::thread(std::move(task));
  }
  std::exception_ptr python_error;  // a KeyboardInterrupt or the callback's exception, raised after the join
  std::uint64_t reported = ~std::uint64_t{0};
  for (;;) {
    bool finished;
    {
      py::gil_scoped_release release;
      finished = future.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready;
    }
    if (!python_error) {
      try {
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!progress.is_none() && total > 0 && done != reported) {
          reported = done;
          progress(reported, total.load());
        }
      } catch (...) {
        python_error = std::current_exception();
        stop = true;
      }
    }
    if (finished) break;
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (python_error) std::rethrow_exception(python_error);
  return future.get();  // the work's own exception (InvalidInput: ValueError) propagates
}

}  // namespace bssrdf::python
