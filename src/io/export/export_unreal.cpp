// Unreal Engine 5 subsurface profiles (Burley). UE takes Surface Albedo and a Mean Free Path Color x
// Mean Free Path Distance in cm, and evaluates Burley's profile with d = mfp / s(A), s the
// searchlight mfp scaling 1.85 - A + 7|A - 0.8|^3 (Christensen & Burley 2015). So the mean free
// path written is d s(A), with d and A fitted to the physical profile: UE then reproduces the fit.
// (UE's 0.6 factor applies only when it upgrades old diffuse-mfp assets.)
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "export_common.hpp"

namespace bssrdf::export_detail {

std::string export_unreal(const std::vector<ExportEntry>& entries) {
  require_rgb(entries, "unreal");
  using json = nlohmann::ordered_json;
  json doc;
  doc["format"] = "bssrdf-unreal-subsurface-profiles";
  doc["tool"] = "bssrdf " BSSRDF_VERSION;
  doc["conventions"] = {
      {"SurfaceAlbedo", "Burley A fitted to the physical profile (total diffuse reflectance of the fit)"},
      {"MeanFreePathDistance", "cm (Unreal's unit); MeanFreePathColor x MeanFreePathDistance = Burley d x s(A), "
                               "s(A) = 1.85 - A + 7|A - 0.8|^3, so that UE's d = mfp / s(A) equals the fitted d"},
      {"burleyDCentimeters", "the fitted Burley d itself, cm"},
      {"IOR", "eta"}};
  doc["profiles"] = json::array();
  for (const auto& e : entries) {
    const auto& q = e.derived;
    std::vector<double> A, mfp, d_cm;
    double mfp_max = 0;
    for (const auto& c : q.channels) {
      const double a = std::isfinite(c.burley_albedo) ? c.burley_albedo : 0.0;
      const double d = std::isfinite(c.burley_d) ? from_mm(c.burley_d, LengthUnit::centimetre) : 0.0;
      A.push_back(a);
      d_cm.push_back(d);
      mfp.push_back(d * burley_searchlight_scaling(a));
      mfp_max = std::max(mfp_max, mfp.back());
    }
    std::vector<double> color;
    for (double v : mfp) color.push_back(mfp_max > 0 ? v / mfp_max : 0.0);
    doc["profiles"].push_back({{"name", e.material.name},
                               {"source", e.material.source},
                               {"bEnableBurley", true},
                               {"bEnableMeanFreePath", true},
                               {"SurfaceAlbedo", A},
                               {"MeanFreePathColor", color},
                               {"MeanFreePathDistance", mfp_max},
                               {"IOR", e.material.medium.eta},
                               {"burleyDCentimeters", d_cm},
                               {"physicalModel", q.physical_model},
                               {"validity", validity_summary(q)}});
  }
  return doc.dump(2) + "\n";
}

}  // namespace bssrdf::export_detail
