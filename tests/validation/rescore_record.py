#!/usr/bin/python3
"""validate_exact rescore against the committed validation record (tools/validation/exact_v9_*).

    rescore_record.py VALIDATE_EXACT           checks
    rescore_record.py VALIDATE_EXACT --write   rewrites each set's lines for the current model in place
                                               (after a change to the model or the table; the '#   v8:'
                                               lines, another table's, are kept)

Each set of tools/validation/exact_v9_vs_montecarlo.txt, exact_v9_unchanged_vs_montecarlo.txt and
exact_v10_vs_montecarlo.txt names its stored bins (BSSRDF_VALIDATE_BINS=PREFIX, files
tools/validation/bins_v9/PREFIX_i.tsv);
scored again with the shipped table they give the record's point lines, to the last printed digit
(a table shipped without its validation scored again fails here). A malformed or missing bins file
is refused with one line on stderr, exit 2 and nothing on stdout.
"""
import glob
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
VALIDATION = os.path.join(ROOT, 'tools', 'validation')
# Last printed digit per column: alpha' (6 significant), g, eta, photons, total %, sigma, then four L2 %.
STEP = [None, 1e-3, 1e-3, 0, 1e-3, 1e-2, 1e-3, 1e-3, 1e-3, 1e-3]


def point_lines(text):
    return [line.split() for line in text.splitlines()
            if line.strip() and not line.startswith('#') and len(line.split()) == 10]


def close(recorded, scored):
    for i, (a, b) in enumerate(zip(recorded, scored)):
        a, b = float(a), float(b)
        step = STEP[i] if STEP[i] is not None else 1e-5 * abs(a)
        if abs(a - b) > step * 1.01:
            return False
    return True


def rewritten(section, out):
    """The section with its current-model block (from the column header not marked v8 to the
    'beyond the runs' noise' line) replaced by rescore's output past its first line."""
    lines = section.split('\n')
    start = next(i for i, line in enumerate(lines) if line.startswith("#    alpha'"))
    end = next(i for i in range(start, len(lines)) if lines[i].startswith('# beyond'))
    return '\n'.join(lines[:start] + out.rstrip('\n').split('\n')[1:] + lines[end + 1:])


def main():
    exe = sys.argv[1]
    write = sys.argv[2:] == ['--write']
    failures, checked = 0, 0
    for record in ('exact_v9_vs_montecarlo.txt', 'exact_v9_unchanged_vs_montecarlo.txt',
                   'exact_v10_vs_montecarlo.txt'):
        path = os.path.join(VALIDATION, record)
        parts = re.split(r'^# --- ', open(path, encoding='utf-8').read(), flags=re.M)
        sections, sections_out = parts[1:], [parts[0]]
        for section in sections:
            name = section.split(':', 1)[0]
            prefix = re.search(r'BSSRDF_VALIDATE_BINS=(\S+)', section).group(1)
            files = sorted(glob.glob(os.path.join(VALIDATION, 'bins_v9', f'{prefix}_*.tsv')))
            out = subprocess.run([exe, 'rescore', *files], capture_output=True, text=True, check=True).stdout
            if write:
                sections_out.append(rewritten(section, out))
                continue
            recorded, scored = point_lines(section.split('\n', 1)[1]), point_lines(out)  # past its command line
            if len(recorded) != len(scored) or not files:
                print(f'{record} {name}: {len(recorded)} recorded points, {len(scored)} scored')
                failures += 1
                continue
            for r, s in zip(recorded, scored):
                checked += 1
                if not close(r, s):
                    print(f'{record} {name}: recorded {" ".join(r)}\n{" " * len(record + name)}   scored   {" ".join(s)}')
                    failures += 1
        if write:
            with open(path, 'w', encoding='utf-8') as f:
                f.write('# --- '.join(sections_out))
    if write:
        return 0
    with tempfile.TemporaryDirectory() as tmp:
        junk = os.path.join(tmp, 'junk.tsv')
        with open(junk, 'w') as f:
            f.write('# alpha\' 0.5 g 0.5 eta 1.3\n# diffuse_reflectance 0.1 stderr 0.001 photons 10\n# columns\n1 2 x\n')
        good = sorted(glob.glob(os.path.join(VALIDATION, 'bins_v9', 'B_*.tsv')))[0]
        for args in ([good, junk], [os.path.join(tmp, 'missing.tsv')]):
            r = subprocess.run([exe, 'rescore', *args], capture_output=True, text=True)
            if r.returncode != 2 or r.stdout or len(r.stderr.strip().splitlines()) != 1:
                print(f'rescore {args}: exit {r.returncode}, stdout {r.stdout!r}, stderr {r.stderr!r}')
                failures += 1
    print(f'{checked} recorded points scored again, {failures} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
