#include "bssrdf/derived_quantities.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/profile.hpp"
#include "bssrdf/transport_total.hpp"

namespace bssrdf {

std::vector<double> burley_fit_radii_mm(const Reduced<double>& m, std::size_t count) {
  const double r_max = m.sigma_tr > 0 ? 16 * m.ell_d : 1000 * m.ell;
  const double r_min = 1e-3 * std::min(m.ell, r_max / 16);
  return log_spaced(r_min, r_max, count);
}

DerivedQuantities derive_quantities(const Medium& medium, const DerivationOptions& options) {
  medium.validate();
  if (!(options.object_size_mm > 0) || !std::isfinite(options.object_size_mm))
    throw InvalidInput("object size", format_number(options.object_size_mm), "> 0 and finite");
  if (options.radii < 8) throw InvalidInput("radii", std::to_string(options.radii), ">= 8");
  if (!options.physical_model.empty()) make_model(options.physical_model);  // an unknown name: InvalidInput
  const ExactTable& table = bundled_exact_table();
  DerivedQuantities out;
  out.object_size_mm = options.object_size_mm;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    DerivedChannel ch;
    ch.name = medium.channel_names[c];
    ch.sigma_a = m.sigma_a;
    ch.sigma_s = m.sigma_s;
    ch.g = m.g;
    ch.sigma_t = m.sigma_t();
    ch.albedo = m.albedo();
    ch.sigma_s_prime = m.sigma_s_prime;
    ch.sigma_t_prime = m.sigma_t_prime;
    ch.albedo_prime = m.albedo_prime;
    ch.mfp = 1 / ch.sigma_t;
    ch.transport_mfp = m.ell;
    ch.diffuse_mfp = m.sigma_tr > 0 ? m.ell_d : std::numeric_limits<double>::infinity();

    const bool inside_exact = exact_domain(table, m.albedo_prime, m.g, m.eta).empty();
    if (options.physical_model.empty()) {
      const auto chosen = default_model(m);
      ch.physical_model = chosen.name;
      ch.model_choice = chosen.reason;
    } else {
      ch.physical_model = options.physical_model;
    }
    const auto model = make_model(ch.physical_model);

    if (m.sigma_s_prime > 0) {
      // The verdict `bssrdf profile` prints for this model: one function decides for both.
      ch.validity = model->validity(m);
      const double model_total = model->total_reflectance(m);
      ch.surface_albedo = model_total;
      if (inside_exact) {
        // Inside the exact model's domain the surface albedo is its total (the radiative-transfer
        // solution, <= 1), whatever the physical model's.
        ch.surface_albedo = exact_total(table, m.albedo_prime, m.g, m.eta);
        if (model_total > 1)
          ch.validity.push_back({Severity::note, "surface_albedo",
                                 "surface albedo and Burley A are the exact model's total " +
                                     format_number(std::round(ch.surface_albedo * 1e5) / 1e5) + ", not " +
                                     ch.physical_model + "'s " + format_number(std::round(model_total * 1e5) / 1e5)});
      } else if (model_total > 1) {
        // The physical model creates energy here (its validity says so): the surface albedo is the
        // exact radiative-transfer total instead, which conserves it.
        ch.surface_albedo = transport_total(m).value;
        ch.validity.push_back({Severity::note, "surface_albedo",
                               "surface albedo and Burley A are the exact total " +
                                   format_number(std::round(ch.surface_albedo * 1e5) / 1e5) +
                                   " (adding-doubling), not " + ch.physical_model + "'s " +
                                   format_number(std::round(model_total * 1e5) / 1e5)});
      }
      // Burley's d fitted to the physical profile, his A held at the surface albedo: the fitted
      // profile carries exactly the surface albedo's energy (its error includes any excess of the
      // physical model's).
      NamedProfile profile{ch.name, model->sample(m, burley_fit_radii_mm(m, options.radii))};
      const auto fit = fit_burley({profile}, LengthUnit::millimetre, ch.physical_model, {ch.surface_albedo});
      ch.burley_d = fit.find("burley_d", ch.name)->value;
      ch.burley_albedo = fit.find("surface_albedo", ch.name)->value;
      ch.burley_error = fit.find("relative_l2_error", ch.name)->value;
    } else {
      // Nothing scatters back: no profile to fit.
      ch.burley_d = ch.burley_albedo = ch.burley_error = nan;
      ch.validity.push_back({Severity::note, "no_scattering", "no scattering (sigma_s' = 0): light is only absorbed"});
    }
    if (m.ell > options.object_size_mm)
      ch.validity.push_back({Severity::warning, "object_size",
                             "transport mean free path " + format_number(std::round(m.ell * 1e3) / 1e3) +
                                 " mm exceeds the object size " + format_number(options.object_size_mm) +
                                 " mm: light leaves before it becomes diffuse"});
    out.channels.push_back(std::move(ch));
  }
  // "exact", or the most common model with the others named: "exact (pbd for B)".
  const std::string& first = out.channels.front().physical_model;
  std::string others;
  for (const auto& c : out.channels)
    if (c.physical_model != first) others += (others.empty() ? "" : ", ") + c.physical_model + " for " + c.name;
  out.physical_model = others.empty() ? first : first + " (" + others + ")";
  return out;
}

}  // namespace bssrdf
