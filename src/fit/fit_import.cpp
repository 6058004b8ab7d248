#include "bssrdf/fit/fit_import.hpp"

#include <nlohmann/json.hpp>
#include <vector>

#include "../io/data_file.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

using json = nlohmann::ordered_json;

// at(), never the const operator[]: on a missing key that is undefined behaviour (found by the
// mutation test under the sanitizers); at() throws, and the caller names the file.
std::string from_fit(const nlohmann::json& fit, const std::string& fit_file, const std::string& name,
                     std::optional<double> eta_given, const std::string& source) {
  if (!fit.is_object() || fit.value("source", "") != "fit")
    throw FileError(fit_file, 0, "$.source: expected \"fit\" (the output of 'bssrdf fit ... -f json')");
  if (!fit.contains("channels") || !fit.at("channels").is_array() || fit.at("channels").empty())
    throw FileError(fit_file, 0, "$.channels: expected a non-empty array");
  double eta = 0;
  if (eta_given)
    eta = *eta_given;
  else if (fit.contains("shared") && fit.at("shared").contains("eta"))
    eta = fit.at("shared").at("eta").at("value").get<double>();
  else
    throw InvalidInput("eta: the fit result has no eta; give the one the fit assumed");
  std::vector<std::string> channels;
  std::vector<double> sigma_a, sigma_s_prime;
  std::string unit;
  for (std::size_t i = 0; i < fit.at("channels").size(); ++i) {
    const auto& c = fit.at("channels").at(i);
    const std::string where = "$.channels[" + std::to_string(i) + "]";
    for (const char* key : {"sigma_a", "sigma_s_prime"})
      if (!c.contains(key) || !c.at(key).contains("value") || !c.at(key).at("value").is_number())
        throw FileError(fit_file, 0,
                        where + "." + key +
                            ": missing (only fits of sigma_a and sigma_s' - profile, albedo, "
                            "slab - give a material)");
    // std::string("c") + ...: "c" + std::string&& trips GCC 12's -Wrestrict false positive (GCC bug 105329).
    channels.push_back(c.value("name", std::string("c") + std::to_string(i)));
    sigma_a.push_back(c.at("sigma_a").at("value").get<double>());
    sigma_s_prime.push_back(c.at("sigma_s_prime").at("value").get<double>());
    const std::string u = c.at("sigma_a").value("unit", "1/mm");
    if (u.rfind("1/", 0) != 0) throw FileError(fit_file, 0, where + ".sigma_a.unit: '" + u + "' is not 1/LENGTH");
    unit = u.substr(2);
  }
  json doc = {
      {"format", "bssrdf-materials"},
      {"version", 1},
      {"source", source},
      {"citation", "bssrdf fit " + fit.value("kind", std::string("?")) + " (" + fit.value("model", std::string("?")) +
                       ") of " + fit.value("data", std::string("?")) + ", " + fit.value("tool", std::string(""))},
      {"unit", unit},
      {"channels", channels},
      {"notes",
       {"Imported from " + fit_file +
        " by 'bssrdf materials import'; g was not fitted, so the entry "
        "gives sigma_s_prime (used with g = 0)."}},
      {"materials", {{{"name", name}, {"eta", eta}, {"sigma_a", sigma_a}, {"sigma_s_prime", sigma_s_prime}}}}};
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
