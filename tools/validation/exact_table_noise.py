#!/usr/bin/python3
"""The exact table's own noise, from its stored per-entry standard errors.

    tools/validation/exact_table_noise.py [--g G] [data/exact/exact_profile.bin ...]

--g G: only the nodes at the table's g node G (e.g. a trial table's new nodes, data/exact/README.md).

Per node: the relative L2 of r R(r) over dr inside and beyond one transport mfp (the measure of
tools/validation/validate_exact), with R from the stored y = 2 pi r^2 R and the noise from the
stored relative standard error of y (entries marked 65535, continued past the measured radii, count
as noiseless). Printed: median and worst over the nodes each kind of Monte Carlo run serves
(data/exact/README.md, "How each part is computed").
"""
import json
import struct
import sys

import numpy as np


def fail(message):
    print(f'exact_table_noise.py: {message}', file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        data = open(path, 'rb').read()
    except OSError as error:
        fail(f'{path}: {error.strerror}')
    if data[:8] != b'BSSRDFX1':
        fail(f'{path}: not an exact table (no BSSRDFX1 magic)')
    length = struct.unpack('<Q', data[8:16])[0]
    header = json.loads(data[16:16 + length])
    offset = 16 + length
    shape = (len(header['eta']), len(header['g']), len(header['albedo_prime']), header['radii'])
    count = int(np.prod(shape))
    ln_y = np.frombuffer(data, '<f4', count, offset).reshape(shape)
    if header['version'] < 3:  # errors inline after ln_y
        relative = np.frombuffer(data, '<u2', count, offset + 4 * count).reshape(shape)
        return header, ln_y.astype(float), relative
    # version 3: in PATH.errors (magic BSSRDFE1, uint64 count, the values)
    try:
        errors = open(path + '.errors', 'rb').read()
    except OSError as error:
        fail(f'{path}.errors: {error.strerror} (the table\'s relative errors are kept beside it)')
    if errors[:8] != b'BSSRDFE1' or struct.unpack('<Q', errors[8:16])[0] != count or len(errors) != 16 + 2 * count:
        fail(f'{path}.errors: not the errors of {path} ({count} values)')
    relative = np.frombuffer(errors, '<u2', count, 16).reshape(shape)
    return header, ln_y.astype(float), relative


def noise(path):
    header, ln_y, relative = load(path)
    r = np.exp(header['ln_r0'] + header['d_ln_r'] * np.arange(header['radii']))
    r_R = np.exp(ln_y) / r  # 2 pi r R(r)
    error = np.where(relative == 65535, 0, relative) * 1e-4
    dr = r  # per unit ln r

    def l2(inside):
        return np.sqrt(np.sum((r_R * error) ** 2 * dr * inside, axis=-1) / np.sum(r_R ** 2 * dr * inside, axis=-1))

    return header, l2(r <= 1), l2(r > 1)


def main():
    args = sys.argv[1:]
    only_g = None
    if args[:1] == ['--g']:
        if len(args) < 2:
            fail('--g: give a g node of the table')
        try:
            only_g = float(args[1])
        except ValueError:
            fail(f"--g: '{args[1]}' is not a number (a g node of the table)")
        args = args[2:]
    paths = args or ['data/exact/exact_profile.bin']
    for path in paths:
        header, near, far = noise(path)
        albedo = np.array(header['albedo_prime'])[None, None, :]
        g = np.array(header['g'])[None, :, None]
        at_g = np.ones_like(g, dtype=bool)
        if only_g is not None:
            at_g = np.isclose(g, only_g, rtol=0, atol=1e-9)
            if not at_g.any():
                fail(f'--g: {only_g} is not a g node of {path} (its nodes: {", ".join(map(str, header["g"]))})')
        scope = '' if only_g is None else f', g {only_g} nodes only'
        print(f'# {path}{scope}: relative L2 of r R(r) from the stored standard errors, % (median, worst)')
        print(f'# {"nodes":34s} {"near median":>11s} {"worst":>6s} {"far median":>10s} {"worst":>6s}')
        parts = [("alpha' > 0.99 (non-absorbing run)", 0.99, 1, 0, 1),
                 ("  of which g >= 0.85", 0.99, 1, 0.85, 1),
                 ("0.9 < alpha' <= 0.99 (base 0.99)", 0.9, 0.99, 0, 1),
                 ("0.5 < alpha' <= 0.9 (base 0.9)", 0.5, 0.9, 0, 1),
                 ("0.1 < alpha' <= 0.5 (base 0.5)", 0.1, 0.5, 0, 1),
                 ("alpha' <= 0.1 (bases 0.01, 0.1)", 0, 0.1, 0, 1),
                 ("  of which alpha' <= 0.012, g >= 0.8", 0, 0.012, 0.8, 1)]
        for name, lo, hi, g_lo, g_hi in parts:
            mask = np.broadcast_to((albedo > lo) & (albedo <= hi) & (g >= g_lo) & (g <= g_hi) & at_g, near.shape)
            if not mask.any():
                continue
            print(f'{name:36s} {100 * np.median(near[mask]):11.2f} {100 * near[mask].max():6.2f} '
                  f'{100 * np.median(far[mask]):10.2f} {100 * far[mask].max():6.2f}')


if __name__ == '__main__':
    main()
