#!/usr/bin/python3
"""Compares two directories of `bssrdf lut --all -f json` outputs of one kind, file by file: the
largest difference of any table value relative to the largest magnitude of its channel, and how many
files differ at all. It measures whether a change to a table kind moved its values (accuracy kept:
differences at the level of rounding, 1e-15, or none). Where the kind records its own error measures
in the header (`bssrdf:*_error` attributes, per channel `*_error.C`: radial's max_error against the
model, gaussians' relative_l2_error and conservation_error, transmission's adding_doubling_error), it
also prints the worst |value| over every file and channel, baseline -> new, one line each.

    lut_compare.py BASELINE_DIR NEW_DIR      (prints a summary line, then one per recorded measure)
"""
import json
import pathlib
import sys


def numbers(doc):
    for channel in doc["channels"]:
        yield channel.get("name", "?"), channel["values"]


def recorded_errors(directory):
    """Worst |value| of each `bssrdf:*_error` attribute (per channel: `name.C`) over the directory."""
    worst = {}
    for path in sorted(directory.glob("*.json")):
        for key, value in json.loads(path.read_text())["attributes"].items():
            measure = key.split(".")[0]
            if not measure.endswith("_error") or not isinstance(value, (int, float)):
                continue
            worst[measure] = max(worst.get(measure, 0.0), abs(value))
    return worst


def shown(value):
    return "absent" if value is None else f"{value:.4g}"


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: lut_compare.py BASELINE_DIR NEW_DIR")
    old_dir, new_dir = (pathlib.Path(p) for p in sys.argv[1:])
    worst, worst_where, files, differing, identical_bytes = 0.0, "", 0, 0, 0
    for old_path in sorted(old_dir.glob("*.json")):
        new_path = new_dir / old_path.name
        if not new_path.exists():
            sys.exit(f"lut_compare: {new_path} missing")
        files += 1
        if old_path.read_bytes() == new_path.read_bytes():
            identical_bytes += 1
            continue
        old, new = (dict(numbers(json.loads(p.read_text()))) for p in (old_path, new_path))
        changed = False
        for name, a in old.items():
            b = new[name]
            if len(a) != len(b):
                sys.exit(f"lut_compare: {old_path.name} {name}: {len(a)} values, then {len(b)}")
            scale = max((abs(x) for x in a), default=0) or 1
            for x, y in zip(a, b):
                if x != y:
                    changed = True
                    d = abs(x - y) / scale
                    if d > worst:
                        worst, worst_where = d, f"{old_path.name} {name}"
        differing += changed
    print(f"{files} files: {identical_bytes} byte-identical, {differing} with a changed value; "
          f"largest change {worst:.2g} of the channel's largest value{' (' + worst_where + ')' if worst_where else ''}")
    old_errors, new_errors = recorded_errors(old_dir), recorded_errors(new_dir)
    for measure in sorted(set(old_errors) | set(new_errors)):
        old, new = shown(old_errors.get(measure)), shown(new_errors.get(measure))
        print(f"    own error measure {measure.removeprefix('bssrdf:')}: worst {old} -> {new}")


main()
