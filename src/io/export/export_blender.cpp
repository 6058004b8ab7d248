// Blender Principled BSDF materials as a Python script, with the inputs chosen so that the medium
// Cycles simulates is ours (cycles_subsurface.hpp has Cycles' conversions): per channel the same
// extinction sigma_t and single-scattering albedo alpha, one g, in the scene unit.
//
// Default method: a random walk with a fixed radius (3.x "Random Walk (Fixed Radius)", 4.x "Random
// Walk"). Every random-walk method traces the same volume once sigma_t, alpha and g are set, so
// the choice is about how faithfully the inputs pin them down: the fixed radius is linear in the
// mean free path (R = 4 pi / (sigma_t (1 - g))), while the radius remap divides by
// sqrt(3 (1 - alpha')) with alpha' from a 12-step bisection of the colour, a staircase in which
// a rounding of the colour moves a bright medium's radius by percents. In 4.x the fixed-radius
// walk also refracts into the surface through the IOR (a dielectric boundary), where "Skin"
// enters half of its paths diffusely. Christensen-Burley draws Burley's profile, not a medium:
// it gets d and A fitted to the physical profile.
#include <cmath>

#include "export_common.hpp"

namespace bssrdf::export_detail {
namespace {

std::string py_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out + "\"";
}

std::string tuple(const std::vector<double>& values) {
  std::string out = "(";
  out += join(values, ", ");
  return out += ")";
}

}  // namespace

std::string export_blender(const std::vector<ExportEntry>& entries, LengthUnit unit, const ExportOptions& options) {
  require_rgb(entries, "blender");
  if (options.blender_version != 0 && options.blender_version != 3 && options.blender_version != 4)
    throw InvalidInput("blender_version", std::to_string(options.blender_version), "3 or 4 (or auto)");
  const auto mapping = options.blender_method;
  const std::string u(symbol(unit));
  std::string methods;
  for (int major : {3, 4})
    if (options.blender_version == 0 || options.blender_version == major)
      methods += std::string(methods.empty() ? "" : ", ") + std::to_string(major) + ": '" +
                 std::string(blender_method_identifier(mapping, major)) + "'";
  const std::string radius_rule =
      mapping == CyclesMapping::fixed_radius ? "R / (4 pi) = 1 / (sigma_t (1 - g))"
      : mapping == CyclesMapping::radius_remap
          ? "R sqrt(3 (1 - alpha'(C, IOR))) = 1 / (sigma_t (1 - g)), alpha' Cycles' 12-step dipole inversion of C"
          : "R / (4 pi) / (1.9 - C + 3.5 (C - 0.8)^2) = Burley's d fitted to the physical profile, C = its A";
  std::string out =
      "# Blender Principled BSDF materials exported by bssrdf " BSSRDF_VERSION
      "\n"
      "# Cycles subsurface method: " +
      std::string(to_string(mapping)) + " (Blender " +
      (options.blender_version ? std::to_string(options.blender_version) + ".x"
                               : std::string("3.x and 4.x, chosen when run")) +
      ").\n"
      "# Chosen so that Cycles simulates our medium (Cycles' kernel: closure/bssrdf.h bssrdf_setup_radius,\n"
      "# integrator/subsurface_random_walk.h subsurface_random_walk_remap), per channel, in " +
      u +
      ":\n"
      "#   R = Subsurface Radius x Subsurface (3.x; here 1) or x Subsurface Scale (4.x; here 1)\n"
      "#   " +
      radius_rule + "\n" +
      (mapping == CyclesMapping::burley
           ? std::string(
                 "#   Christensen-Burley is a profile, not a medium: R(r) = C (e^{-r/d} + e^{-r/3d}) / (8 pi d r).\n")
           : std::string(
                 "#   C = Base Color (and 3.x Subsurface Color) chosen so that Cycles' fit alpha(C, g) equals our\n"
                 "#   single-scattering albedo sigma_s / sigma_t; g = Subsurface Anisotropy (Cycles clamps to [0, "
                 "0.9]).\n"
                 "#   Cycles raises alpha below 0.2 to 0.2 (scaling the throughput instead) and stops walks after\n"
                 "#   256 scattering events; the boundary is index-matched for the walk (3.x enters along a cosine\n"
                 "#   lobe; 4.x refracts through IOR), so Subsurface IOR only matters to the radius remap.\n")) +
      "# One Blender unit = 1 " + u +
      " (Blender's default scene unit is the metre: export with --unit m, the default).\n"
      "# Also set: 3.x Specular = ((eta - 1)/(eta + 1))^2 / 0.08 (the Fresnel reflectance of eta), 4.x IOR = eta.\n"
      "# 3.x adds a retro-reflection lobe at grazing angles that is not part of the medium.\n"
      "# Run in Blender: blender --python THIS_FILE (or paste into the Text Editor and Run Script).\n"
      "import bpy\n\n"
      "METHODS = {" +
      methods +
      "}\n\n\n"
      "def make_material(name, albedo_color, radius, ior, anisotropy):\n"
      "    major = bpy.app.version[0]\n"
      "    if major not in METHODS:\n"
      "        raise RuntimeError('exported for Blender %s; this is %s: export again with --blender-version'\n"
      "                           % (sorted(METHODS), bpy.app.version_string))\n"
      "    mat = bpy.data.materials.get(name) or bpy.data.materials.new(name)\n"
      "    mat.use_nodes = True\n"
      "    bsdf = next(n for n in mat.node_tree.nodes if n.type == 'BSDF_PRINCIPLED')\n"
      "    bsdf.subsurface_method = METHODS[major]\n"
      "    inputs = bsdf.inputs\n"
      "    inputs['Base Color'].default_value = (*albedo_color, 1.0)\n"
      "    inputs['Subsurface Radius'].default_value = radius\n"
      "    inputs['Subsurface IOR'].default_value = ior\n"
      "    inputs['Subsurface Anisotropy'].default_value = anisotropy\n"
      "    if major >= 4:\n"
      "        inputs['Subsurface Weight'].default_value = 1.0\n"
      "        inputs['Subsurface Scale'].default_value = 1.0\n"
      "        inputs['IOR'].default_value = ior\n"
      "    else:\n"
      "        inputs['Subsurface'].default_value = 1.0\n"
      "        inputs['Subsurface Color'].default_value = (*albedo_color, 1.0)\n"
      "        inputs['Specular'].default_value = min(((ior - 1) / (ior + 1)) ** 2 / 0.08, 1.0)\n"
      "    held = tuple(inputs['Subsurface Radius'].default_value)\n"
      "    if any(abs(h - r) > 1e-6 * r for h, r in zip(held, radius)):\n"
      "        raise RuntimeError('%s: Blender holds Subsurface Radius %s, not %s' % (name, held, radius))\n"
      "    return mat\n";
  const double mm = millimetres_per(unit);
  for (const auto& e : entries) {
    const auto in = cycles_inputs(e.material.medium, e.derived, mapping, mm);
    out += "\n\n# " + e.material.name + " (" + e.material.source + "): " + e.material.citation + "\n";
    if (mapping == CyclesMapping::burley) {
      std::vector<double> d, error;
      for (const auto& c : e.derived.channels) d.push_back(from_mm(c.burley_d, unit)), error.push_back(c.burley_error);
      out += "#   Burley d [" + u + "] " + join(d, ", ") + ", A " + join(in.albedo_color, ", ") +
             "; relative L2 error of the fit to " + e.derived.physical_model + ": " + join(error, ", ") + "\n";
    } else {
      out += "#   medium: sigma_t [1/" + u + "] " + join(in.target_sigma_t, ", ") + ", alpha " +
             join(in.target_alpha, ", ") + ", g " + num(in.g) + "\n";
      out += "#   Cycles simulates: sigma_t [1/" + u + "] " + join(in.simulated.sigma_t, ", ") + ", alpha " +
             join(in.simulated.alpha, ", ") + "\n";
    }
    for (const auto& note : in.notes) out += "#   NOTE " + note + "\n";
    out += "#   " + validity_summary(e.derived) + "\n";
    out += "make_material(" + py_string(e.material.name) + ", albedo_color=" + tuple(in.albedo_color) +
           ", radius=" + tuple(in.radius) + ", ior=" + num(in.eta) + ", anisotropy=" + num(in.g) + ")\n";
  }
  return out;
}

}  // namespace bssrdf::export_detail
