// Materials in the form each renderer reads (conventions read from each renderer's own source and documentation;
// README, "Exports"), every number labelled with its unit and distance convention:
//   json       a bssrdf materials file (materials/README.md), coefficients in 1/unit: loads back
//   pbrt-v4    `subsurface` materials: sigma_a, sigma_s (1/scene unit), g, eta
//   mitsuba3   `homogeneous` media (albedo, sigma_t, hg g) and `dielectric` boundaries (int_ior)
//   blender    a Python script making Principled BSDF materials whose Cycles medium is ours
//              (cycles_subsurface.hpp: the method, its radius convention, Cycles' albedo fit)
//   unity-hdrp diffusion profiles: Burley d (scattering distance), world scale, IOR, thickness remap
//              (JSON; unity-hdrp-editor: a C# Editor script creating the DiffusionProfileSettings assets)
//   unreal     UE5 subsurface profiles: surface albedo, mean free path colour x distance (cm), world
//              unit scale (JSON; unreal-python: an editor Python script creating SubsurfaceProfile assets)
// The real-time targets use Burley's d fitted to the physical profile (derived_quantities.hpp),
// not a rule of thumb. Renderers that take one g per material get the channel mean, with sigma_s
// rescaled so that every channel keeps its sigma_s' = sigma_s (1 - g) (what diffusion depends on).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/io/cycles_subsurface.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

enum class RendererTarget { json, pbrt_v4, mitsuba3, blender, unity_hdrp, unity_hdrp_editor, unreal, unreal_python };

// "json", "pbrt-v4", "mitsuba3", "blender", "unity-hdrp", "unity-hdrp-editor", "unreal", "unreal-python";
// InvalidInput lists them otherwise.
RendererTarget parse_renderer_target(std::string_view text);
std::string_view to_string(RendererTarget target);
std::vector<std::string> renderer_target_names();

struct ExportEntry {
  Material material;
  DerivedQuantities derived;  // needed by every target but json
};

// `unit`: the scene unit lengths and coefficients are written in (json: the file's unit; unreal
// always writes cm, its engine unit). Materials must share channel names; pbrt-v4, Mitsuba 3,
// Blender, Unity and Unreal need exactly three (RGB). Throws InvalidInput otherwise.
struct ExportOptions {
  CyclesMapping blender_method = CyclesMapping::fixed_radius;
  int blender_version = 0;  // 3 or 4; 0: the script picks by bpy.app.version when it runs
};
std::string export_materials(RendererTarget target, const std::vector<ExportEntry>& entries, LengthUnit unit,
                             const ExportOptions& options = {});

// One g for renderers that take a single value: the mean over the channels that scatter, and
// sigma_s rescaled per channel to keep sigma_s' (1/mm). `exact` when all g were already equal.
struct SingleG {
  double g = 0;
  std::vector<double> sigma_s;
  bool exact = true;
};
SingleG single_g(const Medium& medium);

// Burley's searchlight mfp scaling s(A) = 1.85 - A + 7|A - 0.8|^3: Unreal's mean free path is d s(A).
double burley_searchlight_scaling(double A);

}  // namespace bssrdf
