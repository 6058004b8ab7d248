"""Where the add-on gets its numbers: the `bssrdf` Python module when Blender's Python can import it,
else the `bssrdf` executable. Both give the Principled BSDF inputs that make Cycles simulate a medium
(the rule `bssrdf materials export --to blender` writes and tests/test_blender_export.cpp verifies in
Cycles); this file holds no physics, only the two ways of asking the library.

BSSRDF_ADDON_BACKEND=module|cli forces one (the tests run both); BSSRDF_EXE names the executable.
"""
import ast
import json
import os
import shutil
import subprocess
import tempfile


class BackendError(Exception):
    """The library refused the input (its one-line message), or no backend is available."""


def _module():
    if os.environ.get("BSSRDF_ADDON_BACKEND", "") == "cli":
        return None
    try:
        import bssrdf  # noqa: PLC0415 -- optional: Blender's Python may not have it
    except ImportError:
        if os.environ.get("BSSRDF_ADDON_BACKEND", "") == "module":
            raise BackendError("BSSRDF_ADDON_BACKEND=module, but Blender's Python cannot import bssrdf")
        return None
    return bssrdf


def executable(preference=""):
    """The bssrdf executable: the add-on preference, $BSSRDF_EXE, or `bssrdf` on PATH."""
    for candidate in (preference, os.environ.get("BSSRDF_EXE", ""), shutil.which("bssrdf") or ""):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return ""


def active(preference=""):
    """'module', 'cli', or '' when neither is available."""
    if _module() is not None:
        return "module"
    return "cli" if executable(preference) else ""


def _run(exe, *args):
    done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        message = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "exit %d" % done.returncode
        raise BackendError(message.replace("bssrdf: error: ", ""))
    return done.stdout


def material_names(db="", preference=""):
    """Names of the bundled database plus the user's (db: a directory or file)."""
    module = _module()
    if module is not None:
        try:
            return module.materials.list(db=db)
        except ValueError as e:
            raise BackendError(str(e)) from None
    exe = executable(preference)
    if not exe:
        raise BackendError("neither the bssrdf Python module nor the bssrdf executable is available")
    args = ["materials", "list", "-f", "json"] + (["--db", db] if db else [])
    return [m["name"] for m in json.loads(_run(exe, *args))]


def _materials_file(name, sigma_a, sigma_s, g, eta, unit):
    """A one-entry materials file (materials/README.md) for coefficients typed into the panel."""
    return {"format": "bssrdf-materials", "version": 1, "source": "blender", "citation": "entered in Blender",
            "unit": unit, "channels": ["R", "G", "B"],
            "materials": [{"name": name, "eta": eta, "sigma_a": list(sigma_a), "sigma_s": list(sigma_s),
                           "g": [g, g, g]}]}


def _parse_export(script, name):
    """The make_material(...) call for `name` in an exported script, its NOTE lines and the method table."""
    tree = ast.parse(script)
    methods = None
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "METHODS":
            methods = ast.literal_eval(node.value)
        if (isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)
                and getattr(node.value.func, "id", "") == "make_material"
                and ast.literal_eval(node.value.args[0]) == name):
            kwargs = {k.arg: ast.literal_eval(k.value) for k in node.value.keywords}
    lines = script.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("# %s (" % name))
    notes = []
    for line in lines[start + 1:]:
        if not line.startswith("#   "):
            break
        if line.startswith("#   NOTE "):
            notes.append(line[len("#   NOTE "):])
    return {"albedo_color": list(kwargs["albedo_color"]), "radius": list(kwargs["radius"]), "ior": kwargs["ior"],
            "anisotropy": kwargs["anisotropy"], "notes": notes, "methods": methods}


def cycles_inputs(source, method="fixed-radius", unit="m", preference=""):
    """The Principled BSDF inputs for a medium.

    source: {"kind": "database", "name": ..., "db": ...} | {"kind": "coefficients", "sigma_a": (3),
    "sigma_s": (3), "g": .., "eta": .., "unit": ..} | {"kind": "fit", "file": .., "eta": None|float}.
    Returns {"albedo_color", "radius", "ior", "anisotropy", "notes", "methods" {3: id, 4: id}, "name",
    "backend"}.
    """
    module = _module()
    kind = source["kind"]
    if module is not None:
        try:
            if kind == "database":
                medium = module.materials.get(source["name"], db=source.get("db", ""))
                name = medium.name
            elif kind == "coefficients":
                medium = module.Medium(sigma_a=source["sigma_a"], sigma_s=source["sigma_s"], g=source["g"],
                                       eta=source["eta"], unit=source["unit"])
                name = source.get("name", "medium")
            else:
                medium = module.materials.from_fit(source["file"], source.get("name", "fit"), eta=source.get("eta"))
                name = medium.name
            c = module.cycles_inputs(medium, method=method, unit=unit)
        except ValueError as e:
            raise BackendError(str(e)) from None
        return {"albedo_color": list(c.albedo_color), "radius": list(c.radius), "ior": c.eta, "anisotropy": c.g,
                "notes": list(c.notes), "methods": {3: c.blender_method(3), 4: c.blender_method(4)}, "name": name,
                "backend": "module"}
    exe = executable(preference)
    if not exe:
        raise BackendError("neither the bssrdf Python module nor the bssrdf executable is available")
    with tempfile.TemporaryDirectory(prefix="bssrdf-blender-") as tmp:
        db = source.get("db", "")
        if kind == "coefficients":
            name = source.get("name", "medium")
            db = os.path.join(tmp, "entered.json")
            with open(db, "w") as f:
                json.dump(_materials_file(name, source["sigma_a"], source["sigma_s"], source["g"], source["eta"],
                                          source["unit"]), f)
        elif kind == "fit":
            name = source.get("name", "fit")
            db = os.path.join(tmp, "fit.json")
            args = ["materials", "import", source["file"], "--name", name, "-o", db]
            if source.get("eta") is not None:
                args += ["--eta", repr(float(source["eta"]))]
            _run(exe, *args)
        else:
            name = source["name"]
        args = ["materials", "export", name, "--to", "blender", "--blender-method", method, "--unit", unit]
        if db:
            args += ["--db", db]
        script = _run(exe, *args)
    # The database's own spelling of the name (lookups are case-insensitive).
    header = next(line for line in script.splitlines() if line.startswith("make_material("))
    name = ast.literal_eval(ast.parse(header).body[0].value.args[0])
    out = _parse_export(script, name)
    out.update(name=name, backend="cli")
    return out
