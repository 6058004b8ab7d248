"""Fits, every lut kind and advise: the CLI's numbers, arrays and files."""
import json
import os

import numpy as np
import pytest

import bssrdf

SOURCE = os.environ.get("BSSRDF_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
RXT = os.path.join(SOURCE, "tests", "data", "iad_basic_B.rxt")


def without_seconds(text):
    doc = json.loads(text)
    doc.pop("seconds", None)
    return doc


def test_fit_profile_recovers_the_medium_and_matches_the_cli(cli, tmp_path):
    csv = tmp_path / "skin.csv"
    csv.write_text(bssrdf.profile("Skin1", model="dipole").to_csv())
    fit = bssrdf.fit.profile(str(csv), model="dipole")
    skin = bssrdf.materials.get("Skin1").medium
    np.testing.assert_allclose(fit["sigma_a"], skin.sigma_a, rtol=1e-4)
    np.testing.assert_allclose(fit["sigma_s_prime"], skin.sigma_s_prime, rtol=1e-4)
    assert fit.stderr("sigma_a").shape == (3,) and fit.converged
    assert without_seconds(fit.to_json()) == without_seconds(cli("fit", "profile", csv, "--model", "dipole",
                                                                 "-f", "json").stdout)
    assert "sigma_a" in fit.report()


def test_fit_albedo_and_slab_match_the_cli(cli):
    a = bssrdf.fit.albedo([0.8, 0.5, 0.3], [1.0, 0.5, 0.25], convention="transport-mfp", eta=1.4)
    out = cli("fit", "albedo", "--albedo", "0.8,0.5,0.3", "--distance", "1,0.5,0.25", "--convention", "transport-mfp",
              "--eta", "1.4", "-f", "json").stdout
    assert without_seconds(a.to_json()) == without_seconds(out)
    s = bssrdf.fit.slab([0.3, 0.2], [0.4, 0.3], thickness=1.0, eta=1.4)
    out = cli("fit", "slab", "--reflectance", "0.3,0.2", "--transmittance", "0.4,0.3", "--thickness", "1", "--eta",
              "1.4", "-f", "json").stdout
    assert without_seconds(s.to_json()) == without_seconds(out)
    # The fitted medium gives back the measurement through adding-doubling.
    medium = bssrdf.Medium.from_sigma_s_prime(s["sigma_a"], s["sigma_s_prime"], eta=1.4)
    t = bssrdf.slab(medium, thickness=1.0)
    np.testing.assert_allclose(t.diffuse_reflectance, [0.3, 0.2], atol=2e-3)
    np.testing.assert_allclose(t.total_transmittance, [0.4, 0.3], atol=2e-3)


def test_fit_rxt_matches_the_cli(cli):
    r = bssrdf.fit.rxt(RXT)
    out = json.loads(cli("fit", "slab", "--rxt", RXT, "-f", "json").stdout)
    got = json.loads(r.to_json())
    out.pop("seconds", None), got.pop("seconds", None)
    assert got == out
    assert r.mu_a.shape == r.wavelength.shape and all(r.converged)


def test_fit_gaussians_and_burley_of_a_medium(cli):
    g = bssrdf.fit.gaussians("Skin1", 4, model="dipole")
    out = cli("fit", "gaussians", "--material", "Skin1", "--model", "dipole", "-n", "4", "-f", "json").stdout
    assert without_seconds(g.to_json()) == without_seconds(out)
    b = bssrdf.fit.burley("Skin1")
    assert (b["burley_d"] > 0).all()


@pytest.mark.parametrize(
    "kind, kwargs, flags",
    [
        ("radial", {}, []),
        ("radial", dict(model="pbd", tolerance=0.01), ["--model", "pbd", "--tolerance", "0.01"]),
        ("albedo-radius", dict(layout="family", size="16x12"), ["--layout", "family", "--size", "16x12"]),
        ("transmission", dict(samples=8), ["--samples", "8"]),
        ("preintegrated", dict(size="16x8"), ["--size", "16x8"]),
        ("penumbra", dict(size="16x8"), ["--size", "16x8"]),
        ("separable", dict(taps=11), ["--taps", "11"]),
        ("gaussians", dict(count=3), ["--count", "3"]),
    ],
)
def test_every_lut_kind_is_the_cli_table(cli, tmp_path, kind, kwargs, flags):
    table = bssrdf.lut("Skin1", kind=kind, **kwargs)
    out = tmp_path / "t.json"
    cli("lut", "--material", "Skin1", "--kind", kind, *flags, "-q", "-o", out)
    assert table.to_json() == out.read_text()
    assert set(table.channels) and table.kind == kind
    first = table[table.channels[0]]
    assert first.size == table.width * table.height
    exr = tmp_path / "t.exr"
    table.write(str(exr))
    cli("lut", "--material", "Skin1", "--kind", kind, *flags, "-q", "-o", tmp_path / "c.exr")
    assert exr.read_bytes() == (tmp_path / "c.exr").read_bytes()
    assert set(bssrdf.lut_kinds) >= {kind}


def test_lut_reference_and_errors_name_keywords():
    t = bssrdf.lut("Skin1", kind="radial", reference=True, photons=20000)
    assert "R.stderr" in t.channels or any("stderr" in c for c in t.channels)
    with pytest.raises(ValueError) as error:
        bssrdf.lut("Skin1", kind="albedo-radius", layout="adaptive", table_tolerance=0)
    assert "table_tolerance" in str(error.value) and "--" not in str(error.value)
    with pytest.raises(ValueError, match="kind"):
        bssrdf.lut("Skin1", kind="cubic")
    for kwargs in (dict(photons=-1, reference=True), dict(threads=-1), dict(kind="separable", taps=-3),
                   dict(kind="penumbra", size="axb")):
        with pytest.raises(ValueError, match=[k for k in kwargs if k != "kind"][0]):
            bssrdf.lut("Skin1", **kwargs)


def test_advise_matches_the_cli(cli):
    a = bssrdf.advise("Skin1", pixel=0.5, reference="exact")
    out = json.loads(cli("advise", "--material", "Skin1", "--pixel", "0.5", "--reference", "exact", "-f",
                         "json").stdout)
    got = json.loads(a.to_json())
    for doc in (got, out):
        doc.pop("reference_seconds", None)
    assert got == out
    assert a.choice is None or a.choice.meets_tolerance
    with pytest.raises(ValueError, match="pixel"):
        bssrdf.advise("Skin1", pixel=-1)
    with pytest.raises(ValueError, match="photons"):
        bssrdf.advise("Skin1", pixel=0.1, photons=10)
