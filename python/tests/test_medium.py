"""bssrdf.Medium, bssrdf.materials and the ValueErrors of bad input."""
import math

import numpy as np
import pytest

import bssrdf


def test_version_is_the_cli_version(cli):
    assert cli("--version").stdout.strip() == "bssrdf " + bssrdf.__version__


def test_medium_units_convert_at_the_edge():
    cm = bssrdf.Medium(sigma_a=[0.1, 0.2, 0.3], sigma_s=[10, 20, 30], g=0.5, eta=1.4, unit="cm")
    mm = cm.to_unit("mm")
    np.testing.assert_allclose(mm.sigma_a, [0.01, 0.02, 0.03], rtol=1e-15)
    np.testing.assert_allclose(cm.sigma_a, [0.1, 0.2, 0.3], rtol=1e-15)
    np.testing.assert_allclose(cm.sigma_s_prime, [5, 10, 15], rtol=1e-15)
    assert cm.g.tolist() == [0.5, 0.5, 0.5] and cm.eta == 1.4 and cm.channels == ["R", "G", "B"]
    assert cm.unit == "cm" and len(cm) == 3


def test_from_sigma_s_prime_keeps_the_reduced_scattering():
    m = bssrdf.Medium.from_sigma_s_prime(sigma_a=0.01, sigma_s_prime=2.0, g=0.8)
    assert m.sigma_s[0] == pytest.approx(10.0, rel=1e-15)
    assert m.sigma_s_prime[0] == pytest.approx(2.0, rel=1e-15)
    assert m.albedo_prime[0] == pytest.approx(2.0 / 2.01, rel=1e-15)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(sigma_a=[-1, 0, 0], sigma_s=1), "sigma_a[R] = -1"),
        (dict(sigma_a=0.1, sigma_s=1, g=1.0), "g[c0] = 1"),
        (dict(sigma_a=0.1, sigma_s=1, eta=9), "eta = 9"),
        (dict(sigma_a=[0.1, 0.2], sigma_s=[1, 2, 3]), "sigma_s: 3 values given"),
        (dict(sigma_a=0.1, sigma_s=1, unit="furlong"), "unit"),
        (dict(sigma_a="abc", sigma_s=1), "sigma_a"),
        (dict(sigma_a=[[1, 2]], sigma_s=1), "sigma_a"),
        (dict(sigma_a=math.nan, sigma_s=1), "sigma_a"),
        (dict(sigma_a=[], sigma_s=[]), "sigma_a: give at least one channel"),
    ],
)
def test_bad_media_raise_value_error_naming_the_field(kwargs, message):
    with pytest.raises(ValueError, match=None) as error:
        bssrdf.Medium(**kwargs)
    assert message in str(error.value)
    assert "\n" not in str(error.value)


# What tools/fuzz_python.py found: messages over several lines (numpy's repr of a 2-D array, a newline in a
# material's name) and a RuntimeError from a cast pybind11 could not make.
@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: bssrdf.validity(np.array([[1.0, 2.0], [3.0, 4.0]])), "medium = array([[1., 2.], [3., 4.]])"),
        (lambda: bssrdf.materials.get("Skin\n1"), "Skin\\x0a1"),
        (lambda: bssrdf.lut("Skin1", kind="separable", range=[[1.0]]), "range = [[1.0]]"),
        (lambda: bssrdf.lut("Skin1", kind="separable", range=np.zeros(3)), "range = array([0., 0., 0.])"),
    ],
)
def test_hostile_arguments_give_one_line_value_errors(call, field):
    with pytest.raises(ValueError) as error:
        call()
    assert field in str(error.value) and "\n" not in str(error.value)


def test_lut_range_takes_a_number_or_the_cli_word(cli):
    assert bssrdf.lut("Skin1", kind="separable", range=np.float32(2.5)).attributes["bssrdf:range"] == \
        bssrdf.lut("Skin1", kind="separable", range="2.5").attributes["bssrdf:range"]


def test_the_cli_refuses_the_same_medium_with_the_same_message(cli):
    with pytest.raises(ValueError) as error:
        bssrdf.Medium(sigma_a=[0.1, -1, 0.1], sigma_s=[1, 1, 1])
    done = cli("profile", "--sigma-a", "0.1,-1,0.1", "--sigma-s", "1,1,1", check=False)
    assert done.returncode == 2
    # The CLI names its option (--sigma-a), the module its argument (sigma_a); the rest is the library's.
    assert done.stderr.strip() == "bssrdf: error: " + str(error.value).replace("sigma_a", "--sigma-a", 1)


def test_materials_database():
    names = bssrdf.materials.list()
    assert "Skin1" in names and len(names) == len(set(names)) > 10
    skin = bssrdf.materials.get("skin1")  # case-insensitive
    assert skin.name == "Skin1" and skin.source == "jensen2001"
    assert skin.medium.material.name == "Skin1"
    assert all(m.source == "jensen2001" for m in bssrdf.materials.all(source="jensen2001"))
    with pytest.raises(ValueError, match="Skin1"):
        bssrdf.materials.get("Skin")  # the message lists close names


def test_materials_list_matches_the_cli(cli):
    listed = cli.json("materials", "list", "-f", "json")
    assert [m["name"] for m in listed] == bssrdf.materials.list()
    assert [m["eta"] for m in listed] == [m.eta for m in bssrdf.materials.all()]


@pytest.mark.parametrize("target", ["blender", "pbrt-v4", "mitsuba3", "json", "unreal"])
def test_export_is_the_cli_export(cli, target):
    text = bssrdf.materials.export("Skin1", to=target)
    assert text == cli("materials", "export", "Skin1", "--to", target).stdout


def test_export_of_a_whole_source_and_of_a_medium(cli, tmp_path):
    marble = bssrdf.materials.all(source="jensen2001")
    text = bssrdf.materials.export(marble, to="blender", blender_version=3, blender_method="radius-remap", unit="cm")
    assert text == cli("materials", "export", "--all", "--source", "jensen2001", "--to", "blender", "--blender-version",
                       "3", "--blender-method", "radius-remap", "--unit", "cm").stdout
    out = tmp_path / "m.py"
    medium = bssrdf.Medium(sigma_a=[0.01, 0.02, 0.03], sigma_s=[1, 2, 3], eta=1.3)
    assert bssrdf.materials.export(medium, to="pbrt-v4", output=str(out)) == out.read_text()
    with pytest.raises(ValueError, match="to"):
        bssrdf.materials.export("Skin1", to="povray")


def test_derive_matches_materials_show(cli):
    shown = cli.json("materials", "show", "Marble", "-f", "json")
    derived = bssrdf.derive("Marble")
    channels = shown["channels"] if "channels" in shown else shown["derived"]["channels"]
    for c, d in zip(channels, derived):
        assert c["name"] == d.name
        for key in ("transport_mfp", "surface_albedo", "burley_d"):
            if key in c:
                value = c[key]["value"] if isinstance(c[key], dict) else c[key]
                assert value == pytest.approx(getattr(d, key), rel=1e-12), key


def test_cycles_inputs_are_what_the_blender_export_writes():
    inputs = bssrdf.cycles_inputs("Skin1", method="fixed-radius", unit="m")
    script = bssrdf.materials.export("Skin1", to="blender", unit="m")
    call = next(line for line in script.splitlines() if line.startswith("make_material("))
    assert "radius=(%r, %r, %r)" % tuple(inputs.radius) in call
    assert "albedo_color=(%r, %r, %r)" % tuple(inputs.albedo_color) in call
    assert inputs.blender_method(3) == "RANDOM_WALK_FIXED_RADIUS"
