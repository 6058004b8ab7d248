#include "bssrdf/profile_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/models/layered.hpp"
#include "bssrdf/models/multipole.hpp"
#include "bssrdf/models/normalized_diffusion.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"
#include "bssrdf/spectral/colour_medium.hpp"

namespace bssrdf {

namespace {

// The coefficients and distances of one channel in the output unit (mm per unit given).
ChannelProfile channel_coefficients(const std::string& name, const Reduced<double>& m, double mm) {
  ChannelProfile ch;
  ch.name = name;
  ch.sigma_a = m.sigma_a * mm;
  ch.sigma_s = m.sigma_s * mm;
  ch.g = m.g;
  ch.sigma_s_prime = m.sigma_s_prime * mm;
  ch.albedo_prime = m.albedo_prime;
  ch.transport_mfp = m.ell / mm;
  ch.diffuse_mfp = m.sigma_tr > 0 ? m.ell_d / mm : std::numeric_limits<double>::infinity();
  return ch;
}

// The postcondition of every report: no negative or infinite profile. Far in the tail the
// multipole's dipole pairs cancel to rounding noise of either sign: that is 0, and a note says so.
// Anything else is refused (an infinite value names the radius; a real negative value points to the
// Monte Carlo reference).
void settle_rounding_tail(ProfileReport& report) {
  for (auto& ch : report.channels) {
    const auto settle = [&](std::vector<double>& values, const char* what) {
      double peak = 0;
      for (double v : values) peak = std::isfinite(v) ? std::max(peak, std::abs(v)) : peak;
      double first_rounded = -1;
      for (std::size_t i = 0; i < values.size(); ++i) {
        const double r = ch.profile.radius[i];
        if (!std::isfinite(values[i]))
          throw InvalidInput(
              "radii", format_number(r),
              std::string("> 0 for ") + report.model + ": its " + what + " is infinite at r = " + format_number(r));
        if (values[i] >= 0) continue;
        if (-values[i] > 1e-9 * peak)
          throw InvalidInput(std::string(what) + "[" + ch.name + "] at r = " + format_number(r) + ": the model gives " +
                             format_number(values[i]) + " here; use 'bssrdf reference' (Monte Carlo)");
        if (first_rounded < 0) first_rounded = r;
        values[i] = 0;
      }
      if (first_rounded >= 0)
        ch.validity.push_back({Severity::note, "rounding_tail",
                               std::string(what) + " below 1e-9 of its peak from r = " + format_number(first_rounded) +
                                   " is the rounding noise of the dipole-pair sum: written as 0"});
    };
    settle(ch.profile.value, "R(r)");
    settle(ch.transmittance, "T(r)");
  }
}

}  // namespace

std::vector<double> default_radii_mm(const Medium& medium, const Model& model, std::size_t samples) {
  // Without scattering R(r) is zero: there is no profile, hence no radius range, to sample.
  if (std::all_of(medium.sigma_s.begin(), medium.sigma_s.end(), [](double s) { return s == 0; }))
    throw InvalidInput("sigma_s", "0 in every channel",
                       "> 0 in some channel (without scattering there is no diffuse profile)");
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    r_min = std::min(r_min, 1e-3 * m.ell);
    r_max = std::max(r_max, model.radius_for_fraction(m, 0.999));
  }
  return log_spaced(r_min, r_max, samples);
}

ProfileReport compute_profile_report(const Medium& medium, const Model& model, const std::vector<double>& radii_mm,
                                     LengthUnit unit) {
  medium.validate();
  ProfileReport report;
  report.model = model.name();
  report.model_description = model.description();
  report.includes_single_scattering = model.includes_single_scattering();
  report.unit = unit;
  report.eta = medium.eta;
  const double mm = millimetres_per(unit);  // lengths: x_unit = x_mm / mm
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    ChannelProfile ch = channel_coefficients(medium.channel_names[c], m, mm);
    ch.total_reflectance = model.total_reflectance(m);
    ch.radius_99 = model.radius_for_fraction(m, 0.99) / mm;
    const auto sampled = model.sample(m, radii_mm);
    for (std::size_t i = 0; i < sampled.size(); ++i) {
      ch.profile.radius.push_back(sampled.radius[i] / mm);
      ch.profile.value.push_back(sampled.value[i] * mm * mm);  // per area: 1/mm^2 -> 1/unit^2
    }
    ch.validity = model.validity(m);
    if (const auto* qd = dynamic_cast<const quantized_diffusion::Model*>(&model)) {
      const auto mixture = qd->gaussians(m);
      for (double v : mixture.variance) ch.gaussian_variance.push_back(v / (mm * mm));
      ch.gaussian_weight = mixture.weight;
    }
    if (const auto* burley = dynamic_cast<const normalized_diffusion::Model*>(&model)) {
      ch.burley_d = burley->shape_parameter(m) / mm;
      ch.surface_albedo = burley->surface_albedo(m);
    }
    if (const auto* slab = dynamic_cast<const multipole::Model*>(&model)) {
      ch.total_transmittance = slab->total_transmittance(m);
      for (double r : radii_mm) ch.transmittance.push_back(slab->transmittance(m, r) * mm * mm);
      ch.dipole_pairs = slab->dipole_pairs(m);
      report.thickness = slab->thickness() / mm;
    }
    report.channels.push_back(std::move(ch));
  }
  settle_rounding_tail(report);
  return report;
}

std::vector<double> default_stack_radii_mm(const LayerStack& stack, std::size_t samples) {
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0;
  for (std::size_t c = 0; c < stack.channels(); ++c) {
    const layered::Stack model(stack, c);
    r_min = std::min(r_min, 1e-3 * model.medium(0).ell);
    r_max = std::max(r_max, model.radius_for_fraction(0.999));
  }
  return log_spaced(r_min, r_max, samples);
}

ProfileReport compute_stack_report(const LayerStack& stack, const std::vector<double>& radii_mm, LengthUnit unit) {
  stack.validate();
  ProfileReport report;
  report.model = "multipole";
  report.model_description =
      "multipole layers (Donner & Jensen 2005) combined by the adding equations on their Hankel spectra, "
      "classical D and A, multiple scattering only";
  report.unit = unit;
  report.eta = stack.layers[0].n / stack.ambient_above;
  report.layers = stack;
  const double mm = millimetres_per(unit);
  for (std::size_t c = 0; c < stack.channels(); ++c) {
    const layered::Stack model(stack, c);
    const auto& m = model.medium(0);
    ChannelProfile ch = channel_coefficients(stack.channel_names[c], m, mm);
    ch.total_reflectance = model.total_reflectance();
    ch.radius_99 = model.radius_for_fraction(0.99) / mm;
    for (double r : radii_mm) {
      ch.profile.radius.push_back(r / mm);
      ch.profile.value.push_back(model.reflectance(r) * mm * mm);
    }
    if (!model.semi_infinite()) {
      ch.total_transmittance = model.total_transmittance();
      for (double r : radii_mm) ch.transmittance.push_back(model.transmittance(r) * mm * mm);
    }
    ch.validity = model.validity();
    report.channels.push_back(std::move(ch));
  }
  settle_rounding_tail(report);
  return report;
}

namespace {

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string in_column(double v, int width, int precision = 5) {
  char buffer[64];
  if (!std::isfinite(v)) {
    std::snprintf(buffer, sizeof buffer, "%*s", width, v > 0 ? "inf" : "nan");
  } else {
    std::snprintf(buffer, sizeof buffer, "%*.*g", width, precision, v);
  }
  // A value as wide as its column still gets a space before it (0.00018102 after g).
  return std::string(buffer[0] == ' ' ? "" : " ") + buffer;
}

}  // namespace

std::string to_json(const ProfileReport& report) {
  nlohmann::json doc;
  doc["tool"] = std::string("bssrdf ") + BSSRDF_VERSION;
  doc["model"] = report.model;
  doc["model_description"] = report.model_description;
  if (!report.model_choice.empty()) doc["model_choice"] = report.model_choice;
  doc["includes_single_scattering"] = report.includes_single_scattering;
  doc["unit"] = std::string(symbol(report.unit));
  doc["reflectance_unit"] = "1/" + std::string(symbol(report.unit)) + "^2";
  doc["normalization"] = "per_entered_flux";
  doc["eta"] = report.eta;
  if (report.material) {
    doc["material"] = {
        {"name", report.material->name}, {"source", report.material->source}, {"citation", report.material->citation}};
  } else {
    doc["material"] = nullptr;
  }
  if (report.colour)
    doc["colour"] = {{"observer", report.colour->observer},
                     {"illuminant", report.colour->illuminant},
                     {"space", report.colour->space},
                     {"wavelength_nm", report.colour->wavelength_nm}};
  doc["geometry"] = report.layers ? "layers" : report.thickness ? "slab" : "semi-infinite";
  doc["thickness"] = report.thickness ? nlohmann::json(*report.thickness) : nlohmann::json(nullptr);
  if (report.layers) {
    const double mm = millimetres_per(report.unit);
    doc["ambient_above"] = report.layers->ambient_above;
    doc["ambient_below"] = report.layers->ambient_below;
    doc["layers"] = nlohmann::json::array();
    for (const auto& layer : report.layers->layers)
      doc["layers"].push_back(
          {{"name", layer.name}, {"thickness", number_or_null(layer.thickness / mm)}, {"n", layer.n}});
  }
  doc["channels"] = nlohmann::json::array();
  for (const auto& ch : report.channels) {
    nlohmann::json c;
    c["name"] = ch.name;
    if (!report.colour) {  // a colour channel has no coefficients of its own
      c["sigma_a"] = ch.sigma_a;
      c["sigma_s"] = ch.sigma_s;
      c["g"] = ch.g;
      c["sigma_s_prime"] = ch.sigma_s_prime;
      c["albedo_prime"] = ch.albedo_prime;
      c["transport_mfp"] = ch.transport_mfp;
      c["diffuse_mfp"] = number_or_null(ch.diffuse_mfp);
    }
    c["total_reflectance"] = ch.total_reflectance;
    c["radius_99"] = number_or_null(ch.radius_99);
    c["radius"] = ch.profile.radius;
    c["reflectance"] = ch.profile.value;
    if (!ch.gaussian_variance.empty())
      c["gaussians"] = {{"variance", ch.gaussian_variance}, {"weight", ch.gaussian_weight}};
    if (ch.burley_d > 0) {
      c["burley_d"] = ch.burley_d;
      c["surface_albedo"] = ch.surface_albedo;
    }
    if (ch.total_transmittance) {
      c["total_transmittance"] = *ch.total_transmittance;
      c["transmittance"] = ch.transmittance;
    }
    if (ch.dipole_pairs > 0) c["dipole_pairs"] = ch.dipole_pairs;
    c["validity"] = nlohmann::json::array();
    for (const auto& note : ch.validity)
      c["validity"].push_back(
          {{"severity", std::string(to_string(note.severity))}, {"code", note.code}, {"message", note.message}});
    doc["channels"].push_back(std::move(c));
  }
  return doc.dump(2) + "\n";
}

std::string to_csv(const ProfileReport& report) {
  std::ostringstream out;
  // Which model produced the numbers, and why when it was not the exact one (read_profile_csv skips it).
  out << "# model: " << report.model << '\n';
  if (!report.model_choice.empty()) out << "# model_choice: " << report.model_choice << '\n';
  if (report.colour) out << "# colour: " << spectral::describe(*report.colour) << '\n';
  const std::string u(symbol(report.unit));
  out << "radius_" << u;
  for (const auto& ch : report.channels) out << ',' << ch.name << "_per_" << u << "2";
  for (const auto& ch : report.channels)
    if (ch.total_transmittance) out << ',' << ch.name << "_transmittance_per_" << u << "2";
  out << '\n';
  if (report.channels.empty()) return out.str();
  const auto& radii = report.channels.front().profile.radius;
  for (std::size_t i = 0; i < radii.size(); ++i) {
    out << format_number(radii[i]);
    for (const auto& ch : report.channels) out << ',' << format_number(ch.profile.value[i]);
    for (const auto& ch : report.channels)
      if (ch.total_transmittance) out << ',' << format_number(ch.transmittance[i]);
    out << '\n';
  }
  return out.str();
}

std::string to_table(const ProfileReport& report) {
  std::ostringstream out;
  const std::string u(symbol(report.unit));
  out << "model     " << report.model << ": " << report.model_description << '\n';
  if (!report.model_choice.empty()) out << "choice    " << report.model_choice << '\n';
  if (report.material) out << "material  " << report.material->name << " (" << report.material->source << ")\n";
  out << "eta       " << format_number(report.eta) << "\n";
  if (report.colour) out << "colour    " << spectral::describe(*report.colour) << "; coefficients are per wavelength\n";
  if (report.thickness) out << "slab      thickness " << format_number(*report.thickness) << ' ' << u << "\n";
  if (report.layers) {
    const double mm = millimetres_per(report.unit);
    out << "layers    ambient above n = " << format_number(report.layers->ambient_above)
        << ", below n = " << format_number(report.layers->ambient_below) << "\n";
    for (const auto& layer : report.layers->layers)
      out << "          " << (layer.name.empty() ? "(unnamed)" : layer.name) << ": n = " << format_number(layer.n)
          << ", thickness "
          << (layer.thickness == kSemiInfinite ? "semi-infinite" : format_number(layer.thickness / mm) + " " + u)
          << "\n";
    out << "          (the channel table shows the top layer's coefficients)\n";
  }
  out << "units     radius in " << u << ", R(r) in 1/" << u << "^2 per unit entered flux"
      << (report.includes_single_scattering ? "" : " (multiple scattering only)") << "\n\n";
  out << "channel  sigma_a     sigma_s'    g        alpha'    ell (" << u << ")   R_total   r_99 (" << u << ")\n";
  for (const auto& ch : report.channels)
    out << std::string(ch.name).append(std::max<std::size_t>(1, 8 - ch.name.size()), ' ')
        << in_column(ch.sigma_a, 10, 4) << in_column(ch.sigma_s_prime, 10, 4) << in_column(ch.g, 7, 3)
        << in_column(ch.albedo_prime, 10, 5) << in_column(ch.transport_mfp, 11, 4)
        << in_column(ch.total_reflectance, 10, 5) << in_column(ch.radius_99, 11, 4)
        << (ch.total_transmittance ? "   T_total " + in_column(*ch.total_transmittance, 9, 5) : std::string())
        << (ch.dipole_pairs > 0 ? "   pairs " + std::to_string(ch.dipole_pairs) : std::string()) << '\n';
  const std::string radius_header = "radius (" + u + ")";
  out << '\n' << std::string(13 - std::min<std::size_t>(12, radius_header.size()), ' ') << radius_header;
  for (const auto& ch : report.channels)
    out << std::string(14 - std::min<std::size_t>(13, ch.name.size()), ' ') << ch.name;
  for (const auto& ch : report.channels)
    if (ch.total_transmittance)
      out << std::string(14 - std::min<std::size_t>(13, ch.name.size() + 2), ' ') << "T " << ch.name;
  out << '\n';
  if (!report.channels.empty()) {
    const auto& radii = report.channels.front().profile.radius;
    for (std::size_t i = 0; i < radii.size(); ++i) {
      out << in_column(radii[i], 13, 5);
      for (const auto& ch : report.channels) out << in_column(ch.profile.value[i], 14, 5);
      for (const auto& ch : report.channels)
        if (ch.total_transmittance) out << in_column(ch.transmittance[i], 14, 5);
      out << '\n';
    }
  }
  bool header = false;
  for (const auto& ch : report.channels)
    for (const auto& note : ch.validity) {
      if (note.severity == Severity::note) continue;
      if (!header) out << "\nvalidity\n";
      header = true;
      out << "  " << ch.name << ": " << to_string(note.severity) << " [" << note.code << "] " << note.message << '\n';
    }
  return out.str();
}

}  // namespace bssrdf
