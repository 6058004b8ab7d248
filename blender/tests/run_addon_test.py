#!/usr/bin/env python3
"""The Blender add-on in real Blender (ctest: blender_addon.cli, blender_addon.module).

  run_addon_test.py --blender blender --zip build/bssrdf-blender-addon.zip --exe build/bssrdf \
      --backend cli|module [--pythonpath build/python] [--render]

Installs the zip with Blender's own installer (blender/tests/check_addon.py), applies three media, and checks
the Principled BSDF it set against the medium: sigma_t (1 - g) within 1 % and the reduced albedo within 5 %
(where Cycles does not raise alpha to 0.2), recomputed from the node values by check_export.py's transcription
of Cycles' kernel. --backend module also runs the CLI backend and requires the same node values, and with
--render compares a Cycles shadow edge's bleed with the library's prediction (within 3 sigma, as
tests/test_blender_export.cpp does). Exit 77 (skipped) without Blender or with BSSRDF_SKIP_BLENDER=1.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))


def run_blender(args, backend, tmp, fit, render):
    out = os.path.join(tmp, "addon-%s.json" % backend)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts-" + backend), BSSRDF_ADDON_BACKEND=backend,
               BSSRDF_EXE=os.path.abspath(args.exe))
    env.pop("PYTHONPATH", None)
    if backend == "module":
        env["PYTHONPATH"] = os.path.abspath(args.pythonpath)
    cmd = [args.blender, "-b", "--factory-startup", "--python", os.path.join(HERE, "check_addon.py"), "--",
           os.path.abspath(args.zip), out, fit, os.path.join(SOURCE, "tests", "blender")]
    if render:
        cmd += ["--render", "24", "128"]
    start = time.time()
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=900)
    seconds = time.time() - start
    if done.returncode != 0 or not os.path.exists(out):
        sys.exit("blender failed (exit %d):\n%s\n%s" % (done.returncode, done.stdout[-3000:], done.stderr[-3000:]))
    with open(out) as f:
        result = json.load(f)
    print("blender %s, backend %s: %.1f s (add-on at %s)" % (result["blender_version"], backend, seconds,
                                                               result["addon_file"]))
    return result


def cli_json(exe, *args):
    return json.loads(subprocess.run([exe, *args], capture_output=True, text=True, check=True).stdout)


def media(args, tmp, fit):
    """Each case's medium per channel in its scene unit: sigma_t (1/unit), albedo, g."""
    per = {"m": 1000.0, "cm": 10.0, "mm": 1.0}

    def from_show(doc, unit):
        return [(c["sigma_t"] * per[unit], c["albedo"], c["g"]) for c in doc["channels"]]

    imported = os.path.join(tmp, "fitted.json")
    subprocess.run([args.exe, "materials", "import", fit, "--name", "fitted", "--eta", "1.3", "-o", imported], check=True,
                   capture_output=True)
    typed = [(a + s) * per["m"] for a, s in zip((0.01, 0.05, 0.2), (2.0, 3.0, 4.0))]
    return {"skin": from_show(cli_json(args.exe, "materials", "show", "Skin1", "-f", "json"), "mm"),
            "typed": [(t, s / (a + s), 0.5) for t, a, s in zip(typed, (0.01, 0.05, 0.2), (2.0, 3.0, 4.0))],
            "fitted": from_show(cli_json(args.exe, "materials", "show", "fitted", "--db", imported, "-f", "json"),
                                "cm")}


def reduced_albedo(alpha, g):
    return alpha * (1 - g) / (1 - alpha * g)


def check_media(result, expected, backend):
    failures = []
    assert result["backend"] == backend, result["backend"]
    assert result["panel"] and result["panel_material"] == "Skin1"
    assert "NoSuchMaterial" in result["bad_request"], result["bad_request"]
    for m in result["materials"]:
        assert m["backend"] == backend, (m["name"], m["backend"])
        sim = m["simulated"]
        for c, (sigma_t, albedo, g) in enumerate(expected[m["name"]]):
            want, got = sigma_t * (1 - g), sim["sigma_t"][c] * (1 - sim["g"])
            line = "%s channel %d: sigma_t(1-g) %.6g, Cycles %.6g (%+.3f %%)" % (m["name"], c, want, got,
                                                                             100 * (got / want - 1))
            if abs(got / want - 1) > 0.01:
                failures.append(line)
            if not sim["alpha_raised"][c]:
                a_want, a_got = reduced_albedo(albedo, g), reduced_albedo(sim["alpha"][c], sim["g"])
                line += "; alpha' %.5f, Cycles %.5f (%+.3f %%)" % (a_want, a_got, 100 * (a_got / a_want - 1))
                if abs(a_got / a_want - 1) > 0.05:
                    failures.append(line)
            else:
                line += "; alpha raised to 0.2 by Cycles (noted: %s)" % bool(m["notes"])
            print(line)
        if m["notes"]:
            print("%s notes: %s" % (m["name"], m["notes"].replace("\n", " | ")))
    return failures


def check_bleed(result, pythonpath):
    """The shadow edge's bleed against the library's half-plane response (pbd, index-matched boundary)."""
    sys.path.insert(0, pythonpath)
    import bssrdf  # noqa: PLC0415

    render = result["render"]
    columns = render["columns"]
    skin = bssrdf.materials.get("Skin1").medium
    medium = bssrdf.Medium(sigma_a=skin.sigma_a, sigma_s=skin.sigma_s, g=skin.g, eta=1.0, unit=skin.unit)
    model = bssrdf.Model("pbd")
    total = model.total(medium)
    failures = []
    for c in range(3):
        predicted, measured, error = [], [], []
        for col in columns:
            x0, x1 = col["x0"], col["x1"]
            xs = [-(x0 + (k + 0.5) * (x1 - x0) / 32) for k in range(32)]
            predicted.append(sum(model.half_plane(medium, xs)[c]) / 32 / total[c])
            measured.append(col["channels"][c]["mean"])
            error.append(max(col["channels"][c]["stderr"], 1e-9))
        half = len(columns) // 2
        num = sum(measured[i] * predicted[i] / error[i] ** 2 for i in range(half, len(columns)))
        den = sum(predicted[i] ** 2 / error[i] ** 2 for i in range(half, len(columns)))
        K = num / den
        dx = render["width"] / len(columns)
        bleed = sum(measured[i] / K * dx for i in range(half))
        var = sum((error[i] / K * dx) ** 2 for i in range(half))
        want = sum(predicted[i] * dx for i in range(half))
        sigma = math.sqrt(var + bleed * bleed / (K * K * den))
        line = "Skin1 render channel %d: bleed %.4f +- %.4f mm, predicted %.4f mm (ratio %.3f); render %.1f s" % (
            c, bleed, sigma, want, bleed / want, render["seconds"])
        print(line)
        if abs(bleed - want) > 3 * sigma:
            failures.append(line)
    return failures


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--blender", default="blender")
    p.add_argument("--zip", required=True)
    p.add_argument("--exe", required=True)
    p.add_argument("--backend", choices=["cli", "module"], required=True)
    p.add_argument("--pythonpath", default="")
    p.add_argument("--render", action="store_true")
    args = p.parse_args()
    if os.environ.get("BSSRDF_SKIP_BLENDER", "0") == "1" or not shutil.which(args.blender):
        print("skipped: no Blender (or BSSRDF_SKIP_BLENDER=1)")
        sys.exit(77)
    with tempfile.TemporaryDirectory(prefix="bssrdf-addon-") as tmp:
        fit = os.path.join(tmp, "fit.json")
        subprocess.run([args.exe, "fit", "albedo", "--albedo", "0.8,0.6,0.4", "--distance", "1,0.8,0.5", "-f",
                        "json", "-o", fit], check=True, capture_output=True)
        expected = media(args, tmp, fit)
        result = run_blender(args, args.backend, tmp, fit, args.render)
        failures = check_media(result, expected, args.backend)
        if args.backend == "module":
            other = run_blender(args, "cli", tmp, fit, False)
            failures += check_media(other, expected, "cli")
            for a, b in zip(result["materials"], other["materials"]):
                if a["inputs"] != b["inputs"] or a["notes"] != b["notes"]:
                    failures.append("%s: the module and the CLI backends set different values" % a["name"])
            print("module and CLI backends: identical node values for %d materials" % len(result["materials"]))
            if args.render:
                failures += check_bleed(result, args.pythonpath)
    if failures:
        sys.exit("FAILED:\n" + "\n".join(failures))
    print("ok")


if __name__ == "__main__":
    main()
