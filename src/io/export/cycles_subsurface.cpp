#include "bssrdf/io/cycles_subsurface.hpp"

#include <algorithm>
#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/io/renderer_export.hpp"

namespace bssrdf {
namespace {
constexpr float kPi = 3.14159265358979323846f;
constexpr double kMinAlpha = 0.2;    // Cycles raises lower single-scattering albedos to this
constexpr double kMaxBounces = 256;  // BSSRDF_MAX_BOUNCES: Cycles ends a walk after this many events
const std::pair<CyclesMapping, const char*> kMappings[] = {{CyclesMapping::fixed_radius, "fixed-radius"},
                                                           {CyclesMapping::radius_remap, "radius-remap"},
                                                           {CyclesMapping::burley, "burley"}};
}  // namespace

CyclesMapping parse_cycles_mapping(std::string_view text, std::string_view field) {
  std::string names;
  for (const auto& [m, name] : kMappings) {
    if (text == name) return m;
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  throw InvalidInput(std::string(field), "'" + std::string(text) + "'", "one of " + names);
}

std::string_view to_string(CyclesMapping mapping) {
  for (const auto& [m, name] : kMappings)
    if (m == mapping) return name;
  return "?";
}

std::string_view blender_method_identifier(CyclesMapping mapping, int blender_major) {
  switch (mapping) {
    case CyclesMapping::fixed_radius:
      return blender_major >= 4 ? "RANDOM_WALK" : "RANDOM_WALK_FIXED_RADIUS";
    case CyclesMapping::radius_remap:
      return blender_major >= 4 ? "RANDOM_WALK_SKIN" : "RANDOM_WALK";
    case CyclesMapping::burley:
      return "BURLEY";
  }
  return "?";
}

float cycles_random_walk_alpha(float albedo, float g) {
  const float g2 = g * g, g3 = g2 * g, g4 = g3 * g, g5 = g4 * g, g6 = g5 * g, g7 = g6 * g;
  const float A = 1.8260523782f + -1.28451056436f * g + -1.79904629312f * g2 + 9.19393289202f * g3 +
                  -22.8215585862f * g4 + 32.0234874259f * g5 + -23.6264803333f * g6 + 7.21067002658f * g7;
  const float B =
      4.98511194385f + 0.127355959438f * std::exp(31.1491581433f * g + -201.847017512f * g2 + 841.576016723f * g3 +
                                                  -2018.09288505f * g4 + 2731.71560286f * g5 + -1935.41424244f * g6 +
                                                  559.009054474f * g7);
  const float C = 1.09686102424f + -0.394704063468f * g + 1.05258115941f * g2 + -8.83963712726f * g3 +
                  28.8643230661f * g4 + -46.8802913581f * g5 + 38.5402837518f * g6 + -12.7181042538f * g7;
  const float D = 0.496310210422f + 0.360146581622f * g + -2.15139309747f * g2 + 17.8896899217f * g3 +
                  -55.2984010333f * g4 + 82.065982243f * g5 + -58.5106008578f * g6 + 15.8478295021f * g7;
  const float E =
      4.23190299701f + 0.00310603949088f * std::exp(76.7316253952f * g + -594.356773233f * g2 + 2448.8834203f * g3 +
                                                    -5576.68528998f * g4 + 7116.60171912f * g5 + -4763.54467887f * g6 +
                                                    1303.5318055f * g7);
  const float F = 2.40602999408f + -2.51814844609f * g + 9.18494908356f * g2 + -79.2191708682f * g3 +
                  259.082868209f * g4 + -403.613804597f * g5 + 302.85712436f * g6 + -87.4370473567f * g7;
  const float blend = std::pow(albedo, 0.25f);
  const float alpha =
      (1.0f - blend) * A * std::pow(std::atan(B * albedo), C) + blend * D * std::pow(std::atan(E * albedo), F);
  return std::clamp(alpha, 0.0f, 0.999999f);
}

float cycles_dipole_alpha_prime(float total, float eta) {
  const float inv_eta = 1.0f / eta;
  const float F_dr = inv_eta * (-1.440f * inv_eta + 0.710f) + 0.668f + 0.0636f * eta;
  const float fourthirdA = (4.0f / 3.0f) * (1.0f + F_dr) / (1.0f - F_dr);
  const auto Rd = [&](float alpha_prime) {
    const float s = std::sqrt(3.0f * (1.0f - alpha_prime));
    return 0.5f * alpha_prime * (1.0f + std::exp(-fourthirdA * s)) * std::exp(-s);
  };
  if (total < 1e-4f) return 0.0f;
  if (total >= 0.995f) return 0.999999f;
  float x0 = 0.0f, x1 = 1.0f, xmid = 0.5f;
  for (int i = 0; i < 12; ++i) {
    xmid = 0.5f * (x0 + x1);
    (Rd(xmid) < total ? x0 : x1) = xmid;
  }
  return xmid;
}

float cycles_burley_scaling(float A) { return 1.9f - A + 3.5f * (A - 0.8f) * (A - 0.8f); }

float cycles_radius_factor(CyclesMapping mapping, float albedo_color, float eta) {
  if (mapping != CyclesMapping::radius_remap) return 0.25f / kPi;
  const float alpha_prime = cycles_dipole_alpha_prime(albedo_color, std::clamp(eta, 1.01f, 3.8f));
  return std::sqrt(3.0f * (1.0f - alpha_prime));
}

CyclesSimulated cycles_simulated(CyclesMapping mapping, const std::vector<double>& albedo_color,
                                 const std::vector<double>& radius, double eta, double anisotropy) {
  CyclesSimulated out;
  out.g = std::clamp(anisotropy, 0.0, 0.9);
  const auto g = static_cast<float>(out.g);
  for (std::size_t c = 0; c < radius.size(); ++c) {
    const auto C = static_cast<float>(albedo_color[c]);
    const float R_eff = static_cast<float>(radius[c]) * cycles_radius_factor(mapping, C, static_cast<float>(eta));
    if (mapping == CyclesMapping::burley) {
      out.burley_d.push_back(R_eff / cycles_burley_scaling(C));
      out.burley_A.push_back(C);
      continue;
    }
    const double alpha = cycles_random_walk_alpha(C, g);
    out.sigma_t.push_back(1.0f / std::max(R_eff, 1e-16f) / (1.0f - g));
    out.alpha.push_back(std::max(alpha, kMinAlpha));
    out.throughput_scale.push_back(alpha < kMinAlpha ? alpha / kMinAlpha : 1.0);
  }
  return out;
}

CyclesInputs cycles_inputs(const Medium& medium, const DerivedQuantities& derived, CyclesMapping mapping,
                           double millimetres_per_unit) {
  if (medium.channels() != 3 || derived.channels.size() != 3)
    throw InvalidInput("blender: " + std::to_string(medium.channels()) + " channels; Cycles takes exactly three (RGB)");
  CyclesInputs in;
  in.mapping = mapping;
  in.eta = std::clamp(medium.eta, 1.01, 3.8);
  if (in.eta != medium.eta) in.notes.push_back("eta " + format_number(medium.eta) + " clamped to Cycles' 1.01-3.8");
  // One g (the channels' mean, sigma_s rescaled to keep sigma_s'), then into Cycles' [0, 0.9] the same way.
  const auto one = single_g(medium);
  in.g = std::clamp(one.g, 0.0, 0.9);
  if (in.g != one.g)
    in.notes.push_back("g " + format_number(one.g) + " outside Cycles' [0, 0.9]: " + format_number(in.g) +
                       " used, sigma_s rescaled to keep sigma_s' = sigma_s (1 - g)");
  const auto g = static_cast<float>(in.g);
  for (std::size_t c = 0; c < 3; ++c) {
    const auto& name = medium.channel_names[c];
    const double sigma_s = one.sigma_s[c] * (1 - one.g) / (1 - in.g);
    const double sigma_t = (medium.sigma_a[c] + sigma_s) * millimetres_per_unit;  // 1/unit
    const double alpha = sigma_s * millimetres_per_unit / sigma_t;
    in.target_sigma_t.push_back(sigma_t);
    in.target_alpha.push_back(alpha);
    if (mapping == CyclesMapping::burley) {
      const auto& d = derived.channels[c];
      const double A = std::isfinite(d.burley_albedo) ? std::clamp(d.burley_albedo, 0.0, 1.0) : 0.0;
      const double burley_d = std::isfinite(d.burley_d) ? d.burley_d / millimetres_per_unit : 0.0;
      in.albedo_color.push_back(A);
      in.radius.push_back(burley_d / cycles_radius_factor(mapping, static_cast<float>(A), 1.0f) *
                          cycles_burley_scaling(static_cast<float>(A)));
      continue;
    }
    // The colour whose remapped alpha is ours: alpha(C) rises monotonically on [0, 1].
    double lo = 0, hi = 1;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (cycles_random_walk_alpha(static_cast<float>(mid), g) < alpha ? lo : hi) = mid;
    }
    const double C = static_cast<float>(0.5 * (lo + hi));
    in.albedo_color.push_back(C);
    const float factor = cycles_radius_factor(mapping, static_cast<float>(C), static_cast<float>(in.eta));
    in.radius.push_back(1.0 / (sigma_t * (1 - in.g) * factor));
    const double reached = cycles_random_walk_alpha(static_cast<float>(C), g);
    if (alpha < kMinAlpha)
      in.notes.push_back(name + ": alpha " + format_number(alpha) +
                         " < 0.2: Cycles walks with alpha 0.2 and scales the throughput by alpha / 0.2 instead "
                         "(total roughly kept, halo too wide)");
    else if (alpha > 1 - 1.0 / kMaxBounces)
      in.notes.push_back(name + ": alpha " + format_number(alpha) +
                         ": walks last up to 1/(1 - alpha) = " + format_number(std::round(1 / (1 - alpha))) +
                         " scattering events before absorption, beyond Cycles' 256-event walk limit: the light that "
                         "travels farthest is lost (less bleed and a lower total than the medium's)");
    if (alpha >= kMinAlpha && std::abs(reached - alpha) > 1e-4)
      in.notes.push_back(name + ": alpha " + format_number(alpha) + " beyond Cycles' range; it simulates " +
                         format_number(reached));
  }
  in.simulated = cycles_simulated(mapping, in.albedo_color, in.radius, in.eta, in.g);
  return in;
}

}  // namespace bssrdf
