#!/usr/bin/env python3
"""Agreement of 'bssrdf fit slab --rxt' with Prahl's iad on iad's own example files.

For every .rxt file under RXT_DIR (iad's tests/rxt: 0_sphere, 1_sphere, 2_sphere) this runs ours
and compares mu_a and mu_s' row by row with iad's results, read from IAD_RESULTS/<sphere dir>/<name>.txt
(iad's output file) or computed here with --iad PATH. Rows compared: those iad solves ('*') and we
solve. Rows iad flags (its last column not '*': a measurement out of range, or 'x', its search
stalled) are counted by what ours says: flagged (not converged), marked (converged, with a status
saying why iad may stop there, e.g. near its albedo edge a = 1), or neither; --require-iad-flags-marked
fails when any row iad flags is neither. Rows we flag or mark that iad solves are counted too.

iad prints 4 decimals, too few for a 0.1 % comparison; its results here come from iad 4-0-0 with
one change, the format of its result rows ("%6.4f" -> "%.10g" in print_optical_property_result),
made by tools/validation/iad_precision.sh.

Usage:
  iad_agreement.py --bssrdf build/bssrdf --rxt-dir IAD/tests/rxt --iad-results DIR [--quadrature 8]
  iad_agreement.py ... --iad IAD/src/iad_hp --iad-args "-M 0 -q 32" --iad-results OUT_DIR
  iad_agreement.py ... --iad-args "-M 0 -a 0.9" --ours-args "--fixed-albedo 0.9" --quadrature 8 (a constraint)
Prints a table per sphere count (files parsed, rows compared, median and 90th percentile of
|ours/iad - 1| over mu_a and mu_s') and exits 1 when --max-median / --max-p90 are exceeded.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys
import time


def iad_rows(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith('#') or not line.strip():
                continue
            parts = line.split()
            if len(parts) < 9:
                continue
            try:
                values = [float(x) for x in parts[:8]]
            except ValueError:
                continue
            rows.append({'mu_a': values[5], 'mu_s_prime': values[6], 'g': values[7], 'flag': parts[8]})
    return rows


def percentile(values, q):
    if not values:
        return float('nan')
    s = sorted(values)
    k = (len(s) - 1) * q
    lo = int(k)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (s[hi] - s[lo]) * (k - lo)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--bssrdf', required=True)
    p.add_argument('--rxt-dir', required=True)
    p.add_argument('--iad-results', required=True)
    p.add_argument('--iad', help='run this iad to make the results (else they must exist)')
    p.add_argument('--iad-args', default='-M 0 -q 32')
    p.add_argument('--quadrature', type=int, default=0, help='ours: --quadrature N (0: our default)')
    p.add_argument('--ours-args', default='', help="more options for ours, e.g. the constraint matching --iad-args "
                   "('--fixed-albedo 0.9' for '-a 0.9')")
    p.add_argument('--files', nargs='*', help='only these files (sphere_dir/name.rxt)')
    p.add_argument('--max-median', type=float, default=None)
    p.add_argument('--max-p90', type=float, default=None)
    p.add_argument('--details', action='store_true', help='print every file')
    p.add_argument('--require-all', action='store_true', help='fail when a file is not compared')
    p.add_argument('--require-iad-flags-marked', action='store_true',
                   help='fail when a row iad flags is neither flagged nor marked by ours')
    a = p.parse_args()
    if a.quadrature and not 4 <= a.quadrature <= 256:
        print(f'--quadrature = {a.quadrature}: accepted range is 4 to 256', file=sys.stderr)
        return 2
    files = a.files or sorted(os.path.join(d, f) for d in os.listdir(a.rxt_dir)
                              if os.path.isdir(os.path.join(a.rxt_dir, d))
                              for f in os.listdir(os.path.join(a.rxt_dir, d)) if f.endswith('.rxt'))
    summary = {}
    timing = {'ours': 0.0, 'iad': 0.0, 'rows': 0}
    for rel in files:
        sphere_dir, name = os.path.split(rel)
        s = summary.setdefault(sphere_dir, {'files': 0, 'parsed': 0, 'refused': [], 'dev': [], 'rows': 0,
                                            'iad_flagged': 0, 'both_flagged': 0, 'marked': 0, 'only_iad': 0,
                                            'only_ours': 0, 'only_ours_marked': 0, 'unmarked': [],
                                            'truncated': []})
        s['files'] += 1
        rxt = os.path.join(a.rxt_dir, rel)
        out = os.path.join(a.iad_results, sphere_dir, name[:-4] + '.txt')
        if a.iad:
            os.makedirs(os.path.dirname(out), exist_ok=True)
            t0 = time.time()
            subprocess.run([a.iad] + shlex.split(a.iad_args) + ['-o', out, rxt], stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
            timing['iad'] += time.time() - t0
        reference = iad_rows(out) if os.path.exists(out) else []
        cmd = [a.bssrdf, 'fit', 'slab', '--rxt', rxt, '-f', 'json']
        if a.quadrature:
            cmd += ['--quadrature', str(a.quadrature)]
        cmd += shlex.split(a.ours_args)
        t0 = time.time()
        r = subprocess.run(cmd, capture_output=True, text=True)
        elapsed = time.time() - t0
        if r.returncode != 0:
            s['refused'].append(f'{name}: {r.stderr.strip()}')
            continue
        s['parsed'] += 1
        ours = json.loads(r.stdout)['rows']
        if len(reference) > len(ours) or not reference:
            s['refused'].append(f'{name}: iad has {len(reference)} rows, ours {len(ours)}')
            continue
        if len(reference) < len(ours):  # iad stopped early (e.g. killed by a time limit)
            s['truncated'].append(f'{name}: iad output has {len(reference)} of {len(ours)} rows; compared those')
            ours = ours[:len(reference)]
        timing['ours'] += elapsed
        timing['rows'] += len(ours)
        file_dev = []
        for mine, theirs in zip(ours, reference):
            iad_ok = theirs['flag'] == '*'
            ours_ok = mine['converged']
            ours_marked = ours_ok and mine['status'] != 'converged'  # converged, with a note on iad's search
            if a.details and iad_ok != ours_ok:
                print(f"    {rel} row {mine['line']}: iad '{theirs['flag']}' {theirs['mu_a']:.4g} {theirs['mu_s_prime']:.4g}, "
                      f"ours {mine['mu_a']['value']:.4g} {mine['mu_s_prime']['value']:.4g} {mine['status']}")
            if not iad_ok:
                s['iad_flagged'] += 1
                s['both_flagged' if not ours_ok else 'marked' if ours_marked else 'only_iad'] += 1
                if ours_ok and not ours_marked:
                    s['unmarked'].append(f"{name} line {mine['line']} (iad '{theirs['flag']}')")
                continue
            if not ours_ok:
                s['only_ours'] += 1
                continue
            if ours_marked:
                s['only_ours_marked'] += 1
            s['rows'] += 1
            for key in ('mu_a', 'mu_s_prime'):
                ref = theirs[key]
                val = mine[key]['value']
                d = abs(val / ref - 1) if ref != 0 else abs(val)
                s['dev'].append(d)
                file_dev.append(d)
        if a.details:
            print(f'  {rel}: {len(ours)} rows, median {percentile(file_dev, 0.5):.2e}, '
                  f'max {max(file_dev) if file_dev else float("nan"):.2e}')
    failed = False
    print(f'ours: {a.bssrdf}' + (f' --quadrature {a.quadrature}' if a.quadrature else ' (default quadrature)') +
          (f' {a.ours_args}' if a.ours_args else '') +
          f'; iad results: {a.iad_results}' + (f' (iad {a.iad_args})' if a.iad else ''))
    print('| files | parse | rows compared | median / p90 of |ours/iad - 1| (mu_a, mu_s\') '
          '| iad flags: ours flag / mark / neither | iad solves: ours flag / mark |')
    print('|---|---|---|---|---|---|')
    for d, s in sorted(summary.items()):
        med, p90 = percentile(s['dev'], 0.5), percentile(s['dev'], 0.9)
        print(f"| {d} | {s['parsed']} of {s['files']} | {s['rows']} | {med:.2e} / {p90:.2e} "
              f"| {s['both_flagged']} / {s['marked']} / {s['only_iad']} | {s['only_ours']} / {s['only_ours_marked']} |")
        if a.require_iad_flags_marked and s['only_iad']:
            failed = True
            print(f"rows iad flags that ours neither flags nor marks ({d}): {', '.join(s['unmarked'])}")
        if a.max_median is not None and not med <= a.max_median:
            failed = True
        if a.max_p90 is not None and not p90 <= a.max_p90:
            failed = True
    for d, s in sorted(summary.items()):
        for why in s['refused']:
            print(f'not compared {d}/{why}')
            failed = failed or a.require_all
        for why in s['truncated']:
            print(f'partly compared {d}/{why}')
    if timing['rows']:
        print(f"time per row: ours {timing['ours'] / timing['rows'] * 1e3:.1f} ms"
              + (f", iad {timing['iad'] / timing['rows'] * 1e3:.1f} ms" if a.iad else ''))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
