// 'bssrdf materials show': see materials_show.hpp.
#include "materials_show.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf::cli {
namespace {

using json = nlohmann::ordered_json;

// A length in the output unit; infinite and NaN become null in JSON.
json length(double mm, LengthUnit unit) {
  const double v = from_mm(mm, unit);
  return std::isfinite(v) ? json(v) : json(nullptr);
}
json value(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json validity_json(const ValidityReport& report) {  // as `bssrdf profile -f json` writes it
  json out = json::array();
  for (const auto& note : report)
    out.push_back(
        {{"severity", std::string(to_string(note.severity))}, {"code", note.code}, {"message", note.message}});
  return out;
}

}  // namespace

std::string show_json(const Material& m, const DerivedQuantities& q, LengthUnit unit) {
  const std::string u(symbol(unit)), per = "1/" + u;
  json doc = {
      {"name", m.name},
      {"source", m.source},
      {"citation", m.citation},
      {"file", m.file},
      {"eta", m.medium.eta},
      {"unit", u},
      {"reduced_scattering_only", m.reduced_scattering_only},
      {"physical_model", q.physical_model},
      {"object_size", from_mm(q.object_size_mm, unit)},
      {"conventions",
       {{"mfp", "1/sigma_t (unreduced), " + u},
        {"transport_mfp", "ell = 1/sigma_t', " + u},
        {"diffuse_mfp", "ell_d = 1/sigma_tr, sigma_tr = sqrt(3 sigma_a sigma_t'), " + u + "; null without absorption"},
        {"burley_d",
         "d of R(r) = A (e^{-r/d} + e^{-r/3d})/(8 pi d r), A = surface_albedo, least-squares fitted to the " +
             q.physical_model + " profile (each channel's physical_model), " + u +
             "; burley_fit_error = sqrt(int r (fit - R)^2 dr / int r R^2 dr)"},
        {"surface_albedo",
         "total diffuse reflectance per entered flux: the exact model's inside its domain; outside it the "
         "channel's physical model's, or where that exceeds 1 (the model creates energy) the exact total by "
         "adding-doubling, and the channel's validity says so (code surface_albedo)"},
        {"coefficients", per}}},
      {"notes", m.notes}};
  doc["channels"] = json::array();
  for (const auto& c : q.channels) {
    doc["channels"].push_back({{"name", c.name},
                               {"sigma_a", coefficient_from_per_mm(c.sigma_a, unit)},
                               {"sigma_s", coefficient_from_per_mm(c.sigma_s, unit)},
                               {"g", c.g},
                               {"sigma_t", coefficient_from_per_mm(c.sigma_t, unit)},
                               {"sigma_s_prime", coefficient_from_per_mm(c.sigma_s_prime, unit)},
                               {"sigma_t_prime", coefficient_from_per_mm(c.sigma_t_prime, unit)},
                               {"albedo", c.albedo},
                               {"albedo_prime", c.albedo_prime},
                               {"mfp", length(c.mfp, unit)},
                               {"transport_mfp", length(c.transport_mfp, unit)},
                               {"diffuse_mfp", length(c.diffuse_mfp, unit)},
                               {"burley_d", length(c.burley_d, unit)},
                               {"burley_albedo", value(c.burley_albedo)},
                               {"burley_fit_error", value(c.burley_error)},
                               {"physical_model", c.physical_model},
                               {"model_choice", c.model_choice},
                               {"surface_albedo", c.surface_albedo},
                               {"valid", c.valid()},
                               {"validity", validity_json(c.validity)}});
  }
  return doc.dump(2) + "\n";
}

std::string show_table(const Material& m, const DerivedQuantities& q, LengthUnit unit) {
  const std::string u(symbol(unit));
  std::ostringstream out;
  out << m.name << " (" << m.source << ")  eta " << m.medium.eta << "\n" << m.citation << "\n";
  for (const auto& n : m.notes) out << "  note: " << n << "\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-24s", "");
  out << line;
  for (const auto& c : q.channels) {
    std::snprintf(line, sizeof line, "%14s", c.name.c_str());
    out << line;
  }
  out << "\n";
  auto row = [&](const std::string& label, auto get) {
    std::snprintf(line, sizeof line, "%-24s", label.c_str());
    out << line;
    for (const auto& c : q.channels) {
      std::snprintf(line, sizeof line, "%14.6g", get(c));
      out << line;
    }
    out << "\n";
  };
  const double mm = millimetres_per(unit);
  row("sigma_a [1/" + u + "]", [&](const DerivedChannel& c) { return c.sigma_a * mm; });
  row("sigma_s [1/" + u + "]", [&](const DerivedChannel& c) { return c.sigma_s * mm; });
  row("g", [](const DerivedChannel& c) { return c.g; });
  row("sigma_s' [1/" + u + "]", [&](const DerivedChannel& c) { return c.sigma_s_prime * mm; });
  row("albedo", [](const DerivedChannel& c) { return c.albedo; });
  row("albedo'", [](const DerivedChannel& c) { return c.albedo_prime; });
  row("mfp 1/sigma_t [" + u + "]", [&](const DerivedChannel& c) { return c.mfp / mm; });
  row("ell 1/sigma_t' [" + u + "]", [&](const DerivedChannel& c) { return c.transport_mfp / mm; });
  row("ell_d 1/sigma_tr [" + u + "]", [&](const DerivedChannel& c) { return c.diffuse_mfp / mm; });
  row("Burley d [" + u + "]", [&](const DerivedChannel& c) { return c.burley_d / mm; });
  row("Burley fit error", [](const DerivedChannel& c) { return c.burley_error; });
  row("surface albedo", [](const DerivedChannel& c) { return c.surface_albedo; });
  out << "physical profile: " << q.physical_model << "; object size " << from_mm(q.object_size_mm, unit) << " " << u
      << "\n";
  for (const auto& c : q.channels) {
    if (!c.model_choice.empty()) out << "  " << c.name << ": " << c.model_choice << "\n";
    bool any = false;
    for (const auto& note : c.validity)
      if (note.severity != Severity::note) out << "  " << c.name << ": " << describe(note) << "\n", any = true;
    if (!any) out << "  " << c.name << ": " << c.physical_model << " valid\n";
  }
  return out.str();
}

}  // namespace bssrdf::cli
