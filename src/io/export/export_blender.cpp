// Blender Principled BSDF (Cycles, EEVEE) for the Random Walk subsurface method, as a Python
// script that creates the materials. Random Walk traces a volume with sigma_t = 1/radius and takes
// the single-scattering albedo from the base colour through a van de Hulst inversion, so:
//   Subsurface Radius x Subsurface Scale = the mean free path 1/sigma_t per channel (scene unit),
//   Base Color = the physical surface albedo (the physical model's total diffuse reflectance),
//   Subsurface IOR = eta (Blender clamps to 1.01-3.8), Subsurface Anisotropy = the mean g.
// The albedo Cycles then derives is written next to the medium's, so the difference is visible.
#include <algorithm>

#include "export_common.hpp"

namespace bssrdf::export_detail {

std::string export_blender(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  require_rgb(entries, "blender");
  const std::string u(symbol(unit));
  std::string out =
      "# Blender Principled BSDF materials exported by bssrdf " BSSRDF_VERSION "\n"
      "# Method: Random Walk (subsurface_method 'RANDOM_WALK'); the values are not meant for Christensen-Burley.\n"
      "# Units: Subsurface Radius x Subsurface Scale = mean free path 1/sigma_t (unreduced) per channel, in " + u + "\n"
      "#   (one Blender unit = 1 " + u + "; Blender's default scene unit is the metre: export with --unit m).\n"
      "# Base Color = surface albedo: total diffuse reflectance of the physical profile per entered flux.\n"
      "# Run in Blender: blender --python THIS_FILE (or paste into the Text Editor and Run Script).\n"
      "import bpy\n\n\n"
      "def make_material(name, base_color, radius, scale, ior, anisotropy):\n"
      "    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)\n"
      "    mat.use_nodes = True\n"
      "    bsdf = next(n for n in mat.node_tree.nodes if n.type == 'BSDF_PRINCIPLED')\n"
      "    bsdf.subsurface_method = 'RANDOM_WALK'\n"
      "    inputs = bsdf.inputs\n"
      "    inputs['Base Color'].default_value = (*base_color, 1.0)\n"
      "    inputs['Subsurface Radius'].default_value = radius\n"
      "    inputs['Subsurface IOR'].default_value = ior\n"
      "    inputs['Subsurface Anisotropy'].default_value = anisotropy\n"
      "    if 'Subsurface Weight' in inputs:  # Blender 4.x\n"
      "        inputs['Subsurface Weight'].default_value = 1.0\n"
      "        inputs['Subsurface Scale'].default_value = scale\n"
      "    else:  # Blender 2.9x-3.x: 'Subsurface' scales the radius\n"
      "        inputs['Subsurface'].default_value = scale\n"
      "        inputs['Subsurface Color'].default_value = (*base_color, 1.0)\n"
      "    return mat\n";
  for (const auto& e : entries) {
    const auto& m = e.material.medium;
    const auto one = single_g(m);
    std::vector<double> color, radius, cycles_alpha, alpha;
    double scale = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const auto& d = e.derived.channels[c];
      color.push_back(d.surface_albedo);
      radius.push_back(from_mm(d.mfp, unit));
      scale = std::max(scale, radius.back());
      cycles_alpha.push_back(random_walk_albedo(d.surface_albedo, one.g));
      alpha.push_back(d.albedo);
    }
    for (auto& r : radius) r /= scale;
    out += "\n\n# " + e.material.name + " (" + e.material.source + "): " + e.material.citation + "\n";
    out += "#   radius x scale = mfp 1/sigma_t [" + u + "]; Cycles' inversion of this base colour gives alpha = " +
           join(cycles_alpha, ", ") + " (the medium's alpha = sigma_s/sigma_t = " + join(alpha, ", ") + ")\n";
    if (!one.exact) out += "#   per-channel g (" + join(m.g, ", ") + ") replaced by their mean\n";
    out += "#   " + validity_summary(e.derived) + "\n";
    std::string name = e.material.name;
    for (std::size_t p; (p = name.find('"')) != std::string::npos;) name.erase(p, 1);
    out += "make_material(\"" + name + "\", base_color=(" + join(color, ", ") + "), radius=(" + join(radius, ", ") +
           "), scale=" + num(scale) + ", ior=" + num(std::clamp(m.eta, 1.01, 3.8)) + ", anisotropy=" + num(one.g) + ")\n";
  }
  return out;
}

}  // namespace bssrdf::export_detail
