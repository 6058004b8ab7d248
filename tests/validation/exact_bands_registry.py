#!/usr/bin/python3
"""The exact model's bands in src/model_registry.cpp against the validation records they come from.

    exact_bands_registry.py

Runs tools/validation/exact_bands.py with the command docs/exact.md names and checks, per region and
for the whole domain, that the registry states no band tighter than the records measure (worst total,
worst of the near and far L2 beyond noise) and none looser by more than 0.002 (a stale band). Then
checks exact_bands.py's --also on two small records: a point given again replaces its run there and
a new point joins its region's group, without dropping that group's other points. Exit 1 on any
mismatch, with one line each.
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
VALIDATION = os.path.join(ROOT, 'tools', 'validation')
BANDS = os.path.join(VALIDATION, 'exact_bands.py')
COMMAND = ('exact_vs_montecarlo.txt exact_extended_vs_montecarlo.txt --then exact_v8_vs_montecarlo.txt '
           'exact_v9_unchanged_vs_montecarlo.txt --then exact_v9_vs_montecarlo.txt '
           '--also exact_v10_vs_montecarlo.txt').split()
STALE = 0.002


def bands(args, cwd):
    out = subprocess.run([sys.executable, BANDS, *args], capture_output=True, text=True, check=True, cwd=cwd).stdout
    measured = {}
    for line in out.splitlines()[1:]:
        m = re.match(r'(.+?)\s{2,}(\d+)(?:\s+([\d.]+)\s+([\d.]+)\s+([\d.]+))?', line)
        if m and m.group(3):
            measured[m.group(1).strip()] = (int(m.group(2)), float(m.group(3)) / 100,
                                            max(float(m.group(4)), float(m.group(5))) / 100)
    return measured


def registry():
    source = open(os.path.join(ROOT, 'src', 'model_registry.cpp'), encoding='utf-8').read()
    block = source[source.index('exact.reference_accuracy'):]
    block = block[:block.index('}};')]
    domain = re.search(r'ReferenceAccuracy\{\s*([\d.]+),\s*([\d.]+),', block)
    regions = {name: (float(t), float(p))
               for name, t, p in re.findall(r'Region\{"([^"]+)",[^}]*?,\s*([\d.]+),\s*([\d.]+)\}', block)}
    regions['domain'] = (float(domain.group(1)), float(domain.group(2)))
    return regions


def main():
    failures = 0
    measured = bands(COMMAND, VALIDATION)
    stated = registry()
    for name, (points, total, profile) in measured.items():
        if name not in stated:
            print(f'{name}: measured ({points} points) but not in the registry')
            failures += 1
            continue
        for what, says, is_ in (('total', stated[name][0], total), ('profile', stated[name][1], profile)):
            if says < is_ - 1e-12 or says > is_ + STALE:
                print(f'{name}: the registry states {what} {says}, the records measure {is_:.5f}')
                failures += 1
    with tempfile.TemporaryDirectory() as tmp:
        line = '{:>11} {:6.3f} {:6.3f} {:10d} {:8.3f} {:7.2f} {:8.3f} {:8.3f} {:8.3f} {:8.3f}\n'
        with open(os.path.join(tmp, 'old.txt'), 'w') as f:  # two tissue points
            f.write(line.format(0.5, 0.5, 1.3, 1000, 0.1, 1.0, 5.0, 0.0, 1.0, 0.0))
            f.write(line.format(0.6, 0.5, 1.3, 1000, 0.1, 1.0, 2.0, 0.0, 1.0, 0.0))
        with open(os.path.join(tmp, 'again.txt'), 'w') as f:  # the first again, one new
            f.write(line.format(0.5, 0.5, 1.3, 1000, 0.1, 1.0, 1.5, 0.0, 1.0, 0.0))
            f.write(line.format(0.7, 0.5, 1.3, 1000, 0.3, 1.0, 1.0, 0.0, 1.0, 0.0))
        got = bands(['old.txt', '--also', 'again.txt'], tmp).get('tissue')
        if got != (3, 0.003, 0.02):
            print(f'--also: tissue {got}, expected 3 points, total 0.3 %, profile 2 % (5 % replaced)')
            failures += 1
    print(f'{len(measured)} bands checked against the registry, {failures} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
