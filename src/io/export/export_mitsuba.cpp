// Mitsuba 3: volumetric path tracing of a `homogeneous` medium (albedo = sigma_s/sigma_t,
// sigma_t in 1/scene unit, scale 1, `hg` phase) inside a `dielectric` boundary (int_ior = eta).
// Mitsuba's hg takes one g: see single_g().
#include "../xml_escape.hpp"
#include "export_common.hpp"

namespace bssrdf::export_detail {
namespace {
// XML comments may not contain "--"; attribute values escape the five special characters.
std::string comment(std::string text) {
  for (std::size_t p; (p = text.find("--")) != std::string::npos;) text.replace(p, 2, "- -");
  return "<!-- " + text + " -->";
}
}  // namespace

std::string export_mitsuba3(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  require_rgb(entries, "mitsuba3");
  const std::string u(symbol(unit));
  std::string out =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n" +
      comment("Mitsuba 3 media exported by bssrdf " BSSRDF_VERSION ". Units: sigma_t in 1/" + u +
              " (one scene unit = 1 " + u +
              "), scale 1; albedo = sigma_s/sigma_t (single-scattering, "
              "unreduced). Distance convention: mean free path 1/sigma_t. Use: <shape ...><ref id=\"NAME_boundary\"/>"
              "<ref name=\"interior\" id=\"NAME_medium\"/></shape>. Media render only with a volumetric integrator: "
              "volpath (or volpathmis), as set below; the default path integrator ignores them.") +
      "\n<scene version=\"3.0.0\">\n"
      "  <integrator type=\"volpath\">\n    <integer name=\"max_depth\" value=\"-1\"/>\n  </integrator>\n";
  for (const auto& e : entries) {
    const auto& m = e.material.medium;
    const auto one = single_g(m);
    std::vector<double> albedo, sigma_t, mfp;
    for (std::size_t c = 0; c < 3; ++c) {
      const double t = m.sigma_a[c] + one.sigma_s[c];
      albedo.push_back(one.sigma_s[c] / t);
      sigma_t.push_back(coefficient_from_per_mm(t, unit));
      mfp.push_back(1 / sigma_t.back());
    }
    const std::string id = identifier(e.material.name);
    std::string note = e.material.name + " (" + e.material.source + "): mean free path 1/sigma_t [" + u + "] " +
                       join(mfp, ", ") + "; " + validity_summary(e.derived);
    if (!one.exact)
      note += "; per-channel g (" + join(m.g, ", ") + ") replaced by their mean, sigma_s rescaled to keep sigma_s'";
    out += "  " + comment(note) + "\n";
    out += "  <medium type=\"homogeneous\" id=\"" + xml_escape(id) + "_medium\">\n";
    out += "    <rgb name=\"albedo\" value=\"" + join(albedo, ", ") + "\"/>\n";
    out += "    <rgb name=\"sigma_t\" value=\"" + join(sigma_t, ", ") + "\"/>\n";
    out += "    <float name=\"scale\" value=\"1\"/>\n";
    out += "    <phase type=\"hg\">\n      <float name=\"g\" value=\"" + num(one.g) + "\"/>\n    </phase>\n";
    out += "  </medium>\n";
    out += "  <bsdf type=\"dielectric\" id=\"" + xml_escape(id) + "_boundary\">\n";
    out += "    <float name=\"int_ior\" value=\"" + num(m.eta) + "\"/>\n";
    out += "    <float name=\"ext_ior\" value=\"1\"/>\n";
    out += "  </bsdf>\n";
  }
  return out + "</scene>\n";
}

}  // namespace bssrdf::export_detail
