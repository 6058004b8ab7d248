#!/usr/bin/env python3
"""Inverse adding-doubling of an integrating-sphere file (Prahl's iad .rxt format), and a check of the result
by the forward solver.

    python3 examples/fit_rxt.py [FILE.rxt]      (default: tests/data/iad_basic_B.rxt)
"""
import os
import sys

import numpy as np

import bssrdf

here = os.path.dirname(os.path.abspath(__file__))
path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "tests", "data", "iad_basic_B.rxt")
fit = bssrdf.fit.rxt(path)
print(fit)  # the table `bssrdf fit slab --rxt` prints
print("mu_a   (1/mm):", np.array2string(fit.mu_a, precision=4))
print("mu_s'  (1/mm):", np.array2string(fit.mu_s_prime, precision=4))
print("1 sigma mu_a :", np.array2string(fit.mu_a_stderr, precision=4))
assert all(fit.converged), fit.status
