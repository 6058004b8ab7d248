#include "bssrdf/medium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "bssrdf/error.hpp"

namespace bssrdf {

std::vector<std::string> default_channel_names(std::size_t count) {
  if (count == 3) return {"R", "G", "B"};
  std::vector<std::string> names;
  for (std::size_t i = 0; i < count; ++i) names.push_back(std::string("c").append(std::to_string(i)));
  return names;
}

std::vector<std::string> wavelength_channel_names(const std::vector<double>& wavelength_nm) {
  std::vector<std::string> names;
  for (double nm : wavelength_nm) names.push_back(format_number(nm) + "nm");
  return names;
}

void Medium::validate() const {
  const std::size_t n = sigma_a.size();
  if (n == 0) throw InvalidInput("sigma_a", "(no values)", "at least one channel");
  auto check_count = [n](const char* field, std::size_t count) {
    if (count != n)
      throw InvalidInput(std::string(field) + ": " + std::to_string(count) + " channels given, but sigma_a has " +
                         std::to_string(n));
  };
  check_count("sigma_s", sigma_s.size());
  check_count("g", g.size());
  check_count("channel names", channel_names.size());

  std::set<std::string> seen;
  for (const auto& name : channel_names) {
    if (name.empty()) throw InvalidInput("channel name", "''", "a non-empty name");
    if (!seen.insert(name).second)
      throw InvalidInput("channel name", "'" + name + "'", "unique names (it is repeated)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::string tag = "[" + channel_names[i] + "]";
    const std::string coefficient_range =
        ">= 0 and finite, at most " + format_number(kMaxCoefficient) + " (a 1 nm mean free path in mm)";
    if (!(sigma_a[i] >= 0 && sigma_a[i] <= kMaxCoefficient))
      throw InvalidInput("sigma_a" + tag, format_number(sigma_a[i]), coefficient_range);
    if (!(sigma_s[i] >= 0 && sigma_s[i] <= kMaxCoefficient))
      throw InvalidInput("sigma_s" + tag, format_number(sigma_s[i]), coefficient_range);
    if (sigma_a[i] + sigma_s[i] <= 0)
      throw InvalidInput("sigma_a" + tag + " + sigma_s" + tag, "0", "> 0 (the medium must absorb or scatter)");
    if (!(g[i] > -1 && g[i] < 1)) throw InvalidInput("g" + tag, format_number(g[i]), "-1 < g < 1");
  }
  if (!wavelength_nm.empty()) {
    check_count("wavelengths", wavelength_nm.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (!(wavelength_nm[i] >= kMinWavelength && wavelength_nm[i] <= kMaxWavelength))
        throw InvalidInput("wavelengths[" + std::to_string(i) + "]", format_number(wavelength_nm[i]),
                           format_number(kMinWavelength) + " to " + format_number(kMaxWavelength) + " nm");
      if (i > 0 && !(wavelength_nm[i] > wavelength_nm[i - 1]))
        throw InvalidInput("wavelengths[" + std::to_string(i) + "]", format_number(wavelength_nm[i]),
                           "strictly increasing (after " + format_number(wavelength_nm[i - 1]) + " nm)");
    }
  }
  if (!(eta >= kMinRefractiveIndex && eta <= kMaxRefractiveIndex))
    throw InvalidInput(
        "eta", format_number(eta),
        format_number(kMinRefractiveIndex) + " to " + format_number(kMaxRefractiveIndex) + " (n_medium / n_outside)");
}

Medium Medium::single_channel(double sigma_a, double sigma_s, double g, double eta) {
  Medium m;
  m.channel_names = {"x"};
  m.sigma_a = {sigma_a};
  m.sigma_s = {sigma_s};
  m.g = {g};
  m.eta = eta;
  return m;
}

Reduced<double> Medium::reduced(std::size_t channel) const {
  return reduce(sigma_a.at(channel), sigma_s.at(channel), g.at(channel), eta);
}

TransportMfpRange transport_mfp_range(const Medium& medium) {
  TransportMfpRange range{std::numeric_limits<double>::infinity(), 0};
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const double ell = medium.reduced(c).ell;
    range.min = std::min(range.min, ell);
    range.max = std::max(range.max, ell);
  }
  return range;
}

}  // namespace bssrdf
