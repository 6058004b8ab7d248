"""bssrdf for Blender: a "bssrdf" panel in the material properties that sets a Principled BSDF so that
Cycles simulates a measured medium (a database material, coefficients you type, or a fit result), and
the same as an operator for scripts:

    bpy.ops.bssrdf.apply_medium(source="DATABASE", material="Skin1", method="fixed-radius", unit="m")

The numbers come from the bssrdf library (backend.py: its Python module when Blender's Python can
import it, else the bssrdf executable), with the rule `bssrdf materials export --to blender` uses.
Where Cycles cannot follow the medium (albedo below 0.2, g above 0.9, the 256-event walk limit) the
notes are shown in the panel and reported by the operator.
"""
import bpy

from . import backend

bl_info = {
    "name": "bssrdf",
    "author": "the bssrdf project",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Material > bssrdf",
    "description": "Principled BSDF subsurface inputs from measured media (the bssrdf library)",
    "category": "Material",
}

METHODS = [("fixed-radius", "Random Walk (Fixed Radius)", "3.x Random Walk (Fixed Radius), 4.x Random Walk"),
           ("radius-remap", "Random Walk (radius remap)", "3.x Random Walk, 4.x Random Walk (Skin)"),
           ("burley", "Christensen-Burley", "a profile, not a medium")]
UNITS = [("m", "m", "one Blender unit is a metre (Blender's default)"), ("cm", "cm", ""), ("mm", "mm", ""),
         ("um", "µm", "")]
SOURCES = [("DATABASE", "Database", "a bundled or user database material"),
           ("COEFFICIENTS", "Coefficients", "sigma_a, sigma_s, g, eta per RGB channel"),
           ("FIT", "Fit result", "the JSON of `bssrdf fit ... -f json`")]

_material_items = []  # Blender keeps only pointers to enum strings: hold them here


def _preference():
    addon = bpy.context.preferences.addons.get(__name__)
    return addon.preferences.executable if addon else ""


def _materials(self, context):
    global _material_items
    try:
        names = backend.material_names(self.db, _preference())
    except backend.BackendError as e:
        names, _material_items = [], [("", "(%s)" % e, "")]
        return _material_items
    _material_items = [(n, n, "") for n in names]
    return _material_items


class BssrdfPreferences(bpy.types.AddonPreferences):
    bl_idname = __name__
    executable: bpy.props.StringProperty(name="bssrdf executable", subtype="FILE_PATH",
                                         description="Used when Blender's Python cannot import the bssrdf module")

    def draw(self, context):
        self.layout.prop(self, "executable")
        self.layout.label(text="Backend now: " + (backend.active(self.executable) or "none found"))


class BssrdfSettings(bpy.types.PropertyGroup):
    source: bpy.props.EnumProperty(name="Source", items=SOURCES, default="DATABASE")
    db: bpy.props.StringProperty(name="User database", subtype="FILE_PATH",
                                 description="Your own materials directory or file, added to the bundled one")
    material: bpy.props.EnumProperty(name="Material", items=_materials)
    sigma_a: bpy.props.FloatVectorProperty(name="sigma_a", size=3, min=0, default=(0.032, 0.17, 0.48), precision=4)
    sigma_s: bpy.props.FloatVectorProperty(name="sigma_s", size=3, min=0, default=(0.74, 0.88, 1.01), precision=4)
    g: bpy.props.FloatProperty(name="g", min=-0.99, max=0.99, default=0.0)
    eta: bpy.props.FloatProperty(name="eta", min=1.0, max=3.0, default=1.3)
    coefficient_unit: bpy.props.EnumProperty(name="Coefficients in 1/", items=UNITS, default="mm")
    fit_file: bpy.props.StringProperty(name="Fit result", subtype="FILE_PATH")
    fit_eta: bpy.props.FloatProperty(name="eta (0: the fit's)", min=0.0, max=3.0, default=0.0,
                                     description="The relative index to record when the fit neither fitted nor "
                                                 "recorded one (albedo fits)")
    method: bpy.props.EnumProperty(name="Cycles method", items=METHODS, default="fixed-radius")
    unit: bpy.props.EnumProperty(name="Scene unit", items=UNITS, default="m")


def apply_inputs(mat, inputs):
    """Set the Principled BSDF as the exported script's make_material does (io/export/export_blender.cpp)."""
    major = bpy.app.version[0]
    if major not in inputs["methods"]:
        raise backend.BackendError("Blender %s: the library knows the methods of %s" %
                                   (bpy.app.version_string, sorted(inputs["methods"])))
    mat.use_nodes = True
    bsdf = next((n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        bsdf = mat.node_tree.nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.subsurface_method = inputs["methods"][major]
    sockets = bsdf.inputs
    color, radius, ior = inputs["albedo_color"], inputs["radius"], inputs["ior"]
    sockets["Base Color"].default_value = (*color, 1.0)
    sockets["Subsurface Radius"].default_value = radius
    sockets["Subsurface IOR"].default_value = ior
    sockets["Subsurface Anisotropy"].default_value = inputs["anisotropy"]
    if major >= 4:
        sockets["Subsurface Weight"].default_value = 1.0
        sockets["Subsurface Scale"].default_value = 1.0
        sockets["IOR"].default_value = ior
    else:
        sockets["Subsurface"].default_value = 1.0
        sockets["Subsurface Color"].default_value = (*color, 1.0)
        sockets["Specular"].default_value = min(((ior - 1) / (ior + 1)) ** 2 / 0.08, 1.0)
    mat["bssrdf_medium"] = inputs["name"]
    mat["bssrdf_backend"] = inputs["backend"]
    mat["bssrdf_notes"] = "\n".join(inputs["notes"])
    return bsdf


class BSSRDF_OT_apply_medium(bpy.types.Operator):
    """Set the material's Principled BSDF so that Cycles simulates the medium"""
    bl_idname = "bssrdf.apply_medium"
    bl_label = "Apply"
    bl_options = {"REGISTER", "UNDO"}

    source: bpy.props.EnumProperty(name="Source", items=SOURCES, default="DATABASE")
    material: bpy.props.StringProperty(name="Material", description="database material (source DATABASE)")
    db: bpy.props.StringProperty(name="User database")
    sigma_a: bpy.props.FloatVectorProperty(size=3, min=0, default=(0.032, 0.17, 0.48))
    sigma_s: bpy.props.FloatVectorProperty(size=3, min=0, default=(0.74, 0.88, 1.01))
    g: bpy.props.FloatProperty(default=0.0)
    eta: bpy.props.FloatProperty(default=1.3)
    coefficient_unit: bpy.props.EnumProperty(items=UNITS, default="mm")
    fit_file: bpy.props.StringProperty()
    fit_eta: bpy.props.FloatProperty(default=0.0, description="0: the fit's own eta")
    method: bpy.props.EnumProperty(items=METHODS, default="fixed-radius")
    unit: bpy.props.EnumProperty(items=UNITS, default="m")
    target: bpy.props.StringProperty(name="Blender material", description="default: the active object's material")

    def execute(self, context):
        mat = bpy.data.materials.get(self.target) if self.target else getattr(context, "material", None)
        if mat is None:
            self.report({"ERROR"}, "no material: give target= or select an object with a material")
            return {"CANCELLED"}
        if self.source == "DATABASE":
            source = {"kind": "database", "name": self.material, "db": bpy.path.abspath(self.db) if self.db else ""}
        elif self.source == "COEFFICIENTS":
            source = {"kind": "coefficients", "sigma_a": tuple(self.sigma_a), "sigma_s": tuple(self.sigma_s),
                      "g": self.g, "eta": self.eta, "unit": self.coefficient_unit, "name": mat.name}
        else:
            source = {"kind": "fit", "file": bpy.path.abspath(self.fit_file), "name": mat.name,
                      "eta": self.fit_eta if self.fit_eta > 0 else None}
        try:
            inputs = backend.cycles_inputs(source, self.method, self.unit, _preference())
            apply_inputs(mat, inputs)
        except backend.BackendError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        for note in inputs["notes"]:
            self.report({"WARNING"}, note)
        self.report({"INFO"}, "%s: %s applied (%s)" % (mat.name, inputs["name"], inputs["backend"]))
        return {"FINISHED"}


class BSSRDF_PT_material(bpy.types.Panel):
    bl_label = "bssrdf"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "material"

    @classmethod
    def poll(cls, context):
        return getattr(context, "material", None) is not None

    def draw(self, context):
        s = context.scene.bssrdf
        layout = self.layout
        layout.prop(s, "source", expand=True)
        if s.source == "DATABASE":
            layout.prop(s, "db")
            layout.prop(s, "material")
        elif s.source == "COEFFICIENTS":
            for name in ("sigma_a", "sigma_s", "g", "eta", "coefficient_unit"):
                layout.prop(s, name)
        else:
            layout.prop(s, "fit_file")
            layout.prop(s, "fit_eta")
        layout.prop(s, "method")
        layout.prop(s, "unit")
        op = layout.operator(BSSRDF_OT_apply_medium.bl_idname)
        for name in ("source", "material", "db", "sigma_a", "sigma_s", "g", "eta", "coefficient_unit", "fit_file",
                     "fit_eta", "method", "unit"):
            setattr(op, name, getattr(s, name))
        op.target = context.material.name
        notes = context.material.get("bssrdf_notes", "")
        if notes:
            box = layout.box()
            box.label(text="Where Cycles cannot follow the medium:", icon="ERROR")
            for note in notes.split("\n"):
                box.label(text=note)
        layout.label(text="Backend: " + (backend.active(_preference()) or "none found"))


CLASSES = (BssrdfPreferences, BssrdfSettings, BSSRDF_OT_apply_medium, BSSRDF_PT_material)


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.bssrdf = bpy.props.PointerProperty(type=BssrdfSettings)


def unregister():
    del bpy.types.Scene.bssrdf
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
