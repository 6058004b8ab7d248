"""bssrdf.reference (Monte Carlo: progress, Ctrl-C) and bssrdf.slab (adding-doubling): the CLI's numbers."""
import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import bssrdf

SOURCE = os.environ.get("BSSRDF_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
LAYERS = os.path.join(SOURCE, "tests", "data", "two_layer_skin.json")


def strip_timing(doc):
    """Wall-clock figures differ between any two runs; everything else must not."""
    for key in ("seconds", "photons_per_second", "threads"):
        doc.pop(key, None)
    return doc


def test_reference_is_the_cli_run_to_the_last_bit(cli):
    ref = bssrdf.reference("Skin1", photons=20000, seed=7, threads=2, bins=40)
    out = cli.json("reference", "--material", "Skin1", "-n", "20000", "--seed", "7", "-j", "1", "--bins", "40",
                   "-f", "json")
    assert strip_timing(json.loads(ref.to_json())) == strip_timing(out)
    R, err = ref.diffuse_reflectance
    assert R.shape == (3,) and np.all(err > 0) and np.all(R > 0.1)
    assert ref.reflectance.shape == (3, 40) and ref.bin_radius.shape == (40,)


def test_reference_of_a_slab_and_of_a_layer_stack(cli):
    slab = bssrdf.reference(bssrdf.Medium(sigma_a=0.1, sigma_s=10, g=0.9, eta=1.4), photons=5000, thickness=0.5)
    T, T_err = slab.total_transmittance
    assert T[0] > 0 and T_err[0] > 0
    stack = bssrdf.reference(layers=LAYERS, photons=5000, seed=3)
    out = cli.json("reference", "--layers", LAYERS, "-n", "5000", "--seed", "3", "-f", "json")
    assert strip_timing(json.loads(stack.to_json())) == strip_timing(out)


def test_progress_callback_and_its_exception_stop_the_run():
    seen = []
    bssrdf.reference("Skin1", photons=40000, threads=2, progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1][1] == 3 * 40000 and all(d <= t for d, t in seen)

    class Enough(Exception):
        pass

    def stop(done, total):
        raise Enough()

    start = time.monotonic()
    with pytest.raises(Enough):
        bssrdf.reference("Skin1", photons=50_000_000, threads=2, progress=stop)
    assert time.monotonic() - start < 10  # 150M photons would take minutes


def test_ctrl_c_stops_the_run_cleanly():
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        bssrdf.reference("Skin1", photons=50_000_000, threads=2)
    assert time.monotonic() - start < 10
    # The interpreter and the library are still usable.
    assert bssrdf.reference("Skin1", photons=1000).diffuse_reflectance[0].shape == (3,)


def test_reference_bad_input():
    for kwargs in (dict(photons=0), dict(photons=-1), dict(threads=-1), dict(seed=-1), dict(bins=1),
                   dict(depth_bins=-2)):
        with pytest.raises(ValueError, match=list(kwargs)[0]):
            bssrdf.reference("Skin1", **kwargs)
    with pytest.raises(ValueError, match="thickness"):
        bssrdf.reference("Skin1", thickness=-1)
    with pytest.raises(ValueError, match="spacing"):
        bssrdf.reference("Skin1", spacing="cubic")


def test_slab_is_the_cli_slab(cli):
    s = bssrdf.slab(bssrdf.Medium(sigma_a=[0.1, 0.2], sigma_s=[10, 5], g=0.8, eta=1.4), thickness=0.3,
                    slides=(1.5, 1.0))
    out = cli.json("slab", "--sigma-a", "0.1,0.2", "--sigma-s", "10,5", "--g", "0.8", "--eta", "1.4", "--thickness",
                   "0.3", "--slides", "1.5,1", "-f", "json")
    for c, ch in enumerate(out["channels"]):
        for key in ("diffuse_reflectance", "specular_reflectance", "total_transmittance", "unscattered_transmittance",
                    "absorbed", "error_estimate"):
            assert getattr(s, key)[c] == ch[key], key
        assert s.points[c] == ch["quadrature_points"]
    # Energy: R_d + R_sp + T + A = 1.
    np.testing.assert_allclose(s.diffuse_reflectance + s.specular_reflectance + s.total_transmittance + s.absorbed, 1,
                               rtol=1e-12)


def test_slab_semi_infinite_agrees_with_the_monte_carlo_reference():
    medium = bssrdf.Medium(sigma_a=0.05, sigma_s=5, g=0.5, eta=1.3)
    exact = bssrdf.slab(medium).diffuse_reflectance[0]
    R, err = bssrdf.reference(medium, photons=200000).diffuse_reflectance
    assert abs(R[0] - exact) < 4 * err[0] + 1e-4


def test_slab_bad_input():
    with pytest.raises(ValueError, match="tolerance"):
        bssrdf.slab("Skin1", thickness=1, tolerance=1)
    with pytest.raises(ValueError, match="slides"):
        bssrdf.slab("Skin1", slides=(1.5, 1))  # semi-infinite
    with pytest.raises(ValueError, match="incidence"):
        bssrdf.slab("Skin1", thickness=1, incidence="oblique")
