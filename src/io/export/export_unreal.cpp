// Unreal Engine 5 subsurface profiles (Burley). UE takes Surface Albedo and a Mean Free Path Color x
// Mean Free Path Distance in cm, and evaluates Burley's profile with d = mfp / s(A), s the
// searchlight mfp scaling 1.85 - A + 7|A - 0.8|^3 (Christensen & Burley 2015). So the mean free
// path written is d s(A), with d and A fitted to the physical profile: UE then reproduces the fit.
// (UE's 0.6 factor applies only when it upgrades old diffuse-mfp assets.)
// Two forms: JSON with UE's field names (unreal), and a Python editor script that creates the
// SubsurfaceProfile assets (unreal-python; UE's Python API: unreal.SubsurfaceProfile's `settings`,
// an unreal.SubsurfaceProfileStruct with surface_albedo, mean_free_path_color,
// mean_free_path_distance (cm), world_unit_scale, enable_burley, enable_mean_free_path, ior).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>

#include "export_common.hpp"

namespace bssrdf::export_detail {
namespace {

struct UnrealProfile {
  std::vector<double> A, mfp, d_cm, color;  // mfp, d in cm; color = mfp / mfp_max
  double mfp_max = 0;
};

UnrealProfile unreal_profile(const ExportEntry& e) {
  UnrealProfile p;
  for (const auto& c : e.derived.channels) {
    const double a = std::isfinite(c.burley_albedo) ? c.burley_albedo : 0.0;
    const double d = std::isfinite(c.burley_d) ? from_mm(c.burley_d, LengthUnit::centimetre) : 0.0;
    p.A.push_back(a);
    p.d_cm.push_back(d);
    p.mfp.push_back(d * burley_searchlight_scaling(a));
    p.mfp_max = std::max(p.mfp_max, p.mfp.back());
  }
  for (double v : p.mfp) p.color.push_back(p.mfp_max > 0 ? v / p.mfp_max : 0.0);
  return p;
}

}  // namespace

std::string export_unreal(const std::vector<ExportEntry>& entries) {
  require_rgb(entries, "unreal");
  using json = nlohmann::ordered_json;
  json doc;
  doc["format"] = "bssrdf-unreal-subsurface-profiles";
  doc["tool"] = "bssrdf " BSSRDF_VERSION;
  doc["conventions"] = {
      {"SurfaceAlbedo", "Burley A fitted to the physical profile (total diffuse reflectance of the fit)"},
      {"MeanFreePathDistance",
       "cm (Unreal's unit); MeanFreePathColor x MeanFreePathDistance = Burley d x s(A), "
       "s(A) = 1.85 - A + 7|A - 0.8|^3, so that UE's d = mfp / s(A) equals the fitted d"},
      {"WorldUnitScale", "cm per Unreal unit: 1 (UE's documented unit; UE's default asset has 0.1)"},
      {"burleyDCentimeters", "the fitted Burley d itself, cm"},
      {"IOR", "eta"}};
  doc["profiles"] = json::array();
  for (const auto& e : entries) {
    const auto p = unreal_profile(e);
    doc["profiles"].push_back({{"name", e.material.name},
                               {"source", e.material.source},
                               {"bEnableBurley", true},
                               {"bEnableMeanFreePath", true},
                               {"SurfaceAlbedo", p.A},
                               {"MeanFreePathColor", p.color},
                               {"MeanFreePathDistance", p.mfp_max},
                               {"WorldUnitScale", 1.0},
                               {"IOR", e.material.medium.eta},
                               {"burleyDCentimeters", p.d_cm},
                               {"physicalModel", e.derived.physical_model},
                               {"validity", validity_summary(e.derived)}});
  }
  return doc.dump(2) + "\n";
}

std::string export_unreal_python(const std::vector<ExportEntry>& entries) {
  require_rgb(entries, "unreal-python");
  std::string out =
      "# Unreal Engine 5 subsurface profiles exported by bssrdf " BSSRDF_VERSION
      ".\n"
      "# Run in the Unreal Editor (Python Editor Script Plugin): Tools > Execute Python Script, or\n"
      "# `py \"THIS_FILE\"` in the console. Creates (or updates) /Game/SubsurfaceProfiles/<name>.\n"
      "# SurfaceAlbedo = Burley A fitted to the physical profile; MeanFreePathColor x MeanFreePathDistance (cm)\n"
      "# = d s(A), s(A) = 1.85 - A + 7|A - 0.8|^3, so UE's Burley d = mfp / s(A) is the fitted d;\n"
      "# WorldUnitScale 1: one Unreal unit = 1 cm (UE's unit; its default asset uses 0.1).\n"
      "import unreal\n\n"
      "FOLDER = '/Game/SubsurfaceProfiles'\n\n\n"
      "def make_profile(name, surface_albedo, mean_free_path_color, mean_free_path_distance_cm, ior):\n"
      "    path = FOLDER + '/' + name\n"
      "    if unreal.EditorAssetLibrary.does_asset_exist(path):\n"
      "        asset = unreal.EditorAssetLibrary.load_asset(path)\n"
      "    else:\n"
      "        asset = unreal.AssetToolsHelpers.get_asset_tools().create_asset(name, FOLDER, unreal.SubsurfaceProfile, "
      "None)\n"
      "    settings = asset.get_editor_property('settings')\n"
      "    settings.set_editor_property('enable_burley', True)\n"
      "    settings.set_editor_property('enable_mean_free_path', True)  # UE 5.1+\n"
      "    settings.set_editor_property('surface_albedo', unreal.LinearColor(*surface_albedo, 1.0))\n"
      "    settings.set_editor_property('mean_free_path_color', unreal.LinearColor(*mean_free_path_color, 1.0))\n"
      "    settings.set_editor_property('mean_free_path_distance', mean_free_path_distance_cm)\n"
      "    settings.set_editor_property('world_unit_scale', 1.0)\n"
      "    settings.set_editor_property('ior', ior)\n"
      "    asset.set_editor_property('settings', settings)\n"
      "    unreal.EditorAssetLibrary.save_loaded_asset(asset)\n"
      "    return asset\n";
  for (const auto& e : entries) {
    const auto p = unreal_profile(e);
    std::string name;
    for (char c : e.material.name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    out += "\n\n# " + e.material.name + " (" + e.material.source + "): Burley d [cm] " + join(p.d_cm, ", ") + "; " +
           validity_summary(e.derived) + "\n";
    out += "make_profile('" + name + "', (" + join(p.A, ", ") + "), (" + join(p.color, ", ") + "), " + num(p.mfp_max) +
           ", " + num(e.material.medium.eta) + ")\n";
  }
  return out;
}

}  // namespace bssrdf::export_detail
