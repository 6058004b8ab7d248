#include "bssrdf/fit/fit_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"

namespace bssrdf {

const FitParameter* FitReport::find(const std::string& name, const std::string& channel) const {
  for (const auto& p : parameters)
    if (p.name == name && p.channel == channel) return &p;
  return nullptr;
}

namespace {
nlohmann::json estimate(const FitParameter& p) {
  nlohmann::json e = {{"value", p.value}};
  e["stderr"] = std::isfinite(p.standard_error) && p.standard_error > 0 ? nlohmann::json(p.standard_error)
                                                                        : nlohmann::json(nullptr);
  if (!p.unit.empty()) e["unit"] = p.unit;
  return e;
}
}  // namespace

std::string FitReport::to_json() const {
  nlohmann::json doc;
  doc["tool"] = std::string("bssrdf ") + BSSRDF_VERSION;
  doc["source"] = "fit";
  doc["kind"] = kind;
  doc["model"] = model;
  if (!model_choice.empty()) doc["model_choice"] = model_choice;
  doc["data"] = data_source;
  nlohmann::json shared = nlohmann::json::object();
  std::vector<std::string> order;
  std::map<std::string, nlohmann::json> channels;
  for (const auto& p : parameters) {
    if (p.channel.empty()) {
      shared[p.name] = estimate(p);
      continue;
    }
    if (!channels.count(p.channel)) {
      order.push_back(p.channel);
      channels[p.channel] = {{"name", p.channel}};
    }
    channels[p.channel][p.name] = estimate(p);
  }
  doc["shared"] = shared;
  if (std::isfinite(eta)) {  // a complete medium: unit, eta, and g and sigma_s per channel
    doc["unit"] = length_unit;
    const FitParameter* fitted_eta = find("eta");
    doc["eta"] = fitted_eta ? estimate(*fitted_eta) : nlohmann::json{{"value", eta}, {"stderr", nullptr}};
    doc["eta"]["fitted"] = fitted_eta != nullptr;
    for (std::size_t i = 0; i < order.size(); ++i) {
      auto& c = channels[order[i]];
      const FitParameter* sa = find("sigma_a", order[i]);
      const FitParameter* ssp = find("sigma_s_prime", order[i]);
      if (!sa || !ssp) continue;
      const FitParameter* fitted_g = find("g", order[i]);
      const double g_value = fitted_g ? fitted_g->value : i < g.size() ? g[i] : 0.0;
      const double g_se = fitted_g && std::isfinite(fitted_g->standard_error) ? fitted_g->standard_error : 0.0;
      if (!fitted_g) c["g"] = {{"value", g_value}, {"stderr", nullptr}};
      c["g"]["fitted"] = fitted_g != nullptr && g_se > 0;
      // sigma_s = sigma_s' / (1 - g); its 1-sigma from those of sigma_s' and g, correlation neglected.
      const double s = ssp->value / (1 - g_value);
      const double se = std::hypot(ssp->standard_error / (1 - g_value), s * g_se / (1 - g_value));
      c["sigma_s"] = estimate({"sigma_s", order[i], s, se, ssp->unit});
    }
  }
  doc["channels"] = nlohmann::json::array();
  for (const auto& name : order) doc["channels"].push_back(channels[name]);
  doc["residual_rms"] = residual_rms;
  doc["relative_rms"] = relative_rms;
  doc["iterations"] = iterations;
  doc["termination"] = termination;
  doc["converged"] = converged;
  doc["seconds"] = seconds;
  doc["warnings"] = warnings;
  doc["residuals"] = nlohmann::json::array();
  for (const auto& r : residuals)
    doc["residuals"].push_back(
        {{"channel", r.channel}, {"x", r.x}, {"measured", r.measured}, {"model", r.model}, {"weighted", r.weighted}});
  return doc.dump(2) + "\n";
}

std::string FitReport::full_report() const {
  std::ostringstream out;
  out << "bssrdf fit " << kind << " — model " << model << "\n";
  if (!model_choice.empty()) out << "model choice: " << model_choice << "\n";
  out << "data      " << data_source << "\n";
  out << "solver    " << termination << (converged ? "" : " (NOT converged)") << ", " << iterations << " iterations, "
      << format_number(std::round(seconds * 1e6) / 1e3) << " ms\n";
  out << "residuals " << residuals.size() << " points, weighted RMS "
      << format_number(std::round(residual_rms * 1e4) / 1e4) << ", relative RMS "
      << format_number(std::round(relative_rms * 1e6) / 1e4) << " %\n\n";
  out << "parameter          channel   value          1-sigma        unit\n";
  for (const auto& p : parameters) {
    // An uncertainty that could not be computed (or an exact inversion) is "n/a", never nan or 0.
    char sigma[32] = "n/a";
    if (std::isfinite(p.standard_error) && p.standard_error > 0)
      std::snprintf(sigma, sizeof sigma, "%.3g", p.standard_error);
    char line[160];
    std::snprintf(line, sizeof line, "%-18s %-9s %-14.6g %-14s %s\n", p.name.c_str(),
                  p.channel.empty() ? "-" : p.channel.c_str(), p.value, sigma, p.unit.c_str());
    out << line;
  }
  if (!warnings.empty()) {
    out << "\nwarnings\n";
    for (const auto& w : warnings) out << "  " << w << "\n";
  }
  return out.str();
}

}  // namespace bssrdf
