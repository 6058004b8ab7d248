// Unity HDRP diffusion profiles. HDRP's Scattering Distance (colour x multiplier) is Burley's d
// directly; its shader reads it in millimetres with World Scale = metres per scene unit. Here d
// is the least-squares fit to the physical profile (fit_burley), never a rule of thumb.
// Thickness remap suggestion: 0 to the thickness where HDRP's transmission
// (A/4)(e^{-t/d} + 3 e^{-t/3d}) falls to 1 % of its value at t = 0 for the widest channel,
// t = 3 ln(75) d_max ~ 12.95 d_max, capped at the object size.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "export_common.hpp"

namespace bssrdf::export_detail {

std::string export_unity_hdrp(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  require_rgb(entries, "unity-hdrp");
  using json = nlohmann::ordered_json;
  json doc;
  doc["format"] = "bssrdf-unity-hdrp-diffusion-profiles";
  doc["tool"] = "bssrdf " BSSRDF_VERSION;
  doc["conventions"] = {
      {"scatteringDistance", "Burley d per channel divided by scatteringDistanceMultiplier (max channel = 1)"},
      {"scatteringDistanceMultiplier", "mm: scatteringDistance x multiplier = Burley d in mm, R(r) = A (e^{-r/d} + e^{-r/3d}) / (8 pi d r)"},
      {"worldScale", "metres per scene unit (from --unit " + std::string(symbol(unit)) + ")"},
      {"ior", "eta clamped to HDRP's 1-2"},
      {"thicknessRemapMillimeters", "suggestion: 0 to where transmission falls to 1 % for the widest channel (12.95 d_max), at most the object size"},
      {"burleyFit", "d and A least-squares fitted to the physical model's R(r); relativeL2Error = sqrt(int r (fit - R)^2 dr / int r R^2 dr)"}};
  doc["profiles"] = json::array();
  for (const auto& e : entries) {
    const auto& q = e.derived;
    std::vector<double> d, A, error, color;
    std::vector<bool> valid;
    double d_max = 0;
    for (const auto& c : q.channels) {
      d.push_back(std::isfinite(c.burley_d) ? c.burley_d : 0.0);
      A.push_back(std::isfinite(c.burley_albedo) ? c.burley_albedo : 0.0);
      error.push_back(c.burley_error);
      valid.push_back(c.diffusion_valid);
      d_max = std::max(d_max, d.back());
    }
    for (double v : d) color.push_back(d_max > 0 ? v / d_max : 0.0);
    json errors = json::array();
    for (double v : error) errors.push_back(std::isfinite(v) ? json(v) : json(nullptr));
    json profile = {
        {"name", e.material.name},
        {"source", e.material.source},
        {"scatteringDistance", color},
        {"scatteringDistanceMultiplier", d_max},
        {"worldScale", millimetres_per(unit) / 1000},
        {"ior", std::clamp(e.material.medium.eta, 1.0, 2.0)},
        {"thicknessRemapMillimeters", {0.0, std::min(3 * std::log(75.0) * d_max, q.object_size_mm)}},
        {"transmissionTint", {1.0, 1.0, 1.0}},
        {"surfaceAlbedo", A},
        {"burleyFit", {{"physicalModel", q.physical_model}, {"burleyDMillimeters", d}, {"relativeL2Error", errors}}},
        {"diffusionValid", valid},
        {"validity", validity_summary(q)}};
    doc["profiles"].push_back(profile);
  }
  return doc.dump(2) + "\n";
}

}  // namespace bssrdf::export_detail
