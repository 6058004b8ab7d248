#!/usr/bin/python3
"""generate_exact_table's state files across grid versions (data/exact/README.md).

    state_versions.py GENERATE_EXACT_TABLE

A state file written by generator version 6 (41 albedo nodes from 0.001) is read into version 7's
grid (six more nodes below 0.001): a run that does not serve the new nodes (base 0.5) continues from
its photons, its rows moved up by six; the base-0.01 run, which serves them, is traced again from
its first chunk; a file of any other size is refused with one line, exit 2. Uses the node g 0,
eta 1.0, whose photons cost about two scatterings each.
"""
import os
import struct
import subprocess
import sys
import tempfile

BINS = 79  # 77 radii + the bins inside the first and beyond the last edge
V6, V7, LOW = 41, 47, 6
MARK = 1e6  # written into every version-6 row of ms_sum: far above any tally of these few photons


def size(albedos):
    return 8 + 48 + (2 * albedos * BINS + 4 * albedos) * 8


def write_v6(path, photons, chunks):
    with open(path, 'wb') as f:
        f.write(b'EXSTATE1' + struct.pack('<3Q3d', photons, chunks, 0, 0, 0, 0))
        f.write(bytes(2 * V6 * BINS * 8))           # bin_sum, bin_sq
        f.write(struct.pack(f'<{V6}d', *[MARK] * V6))  # ms_sum
        f.write(bytes(3 * V6 * 8))                  # ms_sq, ss_sum, ss_sq
    assert os.path.getsize(path) == size(V6)


def read(path):
    data = open(path, 'rb').read()
    photons, chunks = struct.unpack('<2Q', data[8:24])
    offset = 56 + 2 * V7 * BINS * 8
    return len(data), photons, chunks, struct.unpack(f'<{V7}d', data[offset:offset + 8 * V7])


def run(generator, state, *args):
    return subprocess.run([generator, 'run', '--state', state, '--g-max', '0', '--eta-max', '1', *args],
                          capture_output=True, text=True, timeout=300)


def check(condition, message):
    if not condition:
        print(f'FAIL: {message}')
        sys.exit(1)
    print(f'ok: {message}')


def main():
    generator = sys.argv[1]
    with tempfile.TemporaryDirectory() as state:
        base05 = os.path.join(state, 'node_g0_eta0_base2.bin')
        write_v6(base05, 2048, 1)  # one chunk of 16 x 128 photons
        out = run(generator, state, '--photons', '32', '--chunk', '16', '--runs', '0.5')
        check(out.returncode == 0, f'a version-6 base-0.5 file is topped up (rc {out.returncode}: {out.stderr.strip()})')
        length, photons, chunks, ms = read(base05)
        check(length == size(V7), f'it is written in version 7\'s size ({length} bytes)')
        check((photons, chunks) == (4096, 2), f'it continued from its photons: 2048 -> {photons}, {chunks} chunks')
        check(all(m >= MARK for m in ms[LOW:]) and all(m < MARK for m in ms[:LOW]),
              'its rows from 0.001 on are the old ones, moved up by six')

        base001 = os.path.join(state, 'node_g0_eta0_base0.bin')
        write_v6(base001, 8192, 1)  # a complete run of 16 x 512 photons under version 6
        out = run(generator, state, '--photons', '16', '--chunk', '16', '--runs', '0.01')
        check(out.returncode == 0, f'a version-6 base-0.01 file is traced again (rc {out.returncode})')
        length, photons, chunks, ms = read(base001)
        check(length == size(V7) and (photons, chunks) == (8192, 1) and all(m < MARK for m in ms),
              f'from its first chunk, every row new ({photons} photons, {chunks} chunk)')
        check(ms[0] > 0, f'the lowest new node has multiple scattering ({ms[0]:.4g})')

        with open(base05, 'r+b') as f:
            f.truncate(size(V6) - 8)
        out = run(generator, state, '--photons', '64', '--chunk', '16', '--runs', '0.5')
        lines = out.stderr.strip().splitlines()
        check(out.returncode == 2 and len(lines) == 1 and 'wrong size' in lines[0],
              f'a file of another size: one line, exit 2 ({out.returncode}: {out.stderr.strip()})')


if __name__ == '__main__':
    main()
