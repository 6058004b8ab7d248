"""bssrdf.profile, bssrdf.Model, the registry, validity and the model choice: the CLI's numbers."""
import numpy as np
import pytest

import bssrdf


def test_profile_is_the_cli_profile_to_the_last_bit(cli):
    p = bssrdf.profile("Skin1")
    assert p.to_json() == cli("profile", "--material", "Skin1", "-f", "json").stdout
    assert p.to_csv() == cli("profile", "--material", "Skin1", "-f", "csv").stdout
    assert str(p) == cli("profile", "--material", "Skin1").stdout
    assert p.model == "exact" and p.model_choice == ""
    assert np.asarray(p).shape == (3, 64) and p.values.shape == (3, 64) and p.radius.shape == (64,)


@pytest.mark.parametrize("model", ["better-dipole", "pbd", "quantized+ss", "burley-dmfp", "auto"])
def test_every_kind_of_model_request_matches(cli, model):
    r = [0.01, 0.1, 0.5, 1, 2, 5]
    p = bssrdf.profile(bssrdf.Medium(sigma_a=[0.01, 0.05, 0.2], sigma_s=[2, 3, 4], g=0.3, eta=1.4, unit="cm"),
                       r=r, model=model)
    out = cli("profile", "--sigma-a", "0.01,0.05,0.2", "--sigma-s", "2,3,4", "--g", "0.3", "--eta", "1.4", "--unit",
              "cm", "--radii", ",".join(map(str, r)), "--model", model, "-f", "json").stdout
    assert p.to_json() == out
    if model == "auto":
        assert p.model_choice.startswith("auto: " + p.model)


def test_model_R_is_profile_values_and_vectorised():
    skin = bssrdf.materials.get("Skin1").medium
    r = np.geomspace(1e-3, 20, 1000)
    for name in ["exact", "dipole", "pbd"]:
        model = bssrdf.Model(name)
        R = model.R(skin, r)
        assert R.shape == (3, 1000)
        np.testing.assert_array_equal(R, bssrdf.profile(skin, r=r, model=name).values)
        # A scalar radius gives a 3 x 1 array; the same values as in the vector call.
        assert model.R(skin, r[17]).tolist() == R[:, 17:18].tolist()
        np.testing.assert_allclose(model.total(skin), bssrdf.profile(skin, r=r, model=name).total(), rtol=0)


def test_units_scale_as_lengths_and_areas():
    cm = bssrdf.Medium(sigma_a=0.05, sigma_s=10, unit="cm")
    mm = cm.to_unit("mm")
    model = bssrdf.Model("better-dipole")
    R_cm = model.R(cm, [0.1, 1.0])
    R_mm = model.R(mm, [1.0, 10.0])
    np.testing.assert_allclose(R_cm, R_mm * 100, rtol=1e-14)  # 1/cm^2 = 100/mm^2... per area in the unit
    np.testing.assert_allclose(model.radius_for_fraction(cm, 0.5) * 10, model.radius_for_fraction(mm, 0.5), rtol=1e-12)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: bssrdf.profile("Skin1", model="no-such-model"), "no-such-model"),
        (lambda: bssrdf.profile("Skin1", r=[1, 0.5]), "radius"),
        (lambda: bssrdf.profile("Skin1", r=[-1]), "r = -1"),
        (lambda: bssrdf.profile("Skin1", accuracy=0.05), "accuracy: only with model auto"),
        (lambda: bssrdf.profile("Skin1", model="auto", accuracy=20), "accuracy = 20"),
        (lambda: bssrdf.profile("Skin1", samples=1), "samples = 1"),
        (lambda: bssrdf.profile("NoSuchMaterial"), "NoSuchMaterial"),
        (lambda: bssrdf.profile(42), "medium"),
        (lambda: bssrdf.Model("exact").R("Skin1", [np.nan]), "r[0] = nan"),
        (lambda: bssrdf.Model("exact").R("Skin1", [[1.0]]), "1-D"),
        (lambda: bssrdf.Model("nope"), "nope"),
        (lambda: bssrdf.profile("Skin1", model="dipole", surface_albedo=0.5), "burley"),
    ],
)
def test_bad_requests_raise_value_error(call, message):
    with pytest.raises(ValueError) as error:
        call()
    assert message in str(error.value)


def test_models_registry_matches_bssrdf_models(cli):
    listed = cli.json("models", "--json")
    models = bssrdf.models()
    assert [m["name"] for m in listed] == [m.name for m in models]
    for row, info in zip(listed, models):
        assert row["description"] == info.description
        assert row["validity_domain"] == info.domain
        assert row["includes_single_scattering"] == info.includes_single_scattering
        assert info.cost_ns > 0
    exact = next(m for m in models if m.name == "exact")
    assert exact.reference_accuracy["total"] > 0 and exact.bands is None or isinstance(exact.bands, dict)
    dipole = next(m for m in models if m.name == "dipole")
    assert dipole.bands["isotropic"][0][0] <= 1 and dipole.bands["isotropic"][0][1] >= 0
    assert len(bssrdf.models(all=True)) > len(models)


def test_model_errors_and_choice_match_the_cli(cli):
    doc = cli.json("models", "--material", "Skin1", "--accuracy", "0.05", "--json")
    errors = bssrdf.model_errors("Skin1")
    assert [m["name"] for m in doc["models"]] == [e.model for e in errors]
    for row, e in zip(doc["models"], errors):
        assert row["total_error"] == e.total_error and row["profile_l2_error"] == e.profile_error
    chosen = bssrdf.select_model("Skin1", "auto", accuracy=0.05)
    assert chosen.name == doc["chosen"]
    # The explanation is the library's one function, printed by the CLI too.
    assert chosen.note == cli.json("profile", "--material", "Skin1", "--model", "auto", "--accuracy", "0.05",
                                   "-f", "json")["model_choice"]


def test_validity_is_reported_not_hidden():
    thin = bssrdf.Medium(sigma_a=5, sigma_s=1)  # alpha' 1/6: diffusion does not hold
    notes = bssrdf.validity(thin, model="dipole")[0]
    assert any(n.severity == bssrdf.Severity.invalid for n in notes)
    assert all(str(n).startswith(("note", "warning", "invalid")) for n in notes)
    default = bssrdf.select_model(thin)
    assert default.name == "exact" or default.note.startswith("default: ")
