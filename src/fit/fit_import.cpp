#include "bssrdf/fit/fit_import.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "../io/data_file.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/medium.hpp"

namespace bssrdf {
namespace {

using json = nlohmann::ordered_json;

double number_at(const nlohmann::json& object, const char* key) { return object.at(key).at("value").get<double>(); }

// One channel of the new material, in the fit's unit.
struct ImportedChannel {
  std::string name;
  double sigma_a = 0, sigma_s = 0, g = 0;
};

// 'bssrdf fit slab --rxt FILE -f json': one channel per converged row, named by its wavelength, eta from the header,
// coefficients in mm. Rows that did not converge (a status not starting "converged": not solved, not converged, not
// unique, no parameters reproduce the measurements, M_R only) are skipped and listed in `skipped`. When every kept row
// has a wavelength within [kMinWavelength, kMaxWavelength] nm, strictly increasing, they are the spectral material's
// wavelengths (a repeated or decreasing one is refused: a medium has one value per wavelength).
struct RxtRows {
  std::vector<ImportedChannel> channels;
  std::vector<double> wavelength_nm;  // empty: not spectral (e.g. iad's row numbers in the wavelength column)
  std::vector<std::string> skipped;
};

RxtRows rxt_rows(const nlohmann::json& fit, const std::string& fit_file, std::string& unit, double& eta) {
  unit = fit.value("unit", std::string("mm"));
  eta = fit.at("header").at("sample_index").get<double>();
  RxtRows out;
  std::vector<double> nm;
  for (std::size_t i = 0; i < fit.at("rows").size(); ++i) {
    const auto& r = fit.at("rows").at(i);
    const double wavelength = r.value("wavelength", 0.0);
    std::string name = format_number(wavelength);
    const std::string line = "line " + std::to_string(r.at("line").get<int>());
    const std::string status = r.value("status", std::string("converged"));  // results before status: all kept
    // "converged" or "converged; ..." / "converged at the edge ..." (a note on iad's search, the result holds)
    if (status.rfind("converged", 0) != 0) {
      out.skipped.push_back(line + (wavelength > 0 ? " (" + name + " nm)" : "") + ": " + status);
      continue;
    }
    const double g = number_at(r, "g");
    out.channels.push_back({wavelength > 0 ? name + "nm" : "row " + std::to_string(r.at("line").get<int>()),
                            number_at(r, "mu_a"), number_at(r, "mu_s_prime") / (1 - g), g});
    nm.push_back(wavelength);
  }
  if (out.channels.empty())
    throw FileError(fit_file, 0,
                    "$.rows: no row converged, nothing to import (" + std::to_string(out.skipped.size()) +
                        " skipped; first: " + (out.skipped.empty() ? std::string("none") : out.skipped.front()) + ")");
  const bool in_range = std::all_of(
      nm.begin(), nm.end(), [](double x) { return std::isfinite(x) && x >= kMinWavelength && x <= kMaxWavelength; });
  if (!in_range) return out;
  for (std::size_t i = 1; i < nm.size(); ++i)
    if (!(nm[i] > nm[i - 1]))
      throw FileError(fit_file, 0,
                      "$.rows: wavelength " + format_number(nm[i]) + " nm after " + format_number(nm[i - 1]) +
                          " nm: a spectral material takes strictly increasing wavelengths (fit one row per "
                          "wavelength: average or drop the repeated rows of the .rxt)");
  out.wavelength_nm = nm;
  return out;
}

// at(), never the const operator[]: on a missing key that is undefined behaviour (found by the
// mutation test under the sanitizers); at() throws, and the caller names the file.
std::string from_fit(const nlohmann::json& fit, const std::string& fit_file, const std::string& name,
                     std::optional<double> eta_given, const std::string& source, std::vector<std::string>* skipped) {
  const bool rxt = fit.is_object() && fit.contains("rows") && fit.contains("header");
  if (!fit.is_object() || (!rxt && fit.value("source", "") != "fit"))
    throw FileError(fit_file, 0, "$.source: expected \"fit\" (the output of 'bssrdf fit ... -f json')");
  std::vector<ImportedChannel> channels;
  std::string unit = "mm";
  double eta = NAN;
  std::vector<double> wavelength_nm;
  std::vector<std::string> notes{"Imported from " + fit_file + " by 'bssrdf materials import'."};
  if (rxt) {
    if (!fit.at("rows").is_array() || fit.at("rows").empty())
      throw FileError(fit_file, 0, "$.rows: expected a non-empty array");
    auto rows = rxt_rows(fit, fit_file, unit, eta);
    channels = std::move(rows.channels);
    wavelength_nm = std::move(rows.wavelength_nm);
    for (const auto& row : rows.skipped) notes.push_back("Skipped (not converged): " + row);
    if (skipped) *skipped = std::move(rows.skipped);
  } else {
    if (!fit.contains("channels") || !fit.at("channels").is_array() || fit.at("channels").empty())
      throw FileError(fit_file, 0, "$.channels: expected a non-empty array");
    if (fit.contains("eta"))  // a complete medium (every fit of sigma_a and sigma_s' writes it)
      eta = number_at(fit, "eta");
    else if (fit.contains("shared") && fit.at("shared").contains("eta"))
      eta = number_at(fit.at("shared"), "eta");
    for (std::size_t i = 0; i < fit.at("channels").size(); ++i) {
      const auto& c = fit.at("channels").at(i);
      const std::string where = "$.channels[" + std::to_string(i) + "]";
      for (const char* key : {"sigma_a", "sigma_s_prime"})
        if (!c.contains(key) || !c.at(key).contains("value") || !c.at(key).at("value").is_number())
          throw FileError(fit_file, 0,
                          where + "." + key +
                              ": missing (only fits of sigma_a and sigma_s' - profile, albedo, "
                              "slab, slab --rxt - give a material)");
      // Older results lack g: sigma_s' with g = 0 is then the diffusion-equivalent medium.
      const double g = c.contains("g") ? number_at(c, "g") : 0.0;
      // std::string("c") + ...: "c" + std::string&& trips GCC 12's -Wrestrict false positive (GCC bug 105329).
      channels.push_back({c.value("name", std::string("c") + std::to_string(i)), number_at(c, "sigma_a"),
                          number_at(c, "sigma_s_prime") / (1 - g), g});
      const std::string u = c.at("sigma_a").value("unit", "1/mm");
      if (u.rfind("1/", 0) != 0) throw FileError(fit_file, 0, where + ".sigma_a.unit: '" + u + "' is not 1/LENGTH");
      unit = u.substr(2);
    }
  }
  if (eta_given) eta = *eta_given;
  if (!std::isfinite(eta)) throw InvalidInput("eta: the fit result has no eta; give the one the fit assumed (--eta)");
  json names = json::array(), sigma_a = json::array(), sigma_s = json::array(), g = json::array();
  for (const auto& c : channels) {
    names.push_back(c.name);
    sigma_a.push_back(c.sigma_a);
    sigma_s.push_back(c.sigma_s);
    g.push_back(c.g);
  }
  const std::string kind = rxt ? std::string("slab --rxt") : fit.value("kind", std::string("?"));
  json doc = {{"format", "bssrdf-materials"},
              {"version", 1},
              {"source", source},
              {"citation", "bssrdf fit " + kind + " (" + fit.value("model", std::string("?")) + ") of " +
                               fit.value(rxt ? "source" : "data", std::string("?")) + ", " +
                               fit.value("tool", std::string(""))},
              {"unit", unit},
              {"channels", names}};
  if (!wavelength_nm.empty()) doc["wavelength_nm"] = wavelength_nm;  // a spectral material (docs/spectral.md)
  doc["notes"] = notes;
  doc["materials"] = {{{"name", name}, {"eta", eta}, {"sigma_a", sigma_a}, {"sigma_s", sigma_s}, {"g", g}}};
  return doc.dump(2) + "\n";
}

}  // namespace

std::string materials_file_from_fit(const std::string& fit_text, const std::string& fit_file, const std::string& name,
                                    std::optional<double> eta, const std::string& source,
                                    std::vector<std::string>* skipped) {
  const nlohmann::json fit = parse_json_document(fit_text, fit_file);
  try {
    return from_fit(fit, fit_file, name, eta, source, skipped);
  } catch (const nlohmann::json::exception& e) {  // a field of the wrong type (a string where a number belongs)
    const std::string what = e.what();
    throw FileError(fit_file, 0, "not the output of 'bssrdf fit ... -f json': " + what.substr(what.find(' ') + 1));
  }
}

}  // namespace bssrdf
