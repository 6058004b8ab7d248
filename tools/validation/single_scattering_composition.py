#!/usr/bin/env python3
"""Which composition of the dipole family reproduces the full radiative-transfer total: the model
alone, or the model plus exact single scattering (NAME+ss)?  Per case: the exact total by
adding-doubling (`bssrdf slab`, semi-infinite, per entered flux), the Monte Carlo total and its
single-scattering part (`bssrdf reference`), and each model's total alone and with +ss.

usage: single_scattering_composition.py BSSRDF_BINARY [photons]   (about 20 s at 1e6 photons)
"""
import json, subprocess, sys

cli = sys.argv[1]
photons = sys.argv[2] if len(sys.argv) > 2 else "1000000"
models = ["dipole", "better-dipole", "quantized"]


def run(*args):
    return json.loads(subprocess.run([cli, *args, "-f", "json"], check=True, capture_output=True, text=True).stdout)


print("alpha'\tg\teta\texact_total\tmc_total\tmc_single\t" + "\t".join(f"{m}\t{m}+ss" for m in models))
for g in (0.0, 0.5, 0.9):
    for eta in (1.0, 1.4):
        for ap in (0.5, 0.8, 0.9, 0.95, 0.99):
            sigma_s = ap / (1 - g)  # sigma_t' = 1/mm: alpha' = sigma_s' / (sigma_a + sigma_s')
            medium = ["--sigma-a", str(1 - ap), "--sigma-s", repr(sigma_s), "--g", str(g), "--eta", str(eta)]
            exact = run("slab", *medium)["channels"][0]["per_entered_flux"]["diffuse_reflectance"]
            mc = run("reference", *medium, "-n", photons)["channels"][0]["per_entered_flux"]
            row = [ap, g, eta, exact, mc["diffuse_reflectance"]["value"], mc["single_scattering_reflectance"]["value"]]
            for m in models:
                for name in (m, m + "+ss"):
                    row.append(run("profile", *medium, "--model", name, "--radii", "0.5,1")["channels"][0]["total_reflectance"])
            print("\t".join(f"{v:.5f}" if isinstance(v, float) else str(v) for v in row), flush=True)
