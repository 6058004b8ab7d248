#!/usr/bin/env python3
"""The exact model's accuracy bands per region, from validate_exact's outputs.

    tools/validation/exact_bands.py OUTPUT... [--then LATER_OUTPUT...]... [--also CURRENT_OUTPUT...]

Reads every point line (alpha', g, eta, photons, total %, sigma, near %, noise %, far %, noise %);
a point given again (validate_exact at ...: the same alpha', g and eta to 5 digits) replaces its
earlier run. Outputs after --then measure a newer table or model: a region with points there takes
its points from the last such group alone (the earlier runs measured what no longer ships). Outputs
after --also measure the shipped model where a table change moved it: each of their points joins the
group its region takes, replacing a run at the same point (a point the change moved, run again).
Prints, per region of src/model_registry.cpp (first match wins) and for the whole domain, the
points, the worst |total| and the worst L2 excess sqrt(L2^2 - noise^2), near and far: the band the
registry states is the worst total and the worse of the two L2 figures."""
import math
import sys

# (name, alpha' min, max, g min, max, eta min, max): keep in step with the registry's regions.
REGIONS = [
    ("no scattering", 0, 0, 0, 1, 0, 10),
    ("tissue", 0.05, 0.9999, 0, 0.9, 1, 1.6),
    ("forward, mid albedo", 0.05, 0.99, 0.9, 0.98, 1, 1.6),
    ("forward, mid albedo, g 0.98-0.99", 0.05, 0.99, 0.98, 0.99, 1, 1.6),
    ("low albedo", 0, 0.05, 0, 0.99, 1, 1.6),
    ("milk-like", 0.99, 0.998, 0.9, 0.95, 1, 1.6),
    ("near conservative", 0.9999, 1, 0, 0.9, 1, 1.6),
    ("forward, near conservative", 0.9999, 1, 0.9, 0.99, 1, 1.6),
    ("strongly forward, near conservative", 0.9999, 1, 0.99, 0.999, 1, 1.6),
    ("forward, low albedo", 0, 0.05, 0.99, 0.999, 1, 1.6),
    ("strongly forward", 0.05, 1, 0.99, 0.999, 1, 1.6),
    ("forward, high albedo, g 0.98-0.99", 0.99, 0.9999, 0.98, 0.99, 1, 1.6),
    ("forward, high albedo", 0.99, 0.9999, 0.9, 0.98, 1, 1.6),
    ("high index", 0, 1, 0, 0.999, 1.6, 2.0),
]


def points(paths):
    seen = {}
    for path in paths:
        try:
            lines = open(path, encoding="utf-8").readlines()
        except OSError as error:
            print(f"exact_bands.py: {path}: {error.strerror}", file=sys.stderr)
            sys.exit(2)
        for line in lines:
            if line.startswith("#") or not line.strip():
                continue
            fields = line.split()
            if len(fields) != 10:
                continue
            try:
                a, g, eta, photons, total, sigma, near, near_noise, far, far_noise = map(float, fields)
            except ValueError:
                continue
            point = dict(a=a, g=g, eta=eta, total=abs(total), sigma=sigma,
                         near=math.sqrt(max(0.0, near * near - near_noise * near_noise)),
                         far=math.sqrt(max(0.0, far * far - far_noise * far_noise)))
            seen[key(point)] = point
    return list(seen.values())


def key(p):
    """A point's identity: the same alpha', g and eta to the digits validate_exact prints."""
    return (round(p["a"], 5), round(p["g"], 3), round(p["eta"], 3))


def region(p):
    for name, a0, a1, g0, g1, e0, e1 in REGIONS:
        if a0 <= p["a"] <= a1 and g0 <= p["g"] <= g1 and e0 <= p["eta"] <= e1:
            return name
    return "elsewhere"


def main():
    if len(sys.argv) < 2:
        print("usage: exact_bands.py OUTPUT... [--then LATER_OUTPUT...]... [--also CURRENT_OUTPUT...]", file=sys.stderr)
        return 2
    groups, also, target = [[]], [], None
    for arg in sys.argv[1:]:
        if arg == "--then":
            groups.append([])
            target = None
        elif arg == "--also":
            target = also
        else:
            (groups[-1] if target is None else target).append(arg)
    measured = [points(group) for group in groups]
    current = points(also) if also else []
    rows = []
    for name, *_ in REGIONS:
        group = []
        for pts in measured:  # the last group with points in the region stands
            here = [p for p in pts if region(p) == name]
            group = here or group
        for p in current:  # then the current runs join it, each replacing a run at its point
            if region(p) == name:
                group = [q for q in group if key(q) != key(p)] + [p]
        rows.append((name, group))
    pts = [p for _, group in rows for p in group] + [p for m in measured + [current] for p in m
                                                      if region(p) == "elsewhere"]
    rows.append(("domain", pts))
    print(f"{'region':40s} {'points':>6s} {'total %':>8s} {'near %':>7s} {'far %':>7s}   worst profile at")
    for name, group in rows:
        if not group:
            print(f"{name:40s} {0:6d}")
            continue
        worst = max(group, key=lambda p: max(p["near"], p["far"]))
        print(f"{name:40s} {len(group):6d} {max(p['total'] for p in group):8.3f} "
              f"{max(p['near'] for p in group):7.3f} {max(p['far'] for p in group):7.3f}   "
              f"alpha' {worst['a']:.6g}, g {worst['g']:.3f}, eta {worst['eta']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
