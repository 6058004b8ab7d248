// The one parser of a medium on the command line (MediumOptions in cli_common.hpp): --material, or
// --sigma-a with --sigma-s or --sigma-s-prime, --g, --channels, --eta, in --unit.
#include <algorithm>
#include <string>
#include <vector>

#include "bssrdf/error.hpp"
#include "bssrdf/spectral/resample.hpp"
#include "bssrdf/text.hpp"
#include "cli_common.hpp"

namespace bssrdf::cli {
namespace {

// One value per channel: a single value applies to every channel.
std::vector<double> per_channel(std::vector<double> values, std::size_t channels, const std::string& field,
                                const std::string& reference_field) {
  if (values.size() == 1 && channels > 1) return std::vector<double>(channels, values[0]);
  if (values.size() != channels)
    throw InvalidInput(field + ": " + std::to_string(values.size()) + " values given, but " + reference_field +
                       " has " + std::to_string(channels) + " channels (give one value per channel, or one for all)");
  return values;
}

}  // namespace

void MediumOptions::add_coefficients_to(CLI::App& app) {
  auto* sa = app.add_option("--sigma-a", sigma_a, "Absorption coefficient per channel, 1/unit (e.g. 0.032,0.17,0.48)");
  auto* ss = app.add_option("--sigma-s", sigma_s, "Scattering coefficient per channel, 1/unit (with --g)");
  auto* ssp = app.add_option("--sigma-s-prime", sigma_s_prime,
                             "Reduced scattering sigma_s (1 - g) per channel, 1/unit, instead of --sigma-s");
  ss->excludes(ssp);
  app.add_option("--g", g, "Henyey-Greenstein anisotropy per channel (or one for all), -1 < g < 1 [0]");
  app.add_option("--channels", channels, "Channel names, comma-separated [R,G,B for three]");
  app.add_option("--eta", eta, "Relative index of refraction n_medium/n_outside [1.3, or the material's]");
  app.add_option("--wavelengths", wavelengths,
                 "A spectral medium: the channels' wavelengths in nm, increasing (one coefficient per wavelength or "
                 "one for all); with a spectral --material, resamples it (linear in wavelength)");
  (void)sa;
}

void MediumOptions::add_to(CLI::App& app) {
  auto* mat = app.add_option("--material,-m", material, "Material from the database (case-insensitive), e.g. Skin1");
  add_coefficients_to(app);
  app.add_option("--unit", unit, "Length unit of coefficients, radii and outputs: um, mm, cm, m [mm]");
  app.add_option("--db", db, "Your own materials directory or file, added to the bundled database");
  for (const char* name : {"--sigma-a", "--sigma-s", "--sigma-s-prime", "--g", "--channels"})
    mat->excludes(app.get_option(name));
}

MediumOptions::Resolved MediumOptions::resolve() const {
  Resolved out;
  out.unit = parse_length_unit(unit, "--unit");
  if (!material.empty()) {
    std::optional<MaterialDatabase> own;
    const MaterialDatabase& database = loaded ? *loaded : own.emplace(MaterialDatabase::load_with_user(db));
    out.material = database.find(material);
    out.medium = out.material->medium;
    if (!wavelengths.empty())
      out.medium = spectral::resample(out.medium, parse_number_list(wavelengths, "--wavelengths"));
  } else {
    if (sigma_a.empty() || (sigma_s.empty() && sigma_s_prime.empty()))
      throw InvalidInput("medium: give --material NAME, or --sigma-a with --sigma-s (or --sigma-s-prime)");
    // A spectral medium has one channel per wavelength, each coefficient given per wavelength or once.
    if (!wavelengths.empty()) out.medium.wavelength_nm = parse_number_list(wavelengths, "--wavelengths");
    const std::string count_from = wavelengths.empty() ? "--sigma-a" : "--wavelengths";
    const auto a = parse_number_list(sigma_a, "--sigma-a");
    const std::size_t n = wavelengths.empty() ? a.size() : out.medium.wavelength_nm.size();
    out.medium.sigma_a = per_channel(a, n, "--sigma-a", count_from);
    out.medium.g =
        g.empty() ? std::vector<double>(n, 0.0) : per_channel(parse_number_list(g, "--g"), n, "--g", count_from);
    // One scattering value per absorption value: "--sigma-a 0,1 --sigma-s 10" (a decimal comma) must
    // not quietly become two channels.
    const std::string scattering = sigma_s.empty() ? "--sigma-s-prime" : "--sigma-s";
    auto s = parse_number_list(sigma_s.empty() ? sigma_s_prime : sigma_s, scattering);
    if (!wavelengths.empty()) s = per_channel(s, n, scattering, count_from);
    if (s.size() != n)
      throw InvalidInput(scattering + ": " + std::to_string(s.size()) +
                         (s.size() == 1 ? " value given" : " values given") + ", but --sigma-a has " +
                         std::to_string(n) +
                         " channels (one value per channel; the comma separates channels, the decimal point is '.')");
    out.medium.sigma_s = s;
    if (!sigma_s_prime.empty())  // sigma_s = sigma_s' / (1 - g); g < 1 is checked below with the medium
      for (std::size_t c = 0; c < n; ++c)
        if (out.medium.g[c] < 1) out.medium.sigma_s[c] = s[c] / (1 - out.medium.g[c]);
    if (channels.empty()) {
      out.medium.channel_names =
          wavelengths.empty() ? default_channel_names(n) : wavelength_channel_names(out.medium.wavelength_nm);
    } else {
      std::string rest = channels;
      std::vector<std::string> names;
      std::size_t start = 0;
      while (true) {
        const auto comma = rest.find(',', start);
        names.push_back(trim(rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      if (names.size() != n)
        throw InvalidInput("--channels: " + std::to_string(names.size()) + " names given, but --sigma-a has " +
                           std::to_string(n) + " channels");
      out.medium.channel_names = names;
    }
    out.medium.eta = 1.3;
  }
  if (!eta.empty()) out.medium.eta = parse_number(eta, "--eta");
  try {
    out.medium.validate();  // still in the user's unit, so messages quote the numbers typed
  } catch (const InvalidInput& e) {
    // Name the option the user typed ("--sigma-a[G] = -1: ..."), not the library's field.
    std::string message = e.what();
    for (const std::string field : {"sigma_a", "sigma_s", "g", "eta", "wavelengths"}) {
      if (message.rfind(field, 0) != 0) continue;
      const char next = message[field.size()];
      if (next != '[' && next != ' ') continue;
      std::string option = "--" + field;
      std::replace(option.begin(), option.end(), '_', '-');
      if (field == "sigma_s" && !sigma_s_prime.empty()) option = "sigma_s = --sigma-s-prime / (1 - g), sigma_s";
      message =
          (out.material ? "material " + out.material->name + ": " + field : option) + message.substr(field.size());
      if (!out.material) {
        const auto plus = message.find(" + sigma_s[");
        if (plus != std::string::npos) message.replace(plus, 11, " + --sigma-s[");
      }
      break;
    }
    throw InvalidInput(message);
  }
  if (!out.material) {
    // Coefficients arrive in 1/unit; the library works in 1/mm.
    for (auto& v : out.medium.sigma_a) v = coefficient_to_per_mm(v, out.unit);
    for (auto& v : out.medium.sigma_s) v = coefficient_to_per_mm(v, out.unit);
  }
  return out;
}

}  // namespace bssrdf::cli
