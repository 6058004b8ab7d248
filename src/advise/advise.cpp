#include "bssrdf/advise/advise.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/image/realtime_tables.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {
namespace {

bool closed_form(const std::string& model) { return model_entry(model).closed_form; }

// A Monte Carlo channel as a function: the mean R over the annulus holding r (0 beyond the last).
std::function<double(double)> annulus_mean(const AnnularProfile& p) {
  return [&p](double r) {
    const auto i = static_cast<std::size_t>(std::upper_bound(p.edges.begin(), p.edges.end(), r) - p.edges.begin());
    if (i == 0 || i >= p.edges.size()) return 0.0;
    const double inner = p.edges[i - 1], outer = p.edges[i];
    return p.energy[i - 1] / (std::numbers::pi * (outer * outer - inner * inner));
  };
}

struct ReferenceTable {
  std::vector<RadialTableNodes> nodes;
  ImageError image;  // its tabulation error (against the reference), plus U in .error
  std::size_t radii = 0;
};

// The reference with formula channels tabulated (a Monte Carlo channel of a mixed reference: its
// annulus means, read at the same radii): the smallest N whose tabulation error plus U is within
// the tolerance, else the most accurate tried.
ReferenceTable tabulate_reference(const Medium& medium, const ReferenceProfiles& ref, const RealtimeJudge& judge,
                                  double uncertainty, double tolerance) {
  ReferenceTable best;
  for (std::size_t n : kRadialTableSizes) {
    if (uncertainty >= tolerance && n != kRadialTableSizes.back()) continue;  // none can meet it: the finest
    ReferenceTable t;
    t.radii = n;
    std::vector<AnnularProfile> profiles;
    for (std::size_t c = 0; c < medium.channels(); ++c) {
      const auto& source = ref.sources[c];
      t.nodes.push_back(radial_table_nodes(source.reflectance ? source.reflectance : annulus_mean(ref.channels[c]),
                                           medium.reduced(c), n));
      profiles.push_back(annuli_of(judge.meter.edges(), radial_table(t.nodes.back()), 0));  // no light beyond
    }
    t.image = judge.error(profiles);
    t.image.error += uncertainty;
    if (best.nodes.empty() || t.image.error < best.image.error) best = std::move(t);
    if (best.image.error <= tolerance) break;
  }
  return best;
}

}  // namespace

AdviseTarget parse_advise_target(const std::string& text) {
  if (text == "realtime") return AdviseTarget::realtime;
  if (text == "offline") return AdviseTarget::offline;
  if (text == "any") return AdviseTarget::any;
  throw InvalidInput("--target", text, "realtime, offline or any");
}

std::string_view to_string(AdviseTarget target) {
  switch (target) {
    case AdviseTarget::realtime:
      return "realtime";
    case AdviseTarget::offline:
      return "offline";
    default:
      return "any";
  }
}

Advice advise(const Medium& medium, const ReferenceProfile& reference, const AdviseOptions& options) {
  if (!(options.pixel > 0) || !std::isfinite(options.pixel))
    throw InvalidInput("--pixel", format_number(options.pixel), "> 0 and finite");
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidInput("--tolerance", format_number(options.tolerance), "> 0 (8-bit sRGB code values) and finite");
  Advice advice;
  advice.options = options;
  const ReferenceProfiles ref = reference.profiles(medium);
  advice.reference = ref.description;
  advice.reference_seconds = ref.seconds;
  const auto& edges = ref.channels.front().edges;
  const std::size_t channels = medium.channels();
  RealtimeJudge judge{ImageErrorMeter(edges, options.pixel), {}, {}};
  for (const auto& p : ref.channels) {
    judge.reference.push_back(judge.meter.render(p));
    judge.albedo.push_back(p.total());
  }
  advice.diffuse_reflectance = judge.albedo;
  std::vector<double> near_radius;  // one transport mfp: where the exact band's near field ends
  for (std::size_t c = 0; c < channels; ++c) near_radius.push_back(medium.reduced(c).ell);
  advice.reference_uncertainty = reference_uncertainty(judge, ref, near_radius);
  const double U = advice.reference_uncertainty.error();
  for (const auto& source : ref.sources) advice.reference_sources.push_back(source.name);
  // A model that is the source of any reference channel is judged against itself there: it carries U.
  const auto is_reference = [&](const std::string& model) {
    return std::any_of(ref.sources.begin(), ref.sources.end(), [&](const auto& s) { return s.name == model; });
  };

  const auto add = [&](std::string name, const ImageError& image, double cost, std::size_t memory, bool realtime,
                       std::vector<std::pair<std::string, double>> parameters = {}) {
    advice.reference_noise = std::max(advice.reference_noise, image.reference_noise);
    advice.candidates.push_back({std::move(name), image, cost, memory, realtime, false, std::move(parameters)});
  };

  std::vector<AnnularProfile> lambertian;
  for (double albedo : judge.albedo) lambertian.push_back(point_profile(edges, albedo));
  add("lambertian", judge.error(lambertian), 0, 0, true);

  const auto add_model = [&](const std::string& name, double cost) {
    const auto model = make_model(name);
    std::vector<AnnularProfile> profiles;
    for (std::size_t c = 0; c < channels; ++c) {
      const auto m = medium.reduced(c);
      profiles.push_back(annuli_of(
          edges, [&](double r) { return model->reflectance(m, r); }, model->total_reflectance(m)));
    }
    add(name, judge.error(profiles), cost, 0, closed_form(name));
    if (is_reference(name)) advice.candidates.back().image.error = std::max(advice.candidates.back().image.error, U);
  };
  std::string best_model;
  double best_error = INFINITY;
  for (const auto& measured : measured_models()) {
    add_model(measured.model, measured.cost_ns);
    if (advice.candidates.back().image.error < best_error) {
      best_error = advice.candidates.back().image.error;
      best_model = measured.model;
    }
  }
  const auto exact = make_model("exact");
  bool inside_exact = true;
  for (std::size_t c = 0; c < channels; ++c)
    inside_exact = inside_exact && worst(exact->validity(medium.reduced(c))) != Severity::invalid;
  if (inside_exact) add_model("exact", model_entry("exact").cost_ns);
  // The real-time tables of the most accurate model, each sized by the tolerance (realtime_tables.hpp).
  const auto model = make_model(best_model);
  const std::string of = ":" + best_model;
  const auto radial = choose_radial_table_size(medium, *model, judge, options.tolerance);
  add("radial-table-" + std::to_string(radial.count) + of, radial.image, kTableLookupNs, radial.count * channels * 4,
      true, {{"radii", static_cast<double>(radial.count)}});
  const auto gaussians = choose_gaussian_count(medium, *model, judge, options.tolerance);
  add("gaussians-" + std::to_string(gaussians.count) + of, gaussians.image,
      static_cast<double>(gaussians.count) * kGaussianTermNs, gaussians.count * (channels + 1) * 4, true,
      {{"count", static_cast<double>(gaussians.count)}});
  const auto projections = project_channels(medium, *model);
  const auto separable = choose_separable_kernel(medium, projections, judge, options.tolerance);
  add("separable-" + std::to_string(separable.options.taps) + of, separable.image,
      2 * separable.options.taps * kKernelTapNs, static_cast<std::size_t>(separable.options.taps) * 4 * 4, true,
      {{"taps", separable.options.taps}, {"range_mm", separable.options.range}, {"band", separable.options.band}});
  const auto preintegrated = choose_preintegrated_table(medium, projections, judge, options.tolerance);
  add("preintegrated-" + std::to_string(preintegrated.size) + of, preintegrated.image, kTableLookupNs,
      preintegrated.size * preintegrated.size * channels * 4, true,
      {{"size", static_cast<double>(preintegrated.size)},
       {"curvature_max_per_mm", preintegrated.curvature_max},
       {"table_error", preintegrated.table_error}});
  const bool formula = std::any_of(ref.sources.begin(), ref.sources.end(),
                                   [](const auto& s) { return static_cast<bool>(s.reflectance); });
  if (formula) {
    auto table = tabulate_reference(medium, ref, judge, U, options.tolerance);
    std::size_t nodes = 0;
    for (const auto& n : table.nodes) nodes = std::max(nodes, n.radius.size());
    add("reference-table", table.image, kTableLookupNs, nodes * channels * 8, true,
        {{"radii", static_cast<double>(table.radii)}});
    advice.reference_table = std::move(table.nodes);
  } else {  // its own annuli, exactly: no tabulation error
    add("reference-table", judge.error(ref.channels), kTableLookupNs, (edges.size() - 1) * channels * 4, true,
        {{"annuli", static_cast<double>(edges.size() - 1)}});
    advice.candidates.back().image.error = U;
  }

  std::stable_sort(advice.candidates.begin(), advice.candidates.end(), [](const auto& a, const auto& b) {
    return a.cost != b.cost ? a.cost < b.cost : a.memory_bytes < b.memory_bytes;
  });
  for (std::size_t i = 0; i < advice.candidates.size(); ++i) {
    auto& c = advice.candidates[i];
    c.meets_tolerance = c.image.error <= options.tolerance;
    if (!advice.choice && c.meets_tolerance && (options.target != AdviseTarget::realtime || c.realtime))
      advice.choice = i;
  }

  for (const auto& p : ref.channels)
    advice.profile_radius = std::max(advice.profile_radius, p.radius_for_fraction(0.99));
  if (options.object_size > 0 && 2 * advice.profile_radius > options.object_size)
    advice.object_warning =
        "the profile (99 % of the light within " + format_number(advice.profile_radius) +
        " mm of entry) is wider than the object (" + format_number(options.object_size) +
        " mm): the semi-infinite profile does not apply; model the object as a slab or layers (bssrdf slab, --layers)";
  return advice;
}

std::string to_json(const Advice& advice, const std::string& material) {
  using nlohmann::json;
  const auto candidate = [](const AdviseCandidate& c) {
    json out{{"representation", c.representation},
             {"error", c.image.error},
             {"cost", c.cost},
             {"cost_unit", "ns"},
             {"memory_bytes", c.memory_bytes},
             {"realtime", c.realtime},
             {"meets_tolerance", c.meets_tolerance},
             {"worst_pattern", c.image.pattern},
             {"worst_channel", c.image.channel},
             {"worst_position_mm", c.image.position}};
    json parameters = json::object();
    for (const auto& [name, value] : c.parameters) parameters[name] = value;
    out["parameters"] = parameters;
    return out;
  };
  json doc;
  doc["material"] = material;
  doc["pixel_mm"] = advice.options.pixel;
  doc["tolerance"] = advice.options.tolerance;
  doc["error_unit"] = "8-bit sRGB code values";
  doc["target"] = std::string(to_string(advice.options.target));
  doc["reference"] = advice.reference;
  doc["reference_seconds"] = advice.reference_seconds;
  doc["reference_noise"] = advice.reference_noise;
  doc["reference_uncertainty"] = advice.reference_uncertainty.error();
  doc["reference_band_error"] = advice.reference_uncertainty.band.error;
  doc["reference_sources"] = advice.reference_sources;
  doc["profile_radius_mm"] = advice.profile_radius;
  doc["choice"] = advice.choice ? candidate(advice.candidates[*advice.choice]) : json(nullptr);
  doc["candidates"] = json::array();
  for (const auto& c : advice.candidates) doc["candidates"].push_back(candidate(c));
  doc["warnings"] = json::array();
  if (!advice.object_warning.empty()) doc["warnings"].push_back(advice.object_warning);
  return doc.dump(2) + "\n";
}

std::string to_table(const Advice& advice, const std::string& material) {
  std::ostringstream out;
  out << material << " at " << format_number(advice.options.pixel) << " mm per pixel, tolerance "
      << format_number(advice.options.tolerance) << " (8-bit sRGB code values), target "
      << to_string(advice.options.target) << "\n";
  out << "reference: " << advice.reference << " (" << std::fixed << std::setprecision(2) << advice.reference_seconds
      << " s), noise " << std::setprecision(3) << advice.reference_noise << " code values (1 standard error)\n";
  out << "reference uncertainty U = " << advice.reference_uncertainty.error() << " code values (its measured band "
      << advice.reference_uncertainty.band.error << " + 2 x noise): what the reference itself may be off by; "
      << "carried by the candidates that are the reference\n\n";
  out << std::left << std::setw(34) << "representation" << std::right << std::setw(10) << "error" << std::setw(10)
      << "cost_ns" << std::setw(10) << "bytes"
      << "  meets\n";
  for (std::size_t i = 0; i < advice.candidates.size(); ++i) {
    const auto& c = advice.candidates[i];
    out << std::left << std::setw(34) << c.representation << std::right << std::setw(10) << std::setprecision(3)
        << c.image.error << std::setw(10) << std::setprecision(1) << c.cost << std::setw(10) << c.memory_bytes << "  "
        << (c.meets_tolerance ? "yes" : "no") << (c.realtime ? "" : " (offline)")
        << (advice.choice == i ? "  <- choice" : "") << "\n";
  }
  out << std::setprecision(3);
  if (advice.choice) {
    out << "\nchoice: " << advice.candidates[*advice.choice].representation << "; cheaper ones fail:";
    bool any = false;
    for (std::size_t i = 0; i < *advice.choice; ++i) {
      const auto& c = advice.candidates[i];
      out << (any ? "," : "") << " " << c.representation << " (" << c.image.error << " at the " << c.image.pattern
          << ")";
      any = true;
    }
    out << (any ? "\n" : " none\n");
  } else {
    out << "\nno candidate meets the tolerance for this target";
    // Say what would: the most accurate candidate allowed for the target, and whether the tolerance
    // asks for less than the reference itself can tell apart.
    const AdviseCandidate* best = nullptr;
    for (const auto& c : advice.candidates)
      if ((advice.options.target != AdviseTarget::realtime || c.realtime) &&
          (!best || c.image.error < best->image.error))
        best = &c;
    if (best) out << "; the most accurate is " << best->representation << " (" << best->image.error << ")";
    if (advice.options.tolerance < advice.reference_uncertainty.error())
      out << "; a tolerance below the reference's own uncertainty U = " << advice.reference_uncertainty.error()
          << " cannot be certified";
    out << "\n";
  }
  if (!advice.object_warning.empty()) out << "warning: " << advice.object_warning << "\n";
  return out.str();
}

}  // namespace bssrdf
