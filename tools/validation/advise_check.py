#!/usr/bin/python3
"""Checks `bssrdf advise`'s predicted image error independently of the advice code.

For each material and pixel size: the advice (seed 1, default photons, --write) names a
representation, predicts its error and writes its table; this script recomputes that
representation's error in its own code (numpy) from the written table (or, for an analytic model,
from `bssrdf profile`), against an independent, 5x larger Monte Carlo reference (seed 2, the tool's
`reference` command on its own log bins), with the same definition (README, "Choosing by what a
viewer sees"): shadow edge and one-pixel line, box-filtered, 8-bit sRGB code values, largest over
pixels, channels and a flat lit region.

Also the separable-kernel candidate of each advice (chosen or not): the kernel `bssrdf lut --kind
separable` writes with the advised taps and range, rendered here as a screen-space pass applies it
(each pixel: the taps at its centre plus their offsets, reading the irradiance linearly between
pixel centres), times the kernel's recorded total reflectance.

With a reference that has formula channels (--reference exact or auto), `reference-table` is written
as the radial-log nodes it was judged on and checked like any radial table; its predicted error
includes the reference's own uncertainty U (its measured band in image space), which the check,
against Monte Carlo, measures directly.

  /usr/bin/python3 tools/validation/advise_check.py build/bssrdf Skin1,Ketchup 0.01,0.1,1,10 [TOLERANCES [REFERENCE [PHOTONS]]]

TOLERANCES: comma-separated (default 1); REFERENCE: auto, exact or montecarlo (default auto); PHOTONS:
of the independent Monte Carlo truth (default 1000000, seed 2).
"""
import csv, io, json, math, os, subprocess, sys
import numpy as np


def run(cli, *args):
    return subprocess.run([cli, *args], check=True, capture_output=True, text=True).stdout


def reference(cli, material, photons, seed, r_min, r_max, bins=400):
    text = run(cli, "reference", "--material", material, "-n", str(photons), "--seed", str(seed), "--bin-spacing", "log",
               "--bins", str(bins), "--r-min", repr(r_min), "--r-max", repr(r_max), "-f", "csv")
    rows = list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))
    edges = np.array([0.0] + [float(r["radius_outer_mm"]) for r in rows])
    channels = [k[:-len("_R_entered")] for k in rows[0] if k.endswith("_R_entered")]  # columns C_R_entered
    area = np.pi * np.diff(edges ** 2)
    energy = {c: np.array([float(r["%s_R_entered" % c]) for r in rows]) * area for c in channels}
    stderr = {c: np.array([float(r["%s_R_entered_stderr" % c]) for r in rows]) * area for c in channels}
    return edges, channels, energy, stderr


def area_beyond(r, s):
    r, s = np.broadcast_arrays(r, s)
    out = np.where(s <= -r, np.pi * r * r, 0.0)
    inside = np.abs(s) < r
    rr, ss = r[inside], s[inside]
    out[inside] = rr * rr * np.arccos(ss / rr) - ss * np.sqrt(rr * rr - ss * ss)
    return out


def area_integral(r, s):
    h = np.maximum(r * r - s * s, 0.0)
    return s * area_beyond(r, s) - 2.0 / 3.0 * h * np.sqrt(h)


def edge_image(edges, energy, pixel):
    K = min(int(math.ceil(edges[-1] / pixel)) + 1, 4096)
    bounds = np.arange(-K, K + 1) * pixel                       # pixel boundaries
    P = area_integral(edges[None, :], -bounds[:, None])         # [boundary, radius]
    Q = (P[:-1] - P[1:]) / pixel                                # pixel average of the area beyond, per radius
    w = np.clip((Q[:, 1:] - Q[:, :-1]) / (np.pi * np.diff(edges ** 2))[None, :], 0, 1)
    edge = w @ energy
    line = edge - np.concatenate([[0.0], edge[:-1]])
    return edge, line


def srgb(v):
    v = np.clip(v, 0, 1)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def code_error(edges, ref, cand, pixel):
    worst = 0.0
    for c in ref:
        a, b = edge_image(edges, ref[c], pixel), edge_image(edges, cand[c], pixel)
        worst = max(worst, 255 * abs(srgb(ref[c].sum()) - srgb(cand[c].sum())))
        for x, y in zip(a, b):
            worst = max(worst, float(np.max(255 * np.abs(srgb(x) - srgb(y)))))
    return worst


def kernel_error(edges, ref, kernel, pixel):
    """The separable kernel's images (edge, line, flat) against the reference's, code values."""
    table = json.load(open(kernel))
    ch = {c["name"]: np.array(c["values"]) for c in table["channels"]}
    attributes = table["attributes"]
    offset = ch["offset"] * float(attributes["bssrdf:range"])
    worst = 0.0
    for c in ref:
        a_edge, a_line = edge_image(edges, ref[c], pixel)
        K = len(a_edge) // 2
        x = (np.arange(-K, K) + 0.5) * pixel                     # pixel centres
        albedo = float(attributes["bssrdf:total_reflectance." + c])
        reads = np.clip((x[:, None] + offset[None, :]) / pixel + 0.5, 0, 1)  # bilinear between centres
        edge = albedo * reads @ ch[c]
        line = edge - np.concatenate([[0.0], edge[:-1]])
        worst = max(worst, 255 * abs(srgb(ref[c].sum()) - srgb(albedo)))
        for u, v in ((a_edge, edge), (a_line, line)):
            worst = max(worst, float(np.max(255 * np.abs(srgb(u) - srgb(v)))))
    return worst


def ring_energy(edges, R):
    """int 2 pi r R(r) dr over each annulus: 16-point midpoint rule in ln r (first annulus from 1e-6 r_1)."""
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        lo = max(lo, 1e-6 * edges[1])
        u = np.linspace(math.log(lo), math.log(hi), 17)
        r = np.exp(0.5 * (u[1:] + u[:-1]))
        out.append(float(np.sum(2 * np.pi * r * r * R(r)) * (u[1] - u[0])))
    return np.array(out)


def written_table(path, channels, edges):
    table = json.load(open(path))
    ch = {c["name"]: np.array(c["values"]) for c in table["channels"]}
    out = {}
    for c in channels:
        if table["kind"] == "radial-log":
            radii, values = ch["radius." + c], np.log(np.maximum(ch[c], 1e-300))
            R = lambda r, radii=radii, values=values: np.where(
                r > radii[-1], 0.0, np.exp(np.interp(np.log(np.maximum(r, radii[0])), np.log(radii), values)))
        elif table["kind"] == "gaussians" and "variance" in ch:
            v, w = ch["variance"], ch[c]
            R = lambda r, v=v, w=w: np.sum(w[:, None] * np.exp(-np.square(r)[None, :] / (2 * v[:, None])) / (2 * np.pi * v[:, None]), axis=0)
        else:
            return None
        out[c] = ring_energy(edges, R)
    return out


def model_table(cli, material, model, channels, edges):
    radii = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        lo = max(lo, 1e-6 * edges[1])
        u = np.linspace(math.log(lo), math.log(hi), 17)
        radii.extend(np.exp(0.5 * (u[1:] + u[:-1])))
    text = run(cli, "profile", "--material", material, "--model", model, "--radii", ",".join(repr(float(r)) for r in radii), "-f", "csv")
    rows = list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))
    out = {}
    for c in channels:
        R = np.array([float(r[c + "_per_mm2"]) for r in rows]).reshape(-1, 16)
        r = np.array(radii).reshape(-1, 16)
        du = np.array([(math.log(hi) - math.log(max(lo, 1e-6 * edges[1]))) / 16 for lo, hi in zip(edges[:-1], edges[1:])])
        out[c] = np.sum(2 * np.pi * r * r * R, axis=1) * du
    return out  # the tail beyond the last annulus is not added (the tool adds it to the last annulus)


def main():
    cli, materials, pixels = sys.argv[1], sys.argv[2].split(","), [float(p) for p in sys.argv[3].split(",")]
    tolerances = sys.argv[4].split(",") if len(sys.argv) > 4 else ["1"]
    reference_kind = sys.argv[5] if len(sys.argv) > 5 else "auto"
    photons = int(sys.argv[6]) if len(sys.argv) > 6 else 1_000_000
    # exact_checked: the exact model's own image error against the Monte Carlo truth (what U bounds).
    print("material\tpixel_mm\ttolerance\tchoice\tpredicted\tchecked\tU\texact_checked\treference_noise\tseparable\tpredicted\tchecked")
    workdir = "/tmp/advise_check_%d" % os.getpid()
    for material in materials:
        truth_edges = None
        for tolerance in tolerances:
            advice = []
            for p in pixels:
                out = subprocess.run([cli, "advise", "--material", material, "--pixel", "%gmm" % p, "--tolerance", tolerance,
                                      "--reference", reference_kind, "-f", "json", "--write", "%s/%s/%g" % (workdir, tolerance, p)],
                                     capture_output=True, text=True)
                if out.returncode == 2:  # no choice: nothing to write; the advice again without --write
                    out = subprocess.run([cli, "advise", "--material", material, "--pixel", "%gmm" % p, "--tolerance",
                                          tolerance, "--reference", reference_kind, "-f", "json"], check=True,
                                         capture_output=True, text=True)
                advice.append(json.loads(out.stdout))
            if truth_edges is None:
                r_max = 10 * advice[0]["profile_radius_mm"]  # light beyond it (not in the CSV) is negligible
                edges, channels, truth, _ = reference(cli, material, photons, 2, 1e-4, r_max)
                truth_edges = edges
                table = None  # the advised Monte Carlo reference-table, run only if chosen
                exact = model_table(cli, material, "exact", channels, edges)
            for p, a in zip(pixels, advice):
                name = a["choice"]["representation"] if a["choice"] else None
                path = "%s/%s/%g/%s.%s.json" % (workdir, tolerance, p, material, (name or "").replace(":", "_"))
                cand = None
                if name == "reference-table":
                    kind = json.load(open(path))["kind"]
                    if kind != "radial-log" and table is None:
                        table = reference(cli, material, 200_000, 1, 1e-4, r_max)[2]
                    cand = written_table(path, channels, edges) if kind == "radial-log" else table
                elif name == "lambertian":  # its albedo as written
                    albedo = {c["name"]: c["values"][0] for c in json.load(open(path))["channels"]}
                    cand = {c: np.concatenate([[albedo[c]], np.zeros(len(truth[c]) - 1)]) for c in channels}
                elif name and ":" in name:
                    cand = written_table(path, channels, edges)
                elif name:
                    cand = model_table(cli, material, name, channels, edges)
                kernel = next(c for c in a["candidates"] if c["representation"].startswith("separable-"))
                kpath = "%s/%s/%g/%s.kernel.json" % (workdir, tolerance, p, material)
                os.makedirs(os.path.dirname(kpath), exist_ok=True)  # no choice: --write made nothing
                run(cli, "lut", "--kind", "separable", "--material", material, "--model", kernel["representation"].split(":")[1],
                    "--taps", "%d" % kernel["parameters"]["taps"], "--range", repr(kernel["parameters"]["range_mm"]), "-o", kpath, "-q")
                separable = f"{kernel['representation']}\t{kernel['error']:.3f}\t{kernel_error(edges, truth, kpath, p):.3f}"
                U = f'{a.get("reference_uncertainty", 0):.3f}\t{code_error(edges, truth, exact, p):.3f}'
                if not name or cand is None:
                    print(f"{material}\t{p:g}\t{tolerance}\t{name}\t-\t(not checked)\t{U}\t\t{separable}", flush=True)
                    continue
                checked = code_error(edges, truth, cand, p)
                print(f"{material}\t{p:g}\t{tolerance}\t{name}\t{a['choice']['error']:.3f}\t{checked:.3f}\t{U}\t"
                      f"{a['reference_noise']:.3f}\t{separable}", flush=True)


if __name__ == "__main__":
    main()
