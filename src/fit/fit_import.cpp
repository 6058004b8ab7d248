#include "bssrdf/fit/fit_import.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "../io/data_file.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

using json = nlohmann::ordered_json;

double number_at(const nlohmann::json& object, const char* key) { return object.at(key).at("value").get<double>(); }

// One channel of the new material, in the fit's unit.
struct ImportedChannel {
  std::string name;
  double sigma_a = 0, sigma_s = 0, g = 0;
};

// 'bssrdf fit slab --rxt FILE -f json': one channel per row (named by its wavelength), eta from
// the header, coefficients in mm.
std::vector<ImportedChannel> rxt_rows(const nlohmann::json& fit, std::string& unit, double& eta) {
  unit = fit.value("unit", std::string("mm"));
  eta = fit.at("header").at("sample_index").get<double>();
  std::vector<ImportedChannel> out;
  for (const auto& r : fit.at("rows")) {
    const double g = number_at(r, "g");
    const double wavelength = r.at("wavelength").get<double>();
    std::string name = std::to_string(wavelength);
    name.erase(name.find_last_not_of('0') + 1);
    if (name.back() == '.') name.pop_back();
    out.push_back({r.value("wavelength", 0.0) > 0 ? name + "nm" : "row " + std::to_string(r.at("line").get<int>()),
                   number_at(r, "mu_a"), number_at(r, "mu_s_prime") / (1 - g), g});
  }
  return out;
}

// at(), never the const operator[]: on a missing key that is undefined behaviour (found by the
// mutation test under the sanitizers); at() throws, and the caller names the file.
std::string from_fit(const nlohmann::json& fit, const std::string& fit_file, const std::string& name,
                     std::optional<double> eta_given, const std::string& source) {
  const bool rxt = fit.is_object() && fit.contains("rows") && fit.contains("header");
  if (!fit.is_object() || (!rxt && fit.value("source", "") != "fit"))
    throw FileError(fit_file, 0, "$.source: expected \"fit\" (the output of 'bssrdf fit ... -f json')");
  std::vector<ImportedChannel> channels;
  std::string unit = "mm";
  double eta = NAN;
  if (rxt) {
    channels = rxt_rows(fit, unit, eta);
    if (channels.empty()) throw FileError(fit_file, 0, "$.rows: expected a non-empty array");
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
              {"channels", names},
              {"notes", {"Imported from " + fit_file + " by 'bssrdf materials import'."}},
              {"materials", {{{"name", name}, {"eta", eta}, {"sigma_a", sigma_a}, {"sigma_s", sigma_s}, {"g", g}}}}};
  return doc.dump(2) + "\n";
}

}  // namespace

std::string materials_file_from_fit(const std::string& fit_text, const std::string& fit_file, const std::string& name,
                                    std::optional<double> eta, const std::string& source) {
  const nlohmann::json fit = parse_json_document(fit_text, fit_file);
  try {
    return from_fit(fit, fit_file, name, eta, source);
  } catch (const nlohmann::json::exception& e) {  // a field of the wrong type (a string where a number belongs)
    const std::string what = e.what();
    throw FileError(fit_file, 0, "not the output of 'bssrdf fit ... -f json': " + what.substr(what.find(' ') + 1));
  }
}

}  // namespace bssrdf
