#include "bssrdf/advise/advise.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"

namespace bssrdf {
namespace {

bool closed_form(const std::string& model) { return model_entry(model).closed_form; }

}  // namespace

std::function<double(double)> radial_table(const Model& model, const Reduced<double>& m, std::size_t n, double lo_ell, double hi_ell) {
  if (n < 2) throw InvalidInput("radial table radii", std::to_string(n), ">= 2");
  const double lo = lo_ell * m.ell, hi = hi_ell * m.ell, step = std::log(hi_ell / lo_ell) / static_cast<double>(n - 1);
  std::vector<double> log_R(n);
  for (std::size_t j = 0; j < n; ++j) {
    const double R = model.reflectance(m, lo * std::exp(step * static_cast<double>(j)));
    log_R[j] = std::log(std::max(R, 1e-300));
  }
  return [lo, hi, step, log_R](double r) {
    if (r > hi) return 0.0;
    const double u = std::log(std::max(r, lo) / lo) / step;
    const auto j = std::min(static_cast<std::size_t>(u), log_R.size() - 2);
    const double t = u - static_cast<double>(j);
    return std::exp((1 - t) * log_R[j] + t * log_R[j + 1]);
  };
}

AdviseTarget parse_advise_target(const std::string& text) {
  if (text == "realtime") return AdviseTarget::realtime;
  if (text == "offline") return AdviseTarget::offline;
  if (text == "any") return AdviseTarget::any;
  throw InvalidInput("--target", text, "realtime, offline or any");
}

std::string_view to_string(AdviseTarget target) {
  switch (target) {
    case AdviseTarget::realtime: return "realtime";
    case AdviseTarget::offline: return "offline";
    default: return "any";
  }
}

Advice advise(const Medium& medium, const ReferenceProfile& reference, const AdviseOptions& options) {
  if (!(options.pixel > 0) || !std::isfinite(options.pixel)) throw InvalidInput("--pixel", format_number(options.pixel), "> 0 and finite");
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidInput("--tolerance", format_number(options.tolerance), "> 0 (8-bit sRGB code values) and finite");
  Advice advice;
  advice.options = options;
  const ReferenceProfiles ref = reference.profiles(medium);
  advice.reference = ref.description;
  advice.reference_seconds = ref.seconds;
  const auto& edges = ref.channels.front().edges;
  const ImageErrorMeter meter(edges, options.pixel);
  const std::size_t channels = medium.channels();

  const auto add = [&](std::string name, const std::vector<AnnularProfile>& profiles, double cost, std::size_t memory, bool realtime) {
    AdviseCandidate c{std::move(name), meter.error(ref.channels, profiles), cost, memory, realtime, false};
    advice.reference_noise = std::max(advice.reference_noise, c.image.reference_noise);
    advice.candidates.push_back(std::move(c));
  };

  std::vector<AnnularProfile> lambertian;
  for (const auto& p : ref.channels) {
    lambertian.push_back(point_profile(edges, p.total()));
    advice.diffuse_reflectance.push_back(p.total());
  }
  add("lambertian", lambertian, 0, 0, true);

  std::string best_model;
  double best_error = INFINITY;
  for (const auto& measured : measured_models()) {
    const auto model = make_model(measured.model);
    std::vector<AnnularProfile> profiles;
    for (std::size_t c = 0; c < channels; ++c) {
      const auto m = medium.reduced(c);
      profiles.push_back(annuli_of(edges, [&](double r) { return model->reflectance(m, r); }, model->total_reflectance(m)));
    }
    add(measured.model, profiles, measured.cost_ns, 0, closed_form(measured.model));
    if (advice.candidates.back().image.error < best_error) {
      best_error = advice.candidates.back().image.error;
      best_model = measured.model;
    }
  }
  const auto model = make_model(best_model);
  for (std::size_t n : {8, 16, 32, 64}) {
    std::vector<AnnularProfile> profiles;
    for (std::size_t c = 0; c < channels; ++c) {
      const auto m = medium.reduced(c);
      const auto table = radial_table(*model, m, n);
      profiles.push_back(annuli_of(edges, table, 0));  // no light beyond the table
    }
    add("radial-table-" + std::to_string(n) + ":" + best_model, profiles, kTableLookupNs, n * channels * 4, true);
  }
  for (int count : {1, 2, 4, 8}) {
    const GaussianMixtureTable fit = fitted_mixture_table(medium, *model, count);
    std::vector<AnnularProfile> profiles;
    for (std::size_t c = 0; c < channels; ++c) {
      const auto& w = fit.weight[c];
      const auto& v = fit.variance[c];
      const auto sum = [&](double r) {
        double R = 0;
        for (std::size_t k = 0; k < w.size(); ++k) R += w[k] * std::exp(-r * r / (2 * v[k])) / (2 * std::numbers::pi * v[k]);
        return R;
      };
      profiles.push_back(annuli_of(edges, sum, 0));  // a sum of Gaussians has no tail beyond itself
    }
    add("gaussians-" + std::to_string(count) + ":" + best_model, profiles, count * kGaussianTermNs,
        static_cast<std::size_t>(count) * (channels + 1) * 4, true);
  }
  add("reference-table", ref.channels, kTableLookupNs, (edges.size() - 1) * channels * 4, true);
  advice.candidates.back().image.error = 2 * advice.candidates.back().image.reference_noise;

  std::stable_sort(advice.candidates.begin(), advice.candidates.end(), [](const auto& a, const auto& b) {
    return a.cost != b.cost ? a.cost < b.cost : a.memory_bytes < b.memory_bytes;
  });
  for (std::size_t i = 0; i < advice.candidates.size(); ++i) {
    auto& c = advice.candidates[i];
    c.meets_tolerance = c.image.error <= options.tolerance;
    if (!advice.choice && c.meets_tolerance && (options.target != AdviseTarget::realtime || c.realtime)) advice.choice = i;
  }

  for (const auto& p : ref.channels) advice.profile_radius = std::max(advice.profile_radius, p.radius_for_fraction(0.99));
  if (options.object_size > 0 && 2 * advice.profile_radius > options.object_size)
    advice.object_warning = "the profile (99 % of the light within " + format_number(advice.profile_radius) +
                            " mm of entry) is wider than the object (" + format_number(options.object_size) +
                            " mm): the semi-infinite profile does not apply; model the object as a slab or layers (bssrdf slab, --layers)";
  return advice;
}

std::string to_json(const Advice& advice, const std::string& material) {
  using nlohmann::json;
  const auto candidate = [](const AdviseCandidate& c) {
    return json{{"representation", c.representation}, {"error", c.image.error},     {"cost", c.cost},
                {"cost_unit", "ns"},                  {"memory_bytes", c.memory_bytes}, {"realtime", c.realtime},
                {"meets_tolerance", c.meets_tolerance}, {"worst_pattern", c.image.pattern}, {"worst_channel", c.image.channel},
                {"worst_position_mm", c.image.position}};
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
      << format_number(advice.options.tolerance) << " (8-bit sRGB code values), target " << to_string(advice.options.target) << "\n";
  out << "reference: " << advice.reference << " (" << std::fixed << std::setprecision(2) << advice.reference_seconds
      << " s), noise " << std::setprecision(3) << advice.reference_noise << " code values (1 standard error)\n\n";
  out << std::left << std::setw(34) << "representation" << std::right << std::setw(10) << "error" << std::setw(10) << "cost_ns"
      << std::setw(10) << "bytes" << "  meets\n";
  for (std::size_t i = 0; i < advice.candidates.size(); ++i) {
    const auto& c = advice.candidates[i];
    out << std::left << std::setw(34) << c.representation << std::right << std::setw(10) << std::setprecision(3) << c.image.error
        << std::setw(10) << std::setprecision(1) << c.cost << std::setw(10) << c.memory_bytes << "  "
        << (c.meets_tolerance ? "yes" : "no") << (c.realtime ? "" : " (offline)") << (advice.choice == i ? "  <- choice" : "") << "\n";
  }
  out << std::setprecision(3);
  if (advice.choice) {
    out << "\nchoice: " << advice.candidates[*advice.choice].representation << "; cheaper ones fail:";
    bool any = false;
    for (std::size_t i = 0; i < *advice.choice; ++i) {
      const auto& c = advice.candidates[i];
      out << (any ? "," : "") << " " << c.representation << " (" << c.image.error << " at the " << c.image.pattern << ")";
      any = true;
    }
    out << (any ? "\n" : " none\n");
  } else {
    out << "\nno candidate meets the tolerance for this target\n";
  }
  if (!advice.object_warning.empty()) out << "warning: " << advice.object_warning << "\n";
  return out.str();
}

}  // namespace bssrdf
