#!/usr/bin/env python3
"""Random calls of the Python module with hostile arguments, the module's counterpart of
tools/fuzz_cli.py: every call must return, or raise ValueError with one non-empty line (bad input)
or TypeError (an argument of the wrong type, as Python does); never crash the interpreter, never
raise anything else, finish within a time limit and leave no file behind when it raises.

The calls run in a worker process, so a crash is caught and named; trial i is the same call for
the same seed whatever the count. Prints a table of outcomes; exit status 1 on any finding.

Usage: tools/fuzz_python.py [COUNT] [SEED]     (default 300 1; PYTHONPATH must reach the module)
"""
import math
import os
import random
import select
import stat
import subprocess
import sys
import tempfile
import time

import numpy as np

NAN, INF = math.nan, math.inf
# Hostile values of every kind a caller can pass, by what the argument is (most trials stay with the
# argument's own kind, so they reach the checks behind type conversion): numbers at and beyond the
# edges, strings that look like numbers or escape the terminal, arrays of the wrong shape or content.
NUMBERS = [-1, 0, -0.0, 1e308, -1e308, 4.9e-324, NAN, INF, -INF, 2**64, -2**63, 10**40, True, 0.5, 1.3, 2, 100,
           1e-9, 3e9, np.float32(0.5), np.int64(-1), np.float64(NAN)]
STRINGS = ["", "abc", "1,2", "\x1b[31m", "a\nb", "nan", "-1", " mm", "EXACT", "a" * 5000, "Skin1", "\u00b5m", "../x"]
ARRAYS = [[], [NAN], [1, 2, 3, 4], [[1.0]], [-1, 0.5, 2], [INF, 1, 1], (1, 2), np.array([]),
          np.array([[1.0, 2.0], [3.0, 4.0]]), np.full(3, 1e308), np.zeros(3), np.array([1, 2, 3], dtype=np.int64),
          np.array(["a"]), np.full(3, 4.9e-324), 0.5, NAN]
OTHERS = [None, {"a": 1}, object(), b"bytes"]
HOSTILE = NUMBERS + STRINGS + ARRAYS + OTHERS
STRING_KEYS = {"unit", "model", "spacing", "kind", "convention", "to", "blender_method", "method", "physical_model",
               "target", "name", "db", "source", "loss", "incidence", "layout", "interpolation", "size", "output",
               "path", "file", "fit", "reference", "materials"}
ARRAY_KEYS = {"sigma_a", "sigma_s", "sigma_s_prime", "r", "x", "albedo", "distance", "reflectance", "transmittance",
              "reflectance_stderr", "unscattered", "slides", "range", "channels", "thickness"}
# Paths that are not regular files: a write may go into a device (as `-o /dev/stdout` does) but must
# never replace it, and a directory is refused.
NOT_REGULAR = ["/dev/null", "DIR"]


def hostile_for(rng, key):
    if rng.random() < 0.25:
        return rng.choice(HOSTILE)  # the wrong kind altogether
    if key in ("output", "path") and rng.random() < 0.3:
        return rng.choice(NOT_REGULAR)
    if key in STRING_KEYS:
        return rng.choice(STRINGS)
    return rng.choice(ARRAYS + NUMBERS if key in ARRAY_KEYS else NUMBERS)


# Counts that start Monte Carlo or fits stay small when valid, so a trial is seconds at most.
SAFE = {"photons": 2000, "count": 3, "samples": 16, "taps": 9, "bins": 16, "depth_bins": 4, "points": 16,
        "threads": 2, "lost_light_photons": 1000}
HUGE_COUNTS = {"photons", "lost_light_photons", "samples", "bins", "depth_bins", "points", "taps", "count"}

# A medium the calls start from (valid), and what else each call may be given.
MEDIUM = ("medium", lambda bs: bs.Medium(sigma_a=[0.03, 0.17, 0.48], sigma_s=[0.74, 0.88, 1.01], g=0, eta=1.3,
                                         unit="mm"))
RXT = "IAD1 1.4 1.5 1 1 5 .98 1 203.2 25.4 12.7 1 .96 203.2 25.4 12.7 1 .96\n2\n500 0.3 0.2\n0.25 0.3\n"
CSV = "# r,R\n0.1,1.2\n0.2,0.8\n0.5,0.3\n1,0.09\n2,0.01\n4,0.0004\n"
KINDS = ["radial", "albedo-radius", "transmission", "preintegrated", "penumbra", "separable", "gaussians"]

# name -> (base keyword arguments, the keywords a trial may mutate, valid alternatives for some of them)
CALLS = {
    "Medium": ({"sigma_a": [0.1, 0.2], "sigma_s": [1.0, 2.0], "g": 0.5, "eta": 1.4, "unit": "mm"},
               ["sigma_a", "sigma_s", "g", "eta", "unit", "channels"], {"unit": ["cm", "m", "um"]}),
    "Medium.from_sigma_s_prime": ({"sigma_a": 0.01, "sigma_s_prime": 2.0, "g": 0.8, "unit": "cm"},
                                  ["sigma_a", "sigma_s_prime", "g", "eta", "unit", "channels"], {}),
    "materials.get": ({"name": "Skin1"}, ["name", "db"], {"name": ["Skin1", "Spectralon", "Marble"]}),
    "materials.list": ({}, ["source", "db"], {}),
    "materials.export": ({"materials": "Skin1", "to": "json"},
                         ["materials", "to", "unit", "blender_method", "blender_version", "object_size", "output"],
                         {"to": ["json", "blender", "unreal", "unity", "pbrt", "mitsuba"], "unit": ["m", "cm"]}),
    "materials.from_fit": ({"fit": "FIT", "name": "Mine"}, ["fit", "name", "eta", "source"], {}),
    "profile": ({"medium": MEDIUM}, ["medium", "r", "model", "unit", "samples", "r_min", "r_max", "spacing",
                                     "accuracy", "single_scattering", "surface_albedo"],
                {"model": ["exact", "dipole", "pbd", "auto", "multipole"], "spacing": ["log", "linear"]}),
    "Model.R": ({"model": "exact", "medium": MEDIUM, "r": [0.1, 1.0]}, ["model", "medium", "r"],
                {"model": ["exact", "dipole", "better-dipole", "pbd", "quantized+ss"]}),
    "Model.half_plane": ({"model": "pbd", "medium": MEDIUM, "x": [-1.0, 0.0, 1.0]}, ["model", "medium", "x"], {}),
    "models": ({}, ["all"], {}),
    "model_errors": ({"medium": MEDIUM}, ["medium"], {}),
    "select_model": ({"medium": MEDIUM}, ["medium", "model", "accuracy"], {"model": ["auto", "exact"]}),
    "validity": ({"medium": MEDIUM}, ["medium", "model"], {"model": ["dipole", "exact"]}),
    "derive": ({"medium": MEDIUM}, ["medium", "object_size", "physical_model"], {}),
    "cycles_inputs": ({"medium": MEDIUM}, ["medium", "method", "unit", "object_size"],
                      {"method": ["fixed-radius", "random-walk", "burley"]}),
    "reference": ({"medium": MEDIUM, "photons": 2000}, ["medium", "photons", "thickness", "seed", "threads", "r_max",
                                                        "r_min", "bins", "spacing", "depth_bins", "unit"], {}),
    "slab": ({"medium": MEDIUM, "thickness": 0.5}, ["medium", "thickness", "slides", "incidence", "tolerance",
                                                    "points", "unit"], {}),
    "fit.albedo": ({"albedo": [0.8, 0.5, 0.3], "distance": [1.0, 0.5, 0.25]},
                   ["albedo", "distance", "convention", "unit", "model", "eta", "g", "channels"],
                   {"convention": ["transport-mfp", "mfp", "diffuse-mfp"]}),
    "fit.slab": ({"reflectance": [0.3, 0.2], "transmittance": [0.4, 0.3], "thickness": 1.0, "eta": 1.4},
                 ["reflectance", "transmittance", "thickness", "reflectance_stderr", "eta", "g", "unscattered",
                  "slides", "model"], {}),
    "fit.profile": ({"file": "CSV"}, ["file", "model", "eta", "g", "loss", "loss_scale", "unit"], {}),
    "fit.rxt": ({"file": "RXT"}, ["file", "g", "reflectance_stderr", "lost_light", "lost_light_photons"], {}),
    "fit.gaussians": ({"source": MEDIUM, "count": 3}, ["source", "count", "model", "samples"], {}),
    "fit.burley": ({"source": MEDIUM}, ["source", "model", "samples"], {}),
    "lut": ({"medium": MEDIUM, "kind": "radial"},
            ["medium", "kind", "model", "accuracy", "unit", "tolerance", "energy", "size", "thickness", "d_min",
             "d_max", "samples", "taps", "count", "pixel", "g", "eta", "band", "range", "layout", "interpolation"],
            {"kind": KINDS}),
    "Table.write": ({"medium": MEDIUM, "kind": "radial", "path": "OUT"}, ["kind", "path"],
                    {"kind": KINDS, "path": ["OUT.json", "OUT.exr", "OUT.csv", "OUT.xml", "OUT"]}),
    "advise": ({"medium": MEDIUM, "pixel": 0.1}, ["medium", "pixel", "tolerance", "target", "object_size",
                                                   "reference", "photons"],
               {"target": ["realtime", "offline"]}),
}


def mutated_text(rng, text):
    tokens = text.replace("\n", " \n ").split(" ")
    for _ in range(rng.randint(0, 3)):
        k = rng.randrange(len(tokens))
        action = rng.random()
        if action < 0.6:
            tokens[k] = str(rng.choice(NUMBERS + STRINGS[:7] + ["#", "r", "IAD1", "7", ","]))
        elif action < 0.8:
            del tokens[k]
        else:
            tokens.insert(k, tokens[k])
    return " ".join(tokens).replace(" \n ", "\n")


def trial(seed, i):
    """(call name, keyword arguments) of trial i: the base call with 1-3 keywords mutated."""
    rng = random.Random(seed * 1000003 + i)
    name = rng.choice(sorted(CALLS))
    base, mutable, valid = CALLS[name]
    kwargs = dict(base)
    for key in rng.sample(mutable, k=min(len(mutable), rng.randint(1, 3))):
        if key in valid and rng.random() < 0.4:
            kwargs[key] = rng.choice(valid[key])
        elif key in SAFE and rng.random() < 0.2:
            kwargs[key] = SAFE[key]
        else:
            kwargs[key] = hostile_for(rng, key)
        if key in HUGE_COUNTS and isinstance(kwargs[key], (int, float)) and not isinstance(kwargs[key], bool) \
                and math.isfinite(kwargs[key]) and abs(kwargs[key]) > 1e5:
            kwargs[key] = -1  # never start a huge run: still a count the module must refuse or bound
    return name, kwargs, rng


def resolve(bs, value, scratch, i, rng):
    """Materialise the placeholders: the medium, files (mutated), output paths in the scratch directory."""
    if isinstance(value, tuple) and len(value) == 2 and callable(value[1]):
        return value[1](bs)
    if isinstance(value, str) and value in ("CSV", "RXT", "FIT"):
        path = os.path.join(scratch, f"in{i}.{value.lower()}")
        if value == "FIT":
            text = bs.fit.albedo([0.8, 0.5], [1.0, 0.5]).to_json()
        else:
            text = CSV if value == "CSV" else RXT
        with open(path, "w", errors="replace") as f:
            f.write(mutated_text(rng, text))
        return path
    if isinstance(value, str) and value == "DIR":
        return os.path.join(scratch, "directory")
    if isinstance(value, str) and value.startswith("OUT"):
        return os.path.join(scratch, f"out{i}" + value[3:])
    return value


def call(bs, name, kwargs):
    if name == "Medium.from_sigma_s_prime":
        return bs.Medium.from_sigma_s_prime(**kwargs)
    if name.startswith("Model."):
        model = bs.Model(kwargs.pop("model"))
        return getattr(model, name.split(".")[1])(**kwargs)
    if name == "Table.write":
        path = kwargs.pop("path")
        return bs.lut(**kwargs).write(path)
    target = bs
    for part in name.split("."):
        target = getattr(target, part)
    if name == "materials.get":
        return target(kwargs.pop("name"), **kwargs)
    return target(**kwargs)


def worker(seed, start, count):
    import bssrdf as bs
    with tempfile.TemporaryDirectory() as scratch:
        os.chdir(scratch)  # a hostile output name ("-1", " mm") is a relative path: it lands here
        directory = os.path.join(scratch, "directory")
        os.mkdir(directory)
        for i in range(start, start + count):
            name, kwargs, rng = trial(seed, i)
            print(f"start {i}", flush=True)
            kwargs = {k: resolve(bs, v, scratch, i, rng) for k, v in kwargs.items()}
            before = set(os.listdir(scratch))
            try:
                call(bs, name, kwargs)
                outcome = "returned"
                if not (os.path.isdir(directory) and stat.S_ISCHR(os.stat("/dev/null").st_mode)):
                    outcome = "finding: replaced a path that is not a regular file"
            except ValueError as e:
                text = str(e)
                outcome = "ValueError" if text and "\n" not in text and "internal error" not in text \
                    else f"finding: ValueError message {text[:200]!r}"
                left = set(os.listdir(scratch)) - before
                if left and outcome == "ValueError":
                    outcome = f"finding: file left after ValueError: {sorted(left)}"
            except TypeError:
                outcome = "TypeError"
            except Exception as e:  # anything else is a finding
                outcome = f"finding: {type(e).__name__}: {str(e)[:200]!r}"
            print(f"end {i} {outcome}", flush=True)


def describe(seed, i):
    name, kwargs, _ = trial(seed, i)
    shown = {k: (v[0] if isinstance(v, tuple) and len(v) == 2 and callable(v[1]) else v) for k, v in kwargs.items()}
    return f"bssrdf.{name}(**{shown!r})"


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--worker":
        worker(*map(int, sys.argv[2:5]))
        return 0
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    limit = 60.0  # seconds per call
    outcomes, findings = {}, []
    i = 0
    while i < count:  # one worker runs the trials from i on; a crash or hang restarts it after the trial
        proc = subprocess.Popen([sys.executable, __file__, "--worker", str(seed), str(i), str(count - i)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        current, started = None, time.time()
        while True:
            ready, _, _ = select.select([proc.stdout], [], [], 1.0)
            if ready:
                line = proc.stdout.readline()
                if not line:
                    break
                word, index, *rest = line.rstrip("\n").split(" ", 2)
                if word == "start":
                    current, started = int(index), time.time()
                else:
                    outcome = rest[0]
                    if outcome.startswith("finding"):
                        findings.append((outcome, describe(seed, int(index))))
                        outcome = "finding"
                    outcomes[outcome] = outcomes.get(outcome, 0) + 1
                    current = None
                    i = int(index) + 1
            elif current is not None and time.time() - started > limit:
                proc.kill()
                break
        proc.wait()
        if current is not None:  # died or hung inside trial `current`
            why = f"hang > {limit:.0f} s" if proc.returncode == -9 else f"worker died (status {proc.returncode}): " \
                + proc.stderr.read()[-300:].strip().replace("\n", " | ")
            findings.append((why, describe(seed, current)))
            outcomes["finding"] = outcomes.get("finding", 0) + 1
            i = current + 1
        elif proc.returncode != 0:
            findings.append((f"worker failed (status {proc.returncode}): {proc.stderr.read()[-300:]}", "start-up"))
            break
    print(f"{count} calls: " + ", ".join(f"{k}: {v}" for k, v in sorted(outcomes.items())) +
          f", findings: {len(findings)}")
    for what, where in findings:
        print(f"  {what}: {where}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
