# Runs inside Blender (blender -b --factory-startup --python THIS -- ADDON.zip OUT.json FIT.json CHECK_EXPORT_DIR
# [--render WIDTH SAMPLES]): installs the add-on zip with Blender's own installer, enables it, applies three
# media through bpy.ops.bssrdf.apply_medium (a database material, typed coefficients, a fit result), reads
# every Principled BSDF back and recomputes what Cycles simulates from it (tests/blender/check_export.py's
# transcription of Cycles' kernel), and optionally renders a shadow edge on the first one.
import json
import os
import sys

import addon_utils
import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
ZIP, OUT, FIT, CHECK_EXPORT_DIR = argv[:4]
sys.path.insert(0, CHECK_EXPORT_DIR)
import check_export  # noqa: E402 -- Cycles' conversions and the shadow-edge scene

bpy.ops.preferences.addon_install(filepath=ZIP, overwrite=True)
bpy.ops.preferences.addon_enable(module="bssrdf_blender")
assert addon_utils.check("bssrdf_blender")[1], "the add-on did not enable"
import bssrdf_blender  # noqa: E402

result = {"blender_version": bpy.app.version_string, "backend": bssrdf_blender.backend.active(),
          "addon_file": bssrdf_blender.__file__, "panel": hasattr(bpy.types, "BSSRDF_PT_material"), "materials": []}

# The panel's own settings: the database enum lists the library's materials.
settings = bpy.context.scene.bssrdf
settings.material = "Skin1"
result["panel_material"] = settings.material

CASES = [
    ("skin", dict(source="DATABASE", material="Skin1", method="fixed-radius", unit="mm")),
    ("typed", dict(source="COEFFICIENTS", sigma_a=(0.01, 0.05, 0.2), sigma_s=(2.0, 3.0, 4.0), g=0.5, eta=1.4,
                   coefficient_unit="mm", method="radius-remap", unit="m")),
    ("fitted", dict(source="FIT", fit_file=FIT, fit_eta=1.3, method="fixed-radius", unit="cm")),
]
for name, kwargs in CASES:
    mat = bpy.data.materials.new(name)
    status = bpy.ops.bssrdf.apply_medium(target=name, **kwargs)
    assert status == {"FINISHED"}, (name, status)
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    result["materials"].append({
        "name": name, "request": {k: (list(v) if isinstance(v, tuple) else v) for k, v in kwargs.items()},
        "medium": mat["bssrdf_medium"], "backend": mat["bssrdf_backend"], "notes": mat["bssrdf_notes"],
        "inputs": {s.name: (list(s.default_value) if hasattr(s.default_value, "__len__") else s.default_value)
                   for s in bsdf.inputs if hasattr(s, "default_value")},
        "simulated": check_export.simulated_medium(bsdf)})

# A bad request is refused with the library's message, not a traceback.
try:
    bpy.ops.bssrdf.apply_medium(target="skin", source="DATABASE", material="NoSuchMaterial")
    result["bad_request"] = "accepted"
except RuntimeError as e:  # operators report {'ERROR'} as a RuntimeError in scripts
    result["bad_request"] = str(e)

if "--render" in argv:
    k = argv.index("--render")
    mat = bpy.data.materials["skin"]
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Specular IOR Level" if bpy.app.version[0] >= 4 else "Specular"].default_value = 0.0
    check_export.OUT = OUT
    result["render"] = check_export.render_edge(mat, float(argv[k + 1]), int(argv[k + 2]))

with open(OUT, "w") as f:
    json.dump(result, f, indent=1)
print("check_addon: wrote", OUT)
