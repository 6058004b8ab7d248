// A bssrdf materials file (materials/README.md): what `--db` loads back. Coefficients only, in
// 1/unit; derived quantities are recomputed on load, never stored.
#include <nlohmann/json.hpp>
#include <set>

#include "export_common.hpp"

namespace bssrdf::export_detail {

std::string export_json(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  using json = nlohmann::ordered_json;
  std::set<std::string> sources, citations;
  for (const auto& e : entries) sources.insert(e.material.source), citations.insert(e.material.citation);
  json doc;
  doc["format"] = "bssrdf-materials";
  doc["version"] = 1;
  doc["source"] = sources.size() == 1 ? *sources.begin() : std::string("bssrdf-export");
  std::string citation;
  for (const auto& c : citations) citation += (citation.empty() ? "" : " | ") + c;
  doc["citation"] = citation;
  doc["unit"] = std::string(symbol(unit));
  doc["channels"] = entries.front().material.medium.channel_names;
  if (entries.front().material.medium.spectral()) doc["wavelength_nm"] = entries.front().material.medium.wavelength_nm;
  doc["notes"] = {"Exported by bssrdf " BSSRDF_VERSION ": coefficients in 1/" + std::string(symbol(unit)) +
                  "; per-entry notes carry the original file's notes."};
  doc["materials"] = json::array();
  for (const auto& e : entries) {
    const auto& m = e.material.medium;
    std::vector<double> a, s;
    for (double v : m.sigma_a) a.push_back(coefficient_from_per_mm(v, unit));
    for (double v : m.sigma_s) s.push_back(coefficient_from_per_mm(v, unit));
    json entry = {{"name", e.material.name}, {"eta", m.eta}, {"sigma_a", a}};
    if (e.material.reduced_scattering_only) {
      entry["sigma_s_prime"] = s;
    } else {
      entry["sigma_s"] = s;
      entry["g"] = m.g;
    }
    if (!e.material.notes.empty()) entry["notes"] = e.material.notes;
    doc["materials"].push_back(entry);
  }
  return doc.dump(2) + "\n";
}

}  // namespace bssrdf::export_detail
