// Unity HDRP diffusion profiles. HDRP's Scattering Distance (colour x multiplier) is Burley's d
// directly; its shader reads it in millimetres with World Scale = metres per scene unit. Here d
// is the least-squares fit to the physical profile (fit_burley), never a rule of thumb.
// Thickness remap suggestion: 0 to the thickness where HDRP's transmission
// (A/4)(e^{-t/d} + 3 e^{-t/3d}) falls to 1 % of its value at t = 0 for the widest channel,
// t = 3 ln(75) d_max ~ 12.95 d_max, capped at the object size.
// Two forms: JSON with HDRP's field names (unity-hdrp), and a C# Editor script that creates the
// DiffusionProfileSettings assets (unity-hdrp-editor), writing the fields HDRP serialises under
// `profile` (DiffusionProfile: scatteringDistance, scatteringDistanceMultiplier, transmissionTint,
// thicknessRemap, worldScale, ior; HDRP's Runtime/Material/DiffusionProfile/DiffusionProfileSettings.cs).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "export_common.hpp"

namespace bssrdf::export_detail {
namespace {

struct UnityProfile {
  std::vector<double> d, A, error, color;  // d in mm; color = d / d_max
  std::vector<bool> valid;
  double d_max = 0, world_scale = 0, ior = 1.4, thickness_max = 0;
};

UnityProfile unity_profile(const ExportEntry& e, LengthUnit unit) {
  UnityProfile p;
  for (const auto& c : e.derived.channels) {
    p.d.push_back(std::isfinite(c.burley_d) ? c.burley_d : 0.0);
    p.A.push_back(std::isfinite(c.burley_albedo) ? c.burley_albedo : 0.0);
    p.error.push_back(c.burley_error);
    p.valid.push_back(c.valid());
    p.d_max = std::max(p.d_max, p.d.back());
  }
  for (double v : p.d) p.color.push_back(p.d_max > 0 ? v / p.d_max : 0.0);
  p.world_scale = millimetres_per(unit) / 1000;
  p.ior = std::clamp(e.material.medium.eta, 1.0, 2.0);
  p.thickness_max = std::min(3 * std::log(75.0) * p.d_max, e.derived.object_size_mm);
  return p;
}

}  // namespace

std::string export_unity_hdrp(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  require_rgb(entries, "unity-hdrp");
  using json = nlohmann::ordered_json;
  json doc;
  doc["format"] = "bssrdf-unity-hdrp-diffusion-profiles";
  doc["tool"] = "bssrdf " BSSRDF_VERSION;
  doc["conventions"] = {
      {"scatteringDistance", "Burley d per channel divided by scatteringDistanceMultiplier (max channel = 1)"},
      {"scatteringDistanceMultiplier",
       "mm: scatteringDistance x multiplier = Burley d in mm, R(r) = A (e^{-r/d} + e^{-r/3d}) / (8 pi d r)"},
      {"worldScale", "metres per scene unit (from --unit " + std::string(symbol(unit)) + ")"},
      {"ior", "eta clamped to HDRP's 1-2"},
      {"thicknessRemapMillimeters",
       "suggestion: 0 to where transmission falls to 1 % for the widest channel (12.95 d_max), at most the object "
       "size"},
      {"burleyFit",
       "d and A least-squares fitted to the physical model's R(r); relativeL2Error = sqrt(int r (fit - R)^2 dr / int r "
       "R^2 dr)"}};
  doc["profiles"] = json::array();
  for (const auto& e : entries) {
    const auto p = unity_profile(e, unit);
    json errors = json::array();
    for (double v : p.error) errors.push_back(std::isfinite(v) ? json(v) : json(nullptr));
    json profile = {
        {"name", e.material.name},
        {"source", e.material.source},
        {"scatteringDistance", p.color},
        {"scatteringDistanceMultiplier", p.d_max},
        {"worldScale", p.world_scale},
        {"ior", p.ior},
        {"thicknessRemapMillimeters", {0.0, p.thickness_max}},
        {"transmissionTint", {1.0, 1.0, 1.0}},
        {"surfaceAlbedo", p.A},
        {"burleyFit",
         {{"physicalModel", e.derived.physical_model}, {"burleyDMillimeters", p.d}, {"relativeL2Error", errors}}},
        {"diffusionValid", p.valid},
        {"validity", validity_summary(e.derived)}};
    doc["profiles"].push_back(profile);
  }
  return doc.dump(2) + "\n";
}

std::string export_unity_hdrp_editor(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  require_rgb(entries, "unity-hdrp-editor");
  const auto f = [](double v) { return num(v) + "f"; };
  std::string calls;
  for (const auto& e : entries) {
    const auto p = unity_profile(e, unit);
    std::string name;
    for (char c : e.material.name) name += (c == '"' || c == '\\') ? '_' : c;
    calls += "        // " + e.material.name + " (" + e.material.source + "): Burley d [mm] " + join(p.d, ", ") + "; " +
             validity_summary(e.derived) + "\n";
    calls += "        Make(\"" + name + "\", new Color(" + f(p.color[0]) + ", " + f(p.color[1]) + ", " + f(p.color[2]) +
             "), " + f(p.d_max) + ", " + f(p.world_scale) + ", " + f(p.ior) + ", " + f(p.thickness_max) + ");\n";
  }
  return "// Unity HDRP diffusion profiles exported by bssrdf " BSSRDF_VERSION
         ".\n"
         "// Put this file in an Editor folder (e.g. Assets/Editor/) and run the menu item\n"
         "// bssrdf > Create Diffusion Profiles: it writes Assets/DiffusionProfiles/<name>.asset (HDRP's\n"
         "// DiffusionProfileSettings), then assign them in the HDRP Global Settings' Diffusion Profile List.\n"
         "// Scattering Distance (linear colour, largest channel 1) x Multiplier = Burley's d in mm at\n"
         "// World Scale 1 (HDRP's convention); World Scale = metres per scene unit (--unit " +
         std::string(symbol(unit)) +
         ");\n"
         "// d fitted to the physical profile; Thickness Remap 0 to 12.95 d_max (1 % transmission), IOR clamped to "
         "1-2.\n"
         "using UnityEditor;\n"
         "using UnityEngine;\n"
         "using UnityEngine.Rendering.HighDefinition;\n\n"
         "public static class BssrdfDiffusionProfiles\n"
         "{\n"
         "    [MenuItem(\"bssrdf/Create Diffusion Profiles\")]\n"
         "    public static void CreateAll()\n"
         "    {\n" +
         calls +
         "        AssetDatabase.SaveAssets();\n"
         "    }\n\n"
         "    static void Make(string name, Color scatteringColor, float multiplierMillimeters, float worldScale, "
         "float ior,\n"
         "                     float thicknessMaxMillimeters)\n"
         "    {\n"
         "        System.IO.Directory.CreateDirectory(\"Assets/DiffusionProfiles\");\n"
         "        string path = \"Assets/DiffusionProfiles/\" + name + \".asset\";\n"
         "        var asset = AssetDatabase.LoadAssetAtPath<DiffusionProfileSettings>(path);\n"
         "        if (asset == null)\n"
         "        {\n"
         "            asset = ScriptableObject.CreateInstance<DiffusionProfileSettings>();\n"
         "            AssetDatabase.CreateAsset(asset, path);\n"
         "        }\n"
         "        var profile = new SerializedObject(asset).FindProperty(\"profile\");\n"
         "        var multiplier = profile.FindPropertyRelative(\"scatteringDistanceMultiplier\");\n"
         "        if (multiplier != null)\n"
         "        {\n"
         "            profile.FindPropertyRelative(\"scatteringDistance\").colorValue = scatteringColor;\n"
         "            multiplier.floatValue = multiplierMillimeters;\n"
         "        }\n"
         "        else  // HDRP before the colour/multiplier split: one HDR colour in mm\n"
         "        {\n"
         "            profile.FindPropertyRelative(\"scatteringDistance\").colorValue = scatteringColor * "
         "multiplierMillimeters;\n"
         "        }\n"
         "        profile.FindPropertyRelative(\"transmissionTint\").colorValue = Color.white;\n"
         "        profile.FindPropertyRelative(\"thicknessRemap\").vector2Value = new Vector2(0f, "
         "thicknessMaxMillimeters);\n"
         "        profile.FindPropertyRelative(\"worldScale\").floatValue = worldScale;\n"
         "        profile.FindPropertyRelative(\"ior\").floatValue = ior;\n"
         "        profile.serializedObject.ApplyModifiedPropertiesWithoutUndo();\n"
         "        EditorUtility.SetDirty(asset);\n"
         "    }\n"
         "}\n";
}

}  // namespace bssrdf::export_detail
