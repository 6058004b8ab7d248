// pbrt-v4 `subsurface` materials (sigma_a, sigma_s, g, eta, scale) as MakeNamedMaterial blocks,
// coefficients in 1/scene unit with scale 1. pbrt-v4 takes one g per material: see single_g().
#include "export_common.hpp"

namespace bssrdf::export_detail {

std::string export_pbrt_v4(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  require_rgb(entries, "pbrt-v4");
  const std::string u(symbol(unit));
  std::string out = "# pbrt-v4 subsurface materials exported by bssrdf " BSSRDF_VERSION "\n"
                    "# Units: sigma_a and sigma_s in 1/" + u + " (one scene unit = 1 " + u + "), \"scale\" 1.\n"
                    "# Distance convention: extinction coefficients; mean free path 1/(sigma_a + sigma_s) per channel,\n"
                    "# transport mean free path 1/(sigma_a + sigma_s (1 - g)), listed per material below.\n"
                    "# Use: Material \"<name>\" or NamedMaterial \"<name>\" before the shape.\n";
  for (const auto& e : entries) {
    const auto& m = e.material.medium;
    const auto one = single_g(m);
    std::vector<double> a, s, mfp, ell;
    for (std::size_t c = 0; c < 3; ++c) {
      a.push_back(coefficient_from_per_mm(m.sigma_a[c], unit));
      s.push_back(coefficient_from_per_mm(one.sigma_s[c], unit));
      mfp.push_back(from_mm(e.derived.channels[c].mfp, unit));
      ell.push_back(from_mm(e.derived.channels[c].transport_mfp, unit));
    }
    out += "\n# " + e.material.name + " (" + e.material.source + "): " + e.material.citation + "\n";
    out += "#   mfp 1/sigma_t [" + u + "]: " + join(mfp, " ") + "; transport mfp 1/sigma_t' [" + u + "]: " + join(ell, " ") + "\n";
    if (!one.exact)
      out += "#   per-channel g (" + join(m.g, " ") + ") replaced by their mean; sigma_s rescaled to keep sigma_s' = sigma_s (1 - g)\n";
    out += "#   " + validity_summary(e.derived) + "\n";
    out += "MakeNamedMaterial \"" + e.material.name + "\"\n";
    out += "    \"string type\" [ \"subsurface\" ]\n";
    out += "    \"rgb sigma_a\" [ " + join(a, " ") + " ]\n";
    out += "    \"rgb sigma_s\" [ " + join(s, " ") + " ]\n";
    out += "    \"float g\" [ " + num(one.g) + " ]\n";
    out += "    \"float eta\" [ " + num(m.eta) + " ]\n";
    out += "    \"float scale\" [ 1 ]\n";
  }
  return out;
}

}  // namespace bssrdf::export_detail
