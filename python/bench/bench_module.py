#!/usr/bin/env python3
"""The module's speed against the same evaluations in C++, in one process (medians; ratios, not absolute times,
so that a loaded machine affects both sides alike).

    PYTHONPATH=build/python python3 python/bench/bench_module.py [N]       (default N = 1e6 radii)

1. N exact-model evaluations: Model("exact").R(medium, r) with r a numpy array of N radii (one channel), against
   the C++ loop over the same radii (bssrdf._bssrdf._bench_reflectance, timed in C++). Issue 27 asks for <= 2x.
2. Per-call overhead: Model.R with one radius, minus one evaluation in C++. Issue 27 asks for <= 5 us.
"""
import sys
import time

import numpy as np

import bssrdf
from bssrdf import _bssrdf

n = int(float(sys.argv[1])) if len(sys.argv) > 1 else 1_000_000
medium = bssrdf.Medium(sigma_a=0.05, sigma_s=5.0, g=0.2, eta=1.3)  # one channel, inside the exact model's domain
model = bssrdf.Model("exact")
r = np.geomspace(1e-3, 20, n)


def median_time(f, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return sorted(times)[len(times) // 2]


# 1. Throughput, interleaved so that load changes hit both sides.
py_times, cpp_times = [], []
for _ in range(5):
    py_times.append(median_time(lambda: model.R(medium, r), 1))
    cpp_times.append(_bssrdf._bench_reflectance(model, medium, r, 1))
py, cpp = sorted(py_times)[2], sorted(cpp_times)[2]
print("%d exact evaluations: module %.1f ms, C++ %.1f ms: ratio %.3f (limit 2)" % (n, 1e3 * py, 1e3 * cpp, py / cpp))

# 2. Overhead of one call with one radius.
one = np.array([0.5])
calls = 20000
per_eval = _bssrdf._bench_reflectance(model, medium, np.full(calls, 0.5), 5) / calls
array_calls, float_calls = [], []
for _ in range(5):  # interleaved, medians
    array_calls.append(median_time(lambda: [model.R(medium, one) for _ in range(calls)], 1) / calls)
    float_calls.append(median_time(lambda: [model.R(medium, 0.5) for _ in range(calls)], 1) / calls)
per_call, per_float = sorted(array_calls)[2], sorted(float_calls)[2]
print("one radius (numpy array): %.2f us per call, %.2f us of it the evaluation: overhead %.2f us (limit 5)" %
      (1e6 * per_call, 1e6 * per_eval, 1e6 * (per_call - per_eval)))
print("one radius (Python float): %.2f us per call: overhead %.2f us (limit 5)" %
      (1e6 * per_float, 1e6 * (per_float - per_eval)))
sys.exit(0 if py / cpp <= 2 and min(per_call, per_float) - per_eval <= 5e-6 else 1)
