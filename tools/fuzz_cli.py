#!/usr/bin/env python3
"""Random command lines against the bssrdf binary: every run must exit 0 or 2, print exactly one
line on stderr when it exits 2, never say "internal error", finish within a time limit and leave
no file behind on failure. Prints a table of outcomes; exit status 1 on any finding.

Usage: tools/fuzz_cli.py [BINARY] [COUNT] [SEED]     (default build/bssrdf 300 1)
"""
import os
import random
import subprocess
import sys
import tempfile
import time

HOSTILE = ["-1", "0", "1e308", "-1e308", "1e-308", "4.9e-324", "nan", "inf", "-inf", "1e400", "3e9",
           "18446744073709551615", "9" * 40, "", "abc", "1,2", "1,,2", "0.5", "2", "1.3", "100", "1e-9",
           "\r", "x\x1b[31m", "1e6", "64", "-0"]
COMMANDS = {
    "profile": ["--sigma-a", "--sigma-s", "--g", "--eta", "--radii", "--samples", "--r-min", "--r-max",
                "--thickness", "--model", "--unit", "--wavelengths", "--colour", "--illuminant"],
    "skin": ["--melanin", "--eumelanin", "--blood", "--oxygenation", "--epidermis", "--scattering", "--wavelengths",
             "--colour", "--illuminant", "--specular", "--profile-photons"],
    "fit skin": ["--srgb", "--melanin", "--specular", "--min-nm", "--max-nm", "--solve-step"],
    "reference": ["--sigma-a", "--sigma-s", "--g", "--eta", "-n", "--bins", "--seed", "--threads", "--r-max",
                  "--thickness", "--depth-bins", "--roulette-threshold", "--wavelengths", "--colour", "--illuminant"],
    "transmission": ["--sigma-a", "--sigma-s", "--eta", "--samples", "--d-min", "--d-max"],
    "lut": ["--sigma-a", "--sigma-s", "--kind", "--samples", "--taps", "--count", "--photons", "--tolerance",
            "--size", "--energy", "--band", "--wavelengths", "--colour", "--illuminant", "--preview", "--thickness"],
    "fit gaussians": ["--sigma-a", "--sigma-s", "-n", "--samples"],
    "fit albedo": ["--albedo", "--distance", "--eta", "--g"],
    "materials export": ["--sigma-a", "--sigma-s-prime", "--g", "--eta", "--unit", "--channels", "--to", "--wavelengths",
                         "--colour", "--illuminant"],
    "fit slab": ["--quadrature", "--baffles", "--wall-first", "--detector-reflectance", "--unscattered-in-mr",
                 "--unscattered-in-mt", "--g", "--dual-beam", "--fixed-albedo", "--fixed-optical-thickness",
                 "--fixed-mu-a", "--fixed-mu-s", "--fixed-mu-s-prime", "--incidence-angle"],
}
# Values of iad's -F form (the power law 'P lambda0 mu_s0 gamma'), mutated, for --fixed-mu-s.
POWER_LAWS = ["P 500 1 -1.3", "P 500 1", "p 0 1 1", "P 500 nan -1", "P -1 1e308 1e308", "P", "Q 500 1 1",
              "P 500 1 -1 7"]
# The medium each command starts from (the mutated options are added after it).
BASE = {"fit albedo": ["--albedo", "0.5", "--distance", "1"], "skin": [], "fit skin": ["--srgb", "0.7,0.5,0.4"],
        "materials export": ["Mine", "--to", "json", "--sigma-a", "0.1", "--sigma-s-prime", "1"]}
# fit slab reads a mutated .rxt file (iad's layouts: a count, column letters, one line).
RXT_SEEDS = ["IAD1 1.4 1.5 1 1 5 .98 1 203.2 25.4 12.7 1 .96 203.2 25.4 12.7 1 .96\n2\n500 0.3 0.2\n0.25 0.3\n",
             "IAD1 1.4 1.5 1 1 5 .98 2 203.2 25.4 12.7 1 .96 203.2 25.4 12.7 1 .96\nL r t n g\n500 0.3 0.2 1.33 0.8\n",
             "IAD1 1.4 1 1 0 5 .98 0 0 0 0 0 0 0 0 0 0 0 1 0.3 0.2",
             "IAD1 1.4 1.5 1 1 5 .98 0 0 0 0 0 0 0 0 0 0 0\nL r t A g\n500 0.3 0.2 0.05 0.5\n600 0.3 0 0.05 0.5\n"]


def mutated_rxt(rng):
    tokens = rng.choice(RXT_SEEDS).split(" ")
    for _ in range(rng.randint(0, 3)):
        k = rng.randrange(len(tokens))
        action = rng.random()
        if action < 0.6:
            tokens[k] = rng.choice(HOSTILE + ["#", "r", "x", "IAD1", "7", "u", "i"])
        elif action < 0.8:
            del tokens[k]
        else:
            tokens.insert(k, tokens[k])
    return " ".join(tokens)


# Small photon counts keep Monte Carlo runs short; the rest are random.
SAFE = {"-n": "2000", "--photons": "2000", "--profile-photons": "2000"}
# Valid values, sometimes, so the mutations also reach the paths behind them (every lut kind, a spectral medium in
# colour: --wavelengths with the base's one coefficient for all).
VALID = {"--kind": ["radial", "albedo-radius", "transmission", "preintegrated", "penumbra", "separable", "gaussians"],
         "--wavelengths": ["450,550,650", "400,500,600,700"], "--colour": ["srgb", "acescg", "rec2020"],
         "--illuminant": ["d65", "a"], "--thickness": ["0.5,2", "1"]}


def is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "build/bssrdf"
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 300
    rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    outcomes = {"exit 0": 0, "exit 2 (one line)": 0}
    findings = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(count):
            command = rng.choice(list(COMMANDS))
            if command == "fit slab":
                rxt = os.path.join(tmp, f"in{i}.rxt")
                with open(rxt, "w", errors="replace") as f:
                    f.write(mutated_rxt(rng))
                args = command.split() + ["--rxt", rxt]
            else:
                args = command.split() + BASE.get(command, ["--sigma-a", "0.1", "--sigma-s", "1"])
            for option in rng.sample(COMMANDS[command], k=rng.randint(1, 3)):
                if option == "--dual-beam":
                    args.append(option)
                    continue
                value = rng.choice(HOSTILE) if rng.random() < 0.8 or option not in SAFE else SAFE[option]
                if option in VALID and rng.random() < 0.5:
                    value = rng.choice(VALID[option])
                if option == "--preview":  # a PNG in the scratch directory, or a hostile name there
                    value = os.path.join(tmp, f"p{i}.png" if rng.random() < 0.7 else f"p{i}" + rng.choice(HOSTILE))
                if option == "--fixed-mu-s" and rng.random() < 0.5:
                    value = rng.choice(POWER_LAWS)
                if option in SAFE and is_number(value) and abs(float(value)) > 1e5:
                    value = "-1"  # never start a huge Monte Carlo run: still a count the tool must refuse or bound
                args += [option, value]
            output = os.path.join(tmp, f"out{i}.json")
            if command == "lut":
                args += ["-o", output.replace(".json", ".exr")]
            else:
                args += ["-o", output] + (["-q"] if command != "materials export" else []) if command != "fit albedo" else []
            start = time.time()
            try:
                run = subprocess.run([binary] + args, capture_output=True, timeout=60)
            except subprocess.TimeoutExpired:
                findings.append(("hang > 60 s", args))
                continue
            seconds = time.time() - start
            err = run.stderr.decode(errors="replace")
            if run.returncode == 0:
                outcomes["exit 0"] += 1
            elif run.returncode == 2 and err.count("\n") == 1 and "internal error" not in err:
                outcomes["exit 2 (one line)"] += 1
                if any(os.path.exists(p) for p in (output, output.replace(".json", ".exr"), os.path.join(tmp, f"p{i}.png"))):
                    findings.append(("file left after exit 2", args))
            else:
                findings.append((f"exit {run.returncode}: {err.strip()[:200]!r}", args))
            if seconds > 30:
                findings.append((f"slow: {seconds:.0f} s", args))
    print(f"{count} command lines: " + ", ".join(f"{k}: {v}" for k, v in outcomes.items()) + f", findings: {len(findings)}")
    for what, args in findings:
        print(f"  {what}: bssrdf {' '.join(repr(a) if not a or ' ' in a else a for a in args)}")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
