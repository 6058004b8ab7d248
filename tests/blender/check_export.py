# Runs inside Blender (blender -b --factory-startup --python THIS -- EXPORT.py MATERIAL OUT.json
# [--render WIDTH SAMPLES]): executes a `bssrdf materials export --to blender` script, reads the
# Principled BSDF values back through Blender's Python API, recomputes from them the medium Cycles
# will simulate (sigma_t, single-scattering albedo, g per channel, transcribed from Cycles' kernel:
# closure/bssrdf.h bssrdf_setup_radius, integrator/subsurface_random_walk.h
# subsurface_random_walk_remap), and optionally renders a shadow edge on a thick slab of the
# material with Cycles on the CPU, reporting per-column means across the edge.
#
# Scene (one Blender unit = one export unit): the slab's top face is z = 0, 400 x 400 units wide
# and 200 deep; a sun shines straight down; a black plane at z = 1 hidden from the camera shadows
# x < 0; an orthographic camera looks straight down over x in [-W/2, W/2]. Specular is set to 0 so
# only the subsurface term is seen, and the pixel filter is a one-pixel box, so each pixel is the
# mean exitance over its footprint.
import json
import math
import struct
import sys
import time

import bpy


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


# ---- Cycles' conversions, transcribed from its kernel (float arithmetic approximated) -------
def dipole_rd(alpha_prime, fourthird_a):
    s = math.sqrt(3.0 * (1.0 - alpha_prime))
    return 0.5 * alpha_prime * (1.0 + math.exp(-fourthird_a * s)) * math.exp(-s)


def dipole_alpha_prime(rd, eta):
    inv = 1.0 / eta
    f_dr = inv * (-1.440 * inv + 0.710) + 0.668 + 0.0636 * eta
    fourthird_a = (4.0 / 3.0) * (1.0 + f_dr) / (1.0 - f_dr)
    if rd < 1e-4:
        return 0.0
    if rd >= 0.995:
        return 0.999999
    x0, x1 = 0.0, 1.0
    for _ in range(12):
        xmid = f32(0.5 * (x0 + x1))
        if dipole_rd(xmid, fourthird_a) < rd:
            x0 = xmid
        else:
            x1 = xmid
    return xmid


def random_walk_alpha(albedo, g):
    g2, g3, g4, g5, g6, g7 = g**2, g**3, g**4, g**5, g**6, g**7
    A = (1.8260523782 - 1.28451056436 * g - 1.79904629312 * g2 + 9.19393289202 * g3
         - 22.8215585862 * g4 + 32.0234874259 * g5 - 23.6264803333 * g6 + 7.21067002658 * g7)
    B = 4.98511194385 + 0.127355959438 * math.exp(
        31.1491581433 * g - 201.847017512 * g2 + 841.576016723 * g3 - 2018.09288505 * g4
        + 2731.71560286 * g5 - 1935.41424244 * g6 + 559.009054474 * g7)
    C = (1.09686102424 - 0.394704063468 * g + 1.05258115941 * g2 - 8.83963712726 * g3
         + 28.8643230661 * g4 - 46.8802913581 * g5 + 38.5402837518 * g6 - 12.7181042538 * g7)
    D = (0.496310210422 + 0.360146581622 * g - 2.15139309747 * g2 + 17.8896899217 * g3
         - 55.2984010333 * g4 + 82.065982243 * g5 - 58.5106008578 * g6 + 15.8478295021 * g7)
    E = 4.23190299701 + 0.00310603949088 * math.exp(
        76.7316253952 * g - 594.356773233 * g2 + 2448.8834203 * g3 - 5576.68528998 * g4
        + 7116.60171912 * g5 - 4763.54467887 * g6 + 1303.5318055 * g7)
    F = (2.40602999408 - 2.51814844609 * g + 9.18494908356 * g2 - 79.2191708682 * g3
         + 259.082868209 * g4 - 403.613804597 * g5 + 302.85712436 * g6 - 87.4370473567 * g7)
    blend = albedo ** 0.25
    alpha = (1 - blend) * A * math.atan(B * albedo) ** C + blend * D * math.atan(E * albedo) ** F
    return min(max(alpha, 0.0), 0.999999)


def burley_scaling(A):
    return 1.9 - A + 3.5 * (A - 0.8) ** 2


def simulated_medium(bsdf):
    """What Cycles simulates for this Principled BSDF (3.x or 4.x inputs)."""
    inputs = bsdf.inputs
    method = bsdf.subsurface_method
    v4 = bpy.app.version[0] >= 4
    base = list(inputs["Base Color"].default_value)[:3]
    radius = list(inputs["Subsurface Radius"].default_value)
    if v4:
        weight = inputs["Subsurface Weight"].default_value
        albedo = [min(max(c, 0.0), 1.0) for c in base]
        radius = [r * inputs["Subsurface Scale"].default_value for r in radius]
        remap = method == "RANDOM_WALK_SKIN"
        ior = inputs["Subsurface IOR"].default_value if remap else inputs["IOR"].default_value
    else:
        weight = inputs["Subsurface"].default_value
        color = list(inputs["Subsurface Color"].default_value)[:3]
        albedo = [c * weight + b * (1 - weight) for c, b in zip(color, base)]
        radius = [r * weight for r in radius]
        remap = method == "RANDOM_WALK"
        ior = inputs["Subsurface IOR"].default_value
    ior = min(max(ior, 1.01), 3.8)
    g = min(max(inputs["Subsurface Anisotropy"].default_value, 0.0), 0.9)
    out = {"method": method, "subsurface_weight": weight, "albedo_color": albedo, "closure_radius": radius,
           "ior": ior, "g": g, "sigma_t": [], "alpha": [], "alpha_raised": [], "burley_d": [], "burley_A": []}
    for A, r in zip(albedo, radius):
        if method == "BURLEY":
            out["burley_d"].append(r / (4 * math.pi) / burley_scaling(A))
            out["burley_A"].append(A)
            continue
        if remap:
            r_eff = r * math.sqrt(3.0 * (1.0 - dipole_alpha_prime(A, ior)))
        else:
            r_eff = r / (4 * math.pi)
        alpha = random_walk_alpha(A, g)
        out["sigma_t"].append(1.0 / max(r_eff, 1e-16) / (1.0 - g))
        out["alpha_raised"].append(alpha < 0.2)
        out["alpha"].append(max(alpha, 0.2))  # Cycles raises it and scales the throughput instead
    return out


# ---- the shadow-edge render -----------------------------------------------------------------
def render_edge(mat, width, samples, pixels=64):
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    bpy.ops.mesh.primitive_cube_add(size=1, location=(0, 0, -100))
    slab = bpy.context.active_object
    slab.scale = (400, 400, 200)
    slab.data.materials.append(mat)
    bpy.ops.mesh.primitive_plane_add(size=1, location=(-200, 0, 1))
    occluder = bpy.context.active_object
    occluder.scale = (400, 400, 1)
    occluder.visible_camera = False
    black = bpy.data.materials.new("occluder")
    black.use_nodes = True
    black_inputs = black.node_tree.nodes["Principled BSDF"].inputs
    black_inputs["Base Color"].default_value = (0, 0, 0, 1)
    black_inputs["Specular IOR Level" if bpy.app.version[0] >= 4 else "Specular"].default_value = 0.0
    occluder.data.materials.append(black)
    bpy.ops.object.light_add(type="SUN", location=(0, 0, 50))
    sun = bpy.context.active_object
    sun.data.angle = 0.0
    sun.data.energy = 1.0
    bpy.ops.object.camera_add(location=(0, 0, 0.5), rotation=(0, 0, 0))
    cam = bpy.context.active_object
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = width
    cam.data.clip_start = 0.01
    scene.camera = cam
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.seed = 1
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2
    scene.render.resolution_x = pixels
    scene.render.resolution_y = pixels
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.view_settings.view_transform = "Standard"
    scene.render.filepath = OUT + ".exr"
    start = time.time()
    bpy.ops.render.render(write_still=True)
    seconds = time.time() - start
    img = bpy.data.images.load(OUT + ".exr")
    px = list(img.pixels)
    w, h = img.size
    columns = []
    for i in range(w):
        chans = []
        for c in range(3):
            vals = [px[4 * (j * w + i) + c] for j in range(h)]
            m = sum(vals) / h
            var = sum((v - m) ** 2 for v in vals) / (h - 1)
            chans.append({"mean": m, "stderr": math.sqrt(var / h)})
        columns.append({"x0": -width / 2 + i * width / w, "x1": -width / 2 + (i + 1) * width / w, "channels": chans})
    return {"width": width, "pixels": pixels, "samples": samples, "seconds": seconds, "columns": columns}


if __name__ == "__main__":  # imported by blender/tests/check_addon.py for its functions
    argv = sys.argv[sys.argv.index("--") + 1:]
    EXPORT, NAME, OUT = argv[0], argv[1], argv[2]
    exec(compile(open(EXPORT).read(), EXPORT, "exec"))
    mat = bpy.data.materials[NAME]
    bsdf = next(n for n in mat.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    result = {"blender_version": bpy.app.version_string, "material": NAME,
              "inputs": {s.name: (list(s.default_value) if hasattr(s.default_value, "__len__") else s.default_value)
                         for s in bsdf.inputs if hasattr(s, "default_value")},
              "medium": simulated_medium(bsdf)}
    if "--render" in argv:
        k = argv.index("--render")
        if bpy.app.version[0] >= 4:
            bsdf.inputs["Specular IOR Level"].default_value = 0.0
        else:
            bsdf.inputs["Specular"].default_value = 0.0
        result["render"] = render_edge(mat, float(argv[k + 1]), int(argv[k + 2]))
    with open(OUT, "w") as f:
        json.dump(result, f, indent=1)
    print("check_export: wrote", OUT)
