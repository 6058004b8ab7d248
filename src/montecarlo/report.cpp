// The Monte Carlo result for people (report(), in the spirit of Ceres' Summary::FullReport) and
// for scripts (JSON, CSV). Lengths are converted to the requested unit here, at the edge.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/montecarlo.hpp"

namespace bssrdf {
namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json estimate_json(const Estimate& e) {
  return {{"value", number(e.value)}, {"stderr", number(e.standard_error)}};
}

std::vector<double> scaled(const std::vector<double>& v, double k) {
  std::vector<double> out(v);
  for (double& x : out) x *= k;
  return out;
}

nlohmann::json array(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}

// One normalisation of one channel. per_area: 1/mm^2 -> 1/unit^2; per_length: 1/mm -> 1/unit.
nlohmann::json channel_json(const ChannelResult& ch, const char* normalization, double mm) {
  const double per_area = mm * mm, per_length = mm;
  nlohmann::json c;
  c["normalization"] = normalization;
  c["specular_reflectance"] = ch.specular_reflectance;
  c["diffuse_reflectance"] = estimate_json(ch.diffuse_reflectance);
  c["total_transmittance"] = estimate_json(ch.total_transmittance);
  c["single_scattering_reflectance"] = estimate_json(ch.single_scattering_reflectance);
  c["unscattered_reflectance"] = estimate_json(ch.unscattered_reflectance);
  c["unscattered_transmittance"] = estimate_json(ch.unscattered_transmittance);
  c["absorbed"] = estimate_json(ch.absorbed);
  c["lost"] = ch.lost;
  c["reflectance"] = array(scaled(ch.reflectance, per_area));
  c["reflectance_stderr"] = array(scaled(ch.reflectance_stderr, per_area));
  c["reflectance_beyond_r_max"] = ch.reflectance_beyond;
  if (!ch.transmittance.empty()) {
    c["transmittance"] = array(scaled(ch.transmittance, per_area));
    c["transmittance_stderr"] = array(scaled(ch.transmittance_stderr, per_area));
    c["transmittance_beyond_r_max"] = ch.transmittance_beyond;
  }
  if (!ch.absorbed_by_depth.empty()) {
    c["absorbed_by_depth"] = array(scaled(ch.absorbed_by_depth, per_length));
    c["absorbed_by_depth_stderr"] = array(scaled(ch.absorbed_by_depth_stderr, per_length));
  }
  return c;
}

std::string fixed(double v, int width, int precision) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%*.*f", width, precision, v);
  return buffer;
}

std::string general(double v, int width = 12) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%*.6g", width, v);
  return buffer;
}

}  // namespace

std::string to_json(const MonteCarloResult& result, LengthUnit unit) {
  const double mm = millimetres_per(unit);
  const std::string u(symbol(unit));
  const auto& o = result.options;
  nlohmann::json doc;
  doc["tool"] = std::string("bssrdf ") + BSSRDF_VERSION;
  doc["method"] = "monte_carlo";
  doc["unit"] = u;
  doc["reflectance_unit"] = "1/" + u + "^2";
  doc["photons"] = o.photons;
  doc["seed"] = o.seed;
  doc["threads"] = result.threads;
  doc["batch_size"] = o.batch_size;
  doc["seconds"] = result.seconds;
  doc["photons_per_second"] = result.photons_per_second;
  if (result.ranks > 1) {  // MPI: the ranks and rank 0's communication
    doc["ranks"] = result.ranks;
    doc["communication_bytes"] = result.communication_bytes;
    doc["communication_seconds"] = result.communication_seconds;
  }
  doc["absorption_estimator"] = std::string(to_string(o.absorption));
  doc["roulette_threshold"] = o.roulette_threshold;
  doc["roulette_survival"] = o.roulette_survival;
  doc["bin_spacing"] = std::string(to_string(o.spacing));
  doc["bins"] = o.bins;
  doc["r_max"] = o.r_max / mm;
  if (o.spacing == BinSpacing::log) doc["r_min"] = o.r_min / mm;
  doc["radius"] = array(scaled(result.bin_radius, 1 / mm));
  doc["radius_inner"] = array(scaled(result.bin_inner, 1 / mm));
  doc["radius_outer"] = array(scaled(result.bin_outer, 1 / mm));
  if (!result.depth_inner.empty()) {
    doc["depth_inner"] = array(scaled(result.depth_inner, 1 / mm));
    doc["depth_outer"] = array(scaled(result.depth_outer, 1 / mm));
  }
  nlohmann::json stack;
  stack["ambient_above"] = result.stack.ambient_above;
  stack["ambient_below"] = result.stack.ambient_below;
  stack["layers"] = nlohmann::json::array();
  for (const Layer& layer : result.stack.layers) {
    stack["layers"].push_back({{"name", layer.name},
                               {"thickness", number(layer.thickness / mm)},
                               {"n", layer.n},
                               {"sigma_a", scaled(layer.sigma_a, mm)},
                               {"sigma_s", scaled(layer.sigma_s, mm)},
                               {"g", layer.g}});
  }
  doc["stack"] = stack;
  doc["channels"] = nlohmann::json::array();
  for (const ChannelResult& ch : result.channels) {
    nlohmann::json c = channel_json(ch, "per_incident_flux", mm);
    c["name"] = ch.name;
    c["interactions"] = ch.interactions;
    // The radius of each bin, repeated here so a channel object stands alone.
    c["radius"] = doc["radius"];
    c["per_entered_flux"] = channel_json(ch.per_entered_flux(), "per_entered_flux", mm);
    doc["channels"].push_back(std::move(c));
  }
  return doc.dump(2) + "\n";
}

std::string to_csv(const MonteCarloResult& result, LengthUnit unit) {
  const double mm = millimetres_per(unit);
  const std::string u(symbol(unit));
  std::ostringstream out;
  out << "# bssrdf Monte Carlo: R(r), T(r) in 1/" << u << "^2; 'incident' = per unit incident flux, "
      << "'entered' = per unit entered flux (divided by 1 - R_sp)\n";
  out << "radius_" << u << ",radius_inner_" << u << ",radius_outer_" << u;
  const bool transmission = !result.channels.empty() && !result.channels[0].transmittance.empty();
  for (const auto& ch : result.channels) {
    for (const char* norm : {"incident", "entered"}) {
      out << ',' << ch.name << "_R_" << norm << ',' << ch.name << "_R_" << norm << "_stderr";
      if (transmission) out << ',' << ch.name << "_T_" << norm << ',' << ch.name << "_T_" << norm << "_stderr";
    }
  }
  out << '\n';
  std::vector<ChannelResult> entered;
  for (const auto& ch : result.channels) entered.push_back(ch.per_entered_flux());
  for (std::size_t i = 0; i < result.bin_radius.size(); ++i) {
    out << format_number(result.bin_radius[i] / mm) << ',' << format_number(result.bin_inner[i] / mm) << ','
        << format_number(result.bin_outer[i] / mm);
    for (std::size_t c = 0; c < result.channels.size(); ++c) {
      for (const ChannelResult* ch : std::initializer_list<const ChannelResult*>{&result.channels[c], &entered[c]}) {
        out << ',' << format_number(ch->reflectance[i] * mm * mm) << ','
            << format_number(ch->reflectance_stderr[i] * mm * mm);
        if (transmission)
          out << ',' << format_number(ch->transmittance[i] * mm * mm) << ','
              << format_number(ch->transmittance_stderr[i] * mm * mm);
      }
    }
    out << '\n';
  }
  return out.str();
}

std::string to_table(const MonteCarloResult& result, LengthUnit unit) { return result.report(unit); }

std::string MonteCarloResult::report(LengthUnit unit) const {
  const double mm = millimetres_per(unit);
  const std::string u(symbol(unit));
  std::ostringstream out;
  out << "Monte Carlo reference (radiative transfer, Henyey-Greenstein phase function, Fresnel interfaces)\n\n";
  out << "Stack (top to bottom), lengths in " << u << ", coefficients in 1/" << u << ":\n";
  out << "  ambient above      n = " << format_number(stack.ambient_above) << "\n";
  for (std::size_t i = 0; i < stack.layers.size(); ++i) {
    const Layer& layer = stack.layers[i];
    out << "  layer " << i << (layer.name.empty() ? "" : " (" + layer.name + ")") << "  n = " << format_number(layer.n)
        << ", thickness = " << (std::isfinite(layer.thickness) ? format_number(layer.thickness / mm) : "semi-infinite")
        << "\n";
    for (std::size_t c = 0; c < stack.channels(); ++c)
      out << "    " << stack.channel_names[c] << ": sigma_a = " << format_number(layer.sigma_a[c] * mm)
          << ", sigma_s = " << format_number(layer.sigma_s[c] * mm) << ", g = " << format_number(layer.g[c]) << "\n";
  }
  if (!stack.semi_infinite()) out << "  ambient below      n = " << format_number(stack.ambient_below) << "\n";
  out << "\nRun:\n";
  out << "  photons            " << options.photons << " per channel, seed " << options.seed << ", batch size "
      << options.batch_size << "\n";
  out << "  threads            " << threads << (ranks > 1 ? " per rank, " + std::to_string(ranks) + " MPI ranks" : "")
      << "\n";
  if (ranks > 1)
    out << "  communication      " << communication_bytes << " bytes in " << fixed(communication_seconds, 0, 3)
        << " s (rank 0, waiting for the other ranks included)\n";
  out << "  time               " << fixed(seconds, 0, 3) << " s, " << general(photons_per_second, 0) << " photons/s\n";
  out << "  absorption         " << to_string(options.absorption);
  if (options.absorption == AbsorptionEstimator::implicit_capture)
    out << ", roulette below weight " << format_number(options.roulette_threshold) << " with survival "
        << format_number(options.roulette_survival);
  out << "\n  radial bins        " << options.bins << " " << to_string(options.spacing)
      << " bins to r_max = " << format_number(options.r_max / mm) << " " << u;
  if (options.spacing == BinSpacing::log) out << " (first bin [0, " << format_number(options.r_min / mm) << "))";
  out << "\n\nTotals (value +- standard error):\n";
  out << "  channel  quantity                          per incident flux           per entered flux\n";
  for (const ChannelResult& ch : channels) {
    const ChannelResult entered = ch.per_entered_flux();
    const auto row = [&](const char* name, const Estimate& a, const Estimate& b) {
      out << "  " << ch.name << std::string(ch.name.size() < 7 ? 7 - ch.name.size() : 1, ' ') << name
          << fixed(a.value, 12, 6) << " +- " << fixed(a.standard_error, 9, 6) << fixed(b.value, 14, 6) << " +- "
          << fixed(b.standard_error, 9, 6) << "\n";
    };
    out << "  " << ch.name << std::string(ch.name.size() < 7 ? 7 - ch.name.size() : 1, ' ')
        << "specular reflectance R_sp         " << fixed(ch.specular_reflectance, 12, 6) << "\n";
    row("diffuse reflectance R_d         ", ch.diffuse_reflectance, entered.diffuse_reflectance);
    row("  single scattering             ", ch.single_scattering_reflectance, entered.single_scattering_reflectance);
    if (ch.unscattered_reflectance.value > 0)
      row("  unscattered                   ", ch.unscattered_reflectance, entered.unscattered_reflectance);
    if (!stack.semi_infinite()) {
      row("total transmittance T_t         ", ch.total_transmittance, entered.total_transmittance);
      row("  unscattered (ballistic)       ", ch.unscattered_transmittance, entered.unscattered_transmittance);
    }
    row("absorbed                        ", ch.absorbed, entered.absorbed);
    const double balance = ch.specular_reflectance + ch.diffuse_reflectance.value + ch.total_transmittance.value +
                           ch.absorbed.value + ch.lost;
    out << "           energy balance R_sp + R_d + T_t + A = " << fixed(balance, 0, 6)
        << " (1 in expectation; roulette makes it exact only on average)\n";
  }
  std::vector<std::string> warnings;
  for (const ChannelResult& ch : channels) {
    if (ch.lost > 0)
      warnings.push_back(ch.name + ": weight " + format_number(ch.lost) + " stopped after " +
                         std::to_string(options.max_interactions) + " interactions (a bias of that size)");
    if (ch.reflectance_beyond > 0.01 * ch.diffuse_reflectance.value)
      warnings.push_back(ch.name + ": " +
                         fixed(100 * ch.reflectance_beyond / std::max(1e-300, ch.diffuse_reflectance.value), 0, 1) +
                         " % of R_d lands beyond r_max and is not binned (raise --r-max)");
  }
  out << "\nR(r) per unit area, first bins (1/" << u << "^2, per incident flux):\n";
  out << "    radius (" << u << ")";
  for (const auto& ch : channels)
    out << "  " << std::string(ch.name.size() < 22 ? 22 - ch.name.size() : 1, ' ') << ch.name;
  out << "\n";
  const std::size_t shown = std::min<std::size_t>(bin_radius.size(), 12);
  for (std::size_t i = 0; i < shown; ++i) {
    out << "  " << general(bin_radius[i] / mm);
    for (const auto& ch : channels)
      out << "  " << general(ch.reflectance[i] * mm * mm) << " +- " << general(ch.reflectance_stderr[i] * mm * mm, 7);
    out << "\n";
  }
  if (shown < bin_radius.size())
    out << "  ... (" << bin_radius.size() - shown << " more bins in the JSON/CSV output)\n";
  out << "\n" << (warnings.empty() ? "No warnings.\n" : "Warnings:\n");
  for (const auto& w : warnings) out << "  " << w << "\n";
  return out.str();
}

}  // namespace bssrdf
