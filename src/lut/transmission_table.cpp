#include "bssrdf/lut/transmission_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/montecarlo.hpp"

namespace bssrdf {

void TransmissionTableOptions::validate() const {
  if (photons < 100 || photons > 1'000'000'000) throw InvalidInput("photons", std::to_string(photons), "100 to 1e9");
  if (threads > 4096) throw InvalidInput("threads", std::to_string(threads), "0 (all cores) to 4096");
  if (model != "multipole" && model != "adding-doubling")
    throw InvalidInput("model", model, "multipole or adding-doubling");
}

std::string_view to_string(TransmissionSource source) {
  return source == TransmissionSource::multipole     ? "multipole"
         : source == TransmissionSource::monte_carlo ? "monte_carlo"
                                                     : "adding_doubling";
}

SlabThicknessRange default_thickness_range(const Medium& medium, const TransmissionTableOptions& options) {
  const bool every_thickness_valued =
      options.model == "adding-doubling" || options.reference || options.reference_everywhere;
  const auto ell = transport_mfp_range(medium);
  return {every_thickness_valued ? 0.1 * ell.min : 2 * ell.max, 40 * ell.max};
}

std::string multipole_invalid_code(const multipole::Model& model, const Reduced<double>& m) {
  for (const auto& note : model.validity(m))
    if (note.severity == Severity::invalid &&
        (note.code == "thin_slab" || note.code == "source_outside_slab" || note.code.rfind("negative_", 0) == 0))
      return note.code;
  return {};
}

TransmissionTable build_transmission_table(const Medium& medium, std::vector<double> thickness,
                                           const TransmissionTableOptions& options) {
  medium.validate();
  options.validate();
  if (thickness.empty()) throw InvalidInput("thickness: no thicknesses given");
  for (double d : thickness)
    if (!(d > 0) || !std::isfinite(d)) throw InvalidInput("thickness", format_number(d), "> 0 and finite");
  std::sort(thickness.begin(), thickness.end());
  thickness.erase(std::unique(thickness.begin(), thickness.end()), thickness.end());

  const std::size_t channels = medium.channels();
  TransmissionTable t;
  t.options = options;
  t.channel_names = medium.channel_names;
  t.transmittance.resize(channels);
  t.standard_error.resize(channels);
  const bool everywhere = options.reference_everywhere;
  const bool reference = options.reference || everywhere;
  const bool exact_everywhere = options.model == "adding-doubling" && !everywhere;
  // Adding-doubling: every thickness of a channel at once, sharing its angles, boundaries and phase function.
  // Every channel's slab first: one that cannot be solved (a channel without scattering) refuses the table before
  // the other channels' solves, not after them.
  std::vector<adding_doubling::Slab> slabs;
  for (std::size_t c = 0; c < (exact_everywhere ? channels : 0); ++c)
    slabs.push_back(adding_doubling::slab_of(LayerStack::slab(medium, thickness[0]), c));
  std::vector<std::vector<adding_doubling::Totals>> exact(slabs.size());
  for (std::size_t c = 0; c < exact.size(); ++c)
    exact[c] = adding_doubling::solve_thicknesses(slabs[c], thickness, adding_doubling::Incidence::collimated);
  for (std::size_t k = 0; k < thickness.size(); ++k) {
    const double d = thickness[k];
    const multipole::Model model(d);
    std::vector<double> T(channels), se(channels, 0.0);
    std::string invalid;  // "code (channels)"
    std::string code;
    // The multipole and its validity only where they may be used (adding-doubling replaces both).
    for (std::size_t c = 0; c < channels && !exact_everywhere; ++c) {
      const auto m = medium.reduced(c);
      const auto why = multipole_invalid_code(model, m);
      if (!why.empty()) {
        if (code.empty()) code = why;
        invalid += (invalid.empty() ? "" : ", ") + medium.channel_names[c] + ": " + why;
      }
      T[c] = model.total_transmittance(m);
    }
    TransmissionSource source = TransmissionSource::multipole;
    if (exact_everywhere) {
      // Exact: per entered flux, the unscattered beam removed, as the multipole reports it.
      t.adding_doubling_error.resize(channels, 0.0);
      for (std::size_t c = 0; c < channels; ++c) {
        const auto& a = exact[c][k];
        T[c] = (a.total_transmittance - a.unscattered_transmittance) * a.entered_scale();
        t.adding_doubling_error[c] = std::max(t.adding_doubling_error[c], a.error_estimate * a.entered_scale());
      }
      invalid.clear();
      source = TransmissionSource::adding_doubling;
    } else if (everywhere || (!invalid.empty() && reference)) {
      MonteCarloOptions mc;
      mc.photons = options.photons;
      mc.seed = options.seed;
      mc.threads = options.threads;
      mc.bins = 2;
      const auto start = std::chrono::steady_clock::now();
      const auto result = run_monte_carlo(LayerStack::slab(medium, d), mc);
      t.monte_carlo_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      for (std::size_t c = 0; c < channels; ++c) {
        const auto entered = result.channels[c].per_entered_flux();
        T[c] = entered.total_transmittance.value - entered.unscattered_transmittance.value;
        // The two estimates share photons; combining their errors in quadrature is an approximation.
        se[c] =
            std::hypot(entered.total_transmittance.standard_error, entered.unscattered_transmittance.standard_error);
      }
      source = TransmissionSource::monte_carlo;
    } else if (!invalid.empty()) {
      t.omitted_thickness.push_back(d);
      t.omitted_reason.push_back(invalid);
      continue;
    }
    t.thickness.push_back(d);
    t.source.push_back(source);
    for (std::size_t c = 0; c < channels; ++c) {
      t.transmittance[c].push_back(T[c]);
      t.standard_error[c].push_back(se[c]);
    }
  }
  // The channel's other warnings and invalid notes (thickness-independent, e.g. low_albedo).
  const multipole::Model thickest(thickness.back());
  for (std::size_t c = 0; c < channels && options.model == "adding-doubling"; ++c)
    t.validity.push_back("no warnings (adding-doubling is exact)");
  for (std::size_t c = 0; c < channels && options.model != "adding-doubling"; ++c) {
    std::string notes;
    for (const auto& note : thickest.validity(medium.reduced(c)))
      if (note.severity != Severity::note && note.code != "thin_slab")
        notes +=
            (notes.empty() ? "" : "; ") + std::string(to_string(note.severity)) + " " + note.code + ": " + note.message;
    t.validity.push_back(notes.empty() ? "no warnings" : notes);
  }
  return t;
}

LookupTable to_lookup_table(const TransmissionTable& t, const TableContext& context) {
  if (t.size() == 0) {
    std::string why;
    for (std::size_t i = 0; i < t.omitted_thickness.size() && i < 3; ++i)
      why += (why.empty() ? "" : "; ") + format_number(t.omitted_thickness[i] / millimetres_per(context.unit)) + " " +
             std::string(symbol(context.unit)) + " (" + t.omitted_reason[i] + ")";
    throw InvalidInput(
        "thickness", "every thickness",
        "one where the multipole holds (" + why + "), or --reference for the Monte Carlo reference there");
  }
  auto out = described_table("transmission", t.size(), 1, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  bool any_mc = false, any_multipole = false, any_ad = false;
  for (auto s : t.source)
    (s == TransmissionSource::monte_carlo ? any_mc
     : s == TransmissionSource::multipole ? any_multipole
                                          : any_ad) = true;
  out.set("bssrdf:distance", "slab thickness d, in " + u);
  out.set(
      "bssrdf:normalization",
      std::string("per_entered_flux: diffuse total transmittance T(d) = flux leaving the bottom face after at least "
                  "one scattering, per unit flux that entered through the top face (normal incidence); the ballistic "
                  "beam e^{-sigma_t d} is not included"));
  out.set("bssrdf:ballistic_included", std::string("no"));
  out.set("bssrdf:slab",
          std::string("homogeneous slab, the medium's eta on both faces, ambient index 1 above and below"));
  out.set("bssrdf:grid",
          std::string("the thickness channel holds d_j, increasing; interpolate linearly in d (or in ln d)"));
  out.set("bssrdf:size", static_cast<int>(t.size()));
  out.set("bssrdf:sources", std::string(any_ad                    ? "adding_doubling"
                                        : any_multipole && any_mc ? "multipole and monte_carlo (see the source channel)"
                                        : any_mc                  ? "monte_carlo"
                                                                  : "multipole"));
  if (any_ad)
    out.set("bssrdf:adding_doubling",
            std::string("exact slab totals (van de Hulst; Prahl 1995), 1e-4 absolute, true HG phase function "
                        "with delta-M, Fresnel at both faces; T = total minus unscattered, per entered flux"));
  if (any_multipole)
    out.set("bssrdf:multipole",
            std::string("Donner & Jensen 2005, closed-form totals of the infinite dipole-pair series, classical A"));
  if (any_mc) {
    out.set("bssrdf:monte_carlo_photons", static_cast<int>(t.options.photons));
    out.set("bssrdf:monte_carlo_seed", static_cast<int>(t.options.seed));
    out.set("bssrdf:monte_carlo",
            std::string("bssrdf reference: true Henyey-Greenstein phase function, Fresnel at both faces; "
                        "T = total minus unscattered transmittance, per entered flux"));
  }
  std::string omitted;
  for (std::size_t i = 0; i < t.omitted_thickness.size(); ++i)
    omitted += (omitted.empty() ? "" : "; ") + format_number(t.omitted_thickness[i] / mm) + " " + u + " (" +
               t.omitted_reason[i] + ")";
  for (std::size_t c = 0; c < t.channel_names.size() && c < t.validity.size(); ++c)
    out.set("bssrdf:validity." + t.channel_names[c], t.validity[c]);
  // Adding-doubling's own accuracy: the largest change of T over the thicknesses when the angles are halved.
  for (std::size_t c = 0; c < t.channel_names.size() && c < t.adding_doubling_error.size(); ++c)
    out.set("bssrdf:adding_doubling_error." + t.channel_names[c], t.adding_doubling_error[c]);
  out.set("bssrdf:omitted_count", static_cast<int>(t.omitted_thickness.size()));
  if (!omitted.empty())
    out.set("bssrdf:omitted",
            "thicknesses where the multipole is invalid and no reference was run (--reference fills them): " + omitted);
  std::vector<double> d(t.thickness);
  for (auto& x : d) x /= mm;
  out.add_channel("thickness", "slab thickness d, " + u, d);
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    out.add_channel(t.channel_names[c], "diffuse total transmittance T(d) per entered flux, ballistic excluded",
                    t.transmittance[c]);
  if (any_mc) {
    std::vector<double> s;
    for (auto x : t.source) s.push_back(x == TransmissionSource::monte_carlo ? 1.0 : 0.0);
    out.add_channel("source", "0: multipole, 1: Monte Carlo reference", s);
    for (std::size_t c = 0; c < t.channel_names.size(); ++c)
      out.add_channel("stderr." + t.channel_names[c], "standard error of T (0 for the multipole)", t.standard_error[c]);
  }
  return out;
}

std::string summary(const TransmissionTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  std::size_t mc = 0;
  for (auto x : t.source) mc += x == TransmissionSource::monte_carlo;
  s << "transmission table: " << t.size() << " thicknesses from " << short_number(t.thickness.front() / mm) << " to "
    << short_number(t.thickness.back() / mm) << ' ' << u << " (" << t.size() - mc
    << (t.options.model == "adding-doubling" ? " adding-doubling, " : " multipole, ") << mc << " Monte Carlo with "
    << t.options.photons << " photons per channel";
  if (mc) s << ", " << format_number(std::round(t.monte_carlo_seconds * 100) / 100) << " s";
  s << "); diffuse T per entered flux, ballistic excluded\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    s << "  " << t.channel_names[c] << ": T = " << short_number(t.transmittance[c].front()) << " at "
      << short_number(t.thickness.front() / mm) << ' ' << u << ", " << short_number(t.transmittance[c].back()) << " at "
      << short_number(t.thickness.back() / mm) << ' ' << u << '\n';
  if (!t.omitted_thickness.empty()) {
    s << "  omitted " << t.omitted_thickness.size()
      << " thicknesses where the multipole is invalid (recorded in bssrdf:omitted; --reference fills them):";
    for (double d : t.omitted_thickness) s << ' ' << short_number(d / mm);
    s << ' ' << u << '\n';
  }
  return s.str();
}

}  // namespace bssrdf
