#!/usr/bin/env python3
"""Fits the two-layer skin model to every subject of a NIST skin reflectance file (bssrdf fit skin) and prints, per
subject, the fitted parameters, RMS, CIEDE2000 (D65) and CPU time, then the median and worst RMS and the median
CIEDE2000 against the goals of issue 26 (median RMS <= 0.010, worst <= 0.020, median dE2000 <= 1.0, <= 2 s each).

Usage: tools/skin_nist.py [BSSRDF_BINARY] [SPECTRUM_FILE] [extra fit options...]
Exit status 1 when a goal is missed, 2 on bad use."""
import json
import pathlib
import statistics
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
binary = sys.argv[1] if len(sys.argv) > 1 else str(root / "build" / "bssrdf")
data = sys.argv[2] if len(sys.argv) > 2 else str(root / "data" / "skin" / "nist_skin_subjects_1-10.tsv")
extra = sys.argv[3:]
header = None
for line in open(data, encoding="utf-8"):
    if line.startswith("#") and "wavelength" in line:
        header = line.lstrip("#").split()
if not header:
    print(f"skin_nist: {data}: no '# wavelength_nm ...' header naming the columns", file=sys.stderr)
    sys.exit(2)
names = ["melanin", "eumelanin", "blood", "oxygenation", "epidermis", "scattering", "scattering_power"]
print("subject     " + " ".join(f"{n[:11]:>12}" for n in names) + "      rms   dE2000  cpu_s  status")
rms, de, cpu = [], [], []
for column in header[1:]:
    run = subprocess.run([binary, "fit", "skin", "--spectrum", data, "--column", column, "-f", "json", *extra],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print(f"{column}: {run.stderr.strip()}", file=sys.stderr)
        sys.exit(1)
    doc = json.loads(run.stdout)
    p = doc["parameters"]
    cells = []
    for n in names:
        e = p[n]["stderr"]
        cells.append(f"{p[n]['value']:.4g}±{e:.2g}" if e is not None else f"{p[n]['value']:.4g}±?")
    print(f"{column:<11} " + " ".join(f"{c:>12}" for c in cells) +
          f"  {doc['rms']:.4f}  {doc['delta_e2000']:6.3f}  {doc['cpu_seconds']:5.2f}  {doc['status']}")
    rms.append(doc["rms"]), de.append(doc["delta_e2000"]), cpu.append(doc["cpu_seconds"])
summary = (f"median rms {statistics.median(rms):.4f} (goal <= 0.010), worst {max(rms):.4f} (<= 0.020), "
           f"median dE2000 {statistics.median(de):.2f} (<= 1.0), cpu median {statistics.median(cpu):.2f} s, "
           f"worst {max(cpu):.2f} s (<= 2)")
print(summary)
ok = statistics.median(rms) <= 0.010 and max(rms) <= 0.020 and statistics.median(de) <= 1.0
sys.exit(0 if ok else 1)
