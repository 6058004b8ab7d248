#include "bssrdf/lut/gaussian_mixture_table.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/fit/inverse_fits.hpp"
#include "bssrdf/profile_report.hpp"

namespace bssrdf {
namespace {
// Innermost fitted radius, in transport mfp of the clearest channel: 0.05 keeps Skin1 pbd within 8 %
// of its total (1e-3: 39 % short; 0.2: 12 %, the near field then missing).
constexpr double kFitInner = 0.05;

bool scatters(const Medium& medium, std::size_t c) { return medium.sigma_s[c] > 0; }
}  // namespace

std::size_t GaussianMixtureTable::count() const {
  std::size_t n = 0;
  for (const auto& w : weight) n = std::max(n, w.size());
  return n;
}

GaussianMixtureTable quantized_mixture_table(const Medium& medium, const quantized_diffusion::Model& model) {
  medium.validate();
  const auto start = std::chrono::steady_clock::now();
  GaussianMixtureTable t;
  t.method = "quantized diffusion's own mixture (d'Eon & Irving 2011), time-bin ratio chosen for tolerance 1e-3";
  t.shared_variance = false;
  t.channel_names = medium.channel_names;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto m = medium.reduced(c);
    if (!scatters(medium, c)) {
      t.variance.push_back({1.0});  // any variance: its weight is 0
      t.weight.push_back({0.0});
      t.total_reflectance.push_back(0);
      t.conservation_error.push_back(0);
      t.relative_l2_error.push_back(0);
      continue;
    }
    const auto mix = model.gaussians(m);
    t.variance.push_back(mix.variance);
    t.weight.push_back(mix.weight);
    double sum = 0;
    for (double w : mix.weight) sum += w;
    const double total = model.total_reflectance(m);
    t.total_reflectance.push_back(total);
    t.conservation_error.push_back(sum / total - 1);
    t.relative_l2_error.push_back(0);  // the mixture is the model
  }
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

GaussianMixtureTable fitted_mixture_table(const Medium& medium, const Model& model, int count, std::size_t samples) {
  medium.validate();
  if (count < 1 || count > 32) throw InvalidInput("count", std::to_string(count), "1 to 32");
  if (samples < 8 || samples > 100000) throw InvalidInput("samples", std::to_string(samples), "8 to 100000");
  const auto start = std::chrono::steady_clock::now();
  // From 0.05 transport mfp out (not 1e-3 as default_radii_mm): profiles singular at 0 (single
  // scattering, Burley's 1/r) make int r R^2 dr diverge there, and the fit would spend every
  // Gaussian on the first micrometres and lose the tail's energy.
  const auto radii = log_spaced(kFitInner * transport_mfp_range(medium).min, default_radii_mm(medium, model, 2).back(), samples);
  // Channels without scattering (sigma_s = 0) reflect nothing: weight 0 for every Gaussian, out of the fit.
  std::vector<NamedProfile> profiles;
  std::vector<double> totals;
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    if (!scatters(medium, c)) continue;
    profiles.push_back({medium.channel_names[c], model.sample(medium.reduced(c), radii)});
    totals.push_back(model.total_reflectance(medium.reduced(c)));
  }
  if (profiles.empty())
    throw InvalidInput("profile", "0 in every channel", "a medium that scatters (sigma_s > 0) in at least one channel");
  const auto report = fit_gaussians(profiles, count, LengthUnit::millimetre, model.name() + " profile", totals);
  GaussianMixtureTable t;
  t.method = "least-squares fit of " + std::to_string(count) + " shared-variance Gaussians to the " + model.name() +
             " profile on " + std::to_string(samples) + " radii (min int r (R - sum w G2)^2 dr, weights >= 0, weights held to the model's total; bssrdf fit gaussians)";
  t.shared_variance = true;
  t.channel_names = medium.channel_names;
  std::vector<double> variance;
  for (int k = 1; k <= count; ++k) variance.push_back(report.find("variance_" + std::to_string(k))->value);
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const auto& name = medium.channel_names[c];
    if (!scatters(medium, c)) {
      t.variance.push_back(variance);
      t.weight.emplace_back(count, 0.0);
      t.total_reflectance.push_back(0);
      t.conservation_error.push_back(0);
      t.relative_l2_error.push_back(0);
      continue;
    }
    std::vector<double> w;
    double sum = 0;
    for (int k = 1; k <= count; ++k) {
      w.push_back(report.find("weight_" + std::to_string(k), name)->value);
      sum += w.back();
    }
    const double total = model.total_reflectance(medium.reduced(c));
    t.variance.push_back(variance);
    t.weight.push_back(std::move(w));
    t.total_reflectance.push_back(total);
    t.conservation_error.push_back(sum / total - 1);
    t.relative_l2_error.push_back(report.find("relative_l2_error", name)->value);
  }
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

LookupTable to_lookup_table(const GaussianMixtureTable& t, const TableContext& context) {
  auto out = described_table("gaussians", t.count(), 1, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  out.set("bssrdf:method", t.method);
  out.set("bssrdf:formula", "R(r) = sum_k w_k G2(v_k, r), G2(v, r) = exp(-r^2 / (2 v)) / (2 pi v); r in " + u + ", v in " + u +
                                "^2, R per entered flux");
  out.set("bssrdf:normalization", std::string("per_entered_flux: sum_k w_k is the channel's total diffuse reflectance"));
  out.set("bssrdf:variances", std::string(t.shared_variance ? "shared by all channels (channel 'variance')"
                                                            : "per channel ('variance.<c>'); padding has weight 0"));
  out.set("bssrdf:count", static_cast<int>(t.count()));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    const auto& name = t.channel_names[c];
    out.set("bssrdf:count." + name, static_cast<int>(t.weight[c].size()));
    if (t.total_reflectance[c] == 0)
      out.set("bssrdf:note." + name, std::string("the channel does not scatter (sigma_s = 0): every weight is 0"));
    out.set("bssrdf:total_reflectance." + name, t.total_reflectance[c]);
    out.set("bssrdf:conservation_error." + name, t.conservation_error[c]);
    if (t.shared_variance) out.set("bssrdf:relative_l2_error." + name, t.relative_l2_error[c]);
  }
  const std::size_t n = t.count();
  const auto padded = [&](const std::vector<double>& v, double fill_scale, bool repeat) {
    std::vector<double> o(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) o[k] = k < v.size() ? v[k] * fill_scale : repeat && !v.empty() ? v.back() * fill_scale : 0.0;
    return o;
  };
  if (t.shared_variance) {
    out.add_channel("variance", "variance v_k, " + u + "^2", padded(t.variance[0], 1 / (mm * mm), true));
    for (std::size_t c = 0; c < t.channel_names.size(); ++c)
      out.add_channel(t.channel_names[c], "weight w_k (reflectance carried by Gaussian k)", padded(t.weight[c], 1, false));
  } else {
    for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
      out.add_channel("variance." + t.channel_names[c], "variance v_k of channel " + t.channel_names[c] + ", " + u + "^2",
                      padded(t.variance[c], 1 / (mm * mm), true));
      out.add_channel(t.channel_names[c], "weight w_k (reflectance carried by Gaussian k)", padded(t.weight[c], 1, false));
    }
  }
  return out;
}

std::string summary(const GaussianMixtureTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  s << "Gaussian mixture: " << t.count() << " Gaussians (" << (t.shared_variance ? "shared" : "per-channel") << " variances) in "
    << short_number(t.seconds * 1000) << " ms; " << t.method << '\n';
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    if (t.total_reflectance[c] == 0) {
      s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): every weight 0\n";
      continue;
    }
    s << "  " << t.channel_names[c] << ": " << t.weight[c].size() << " Gaussians, variances "
      << short_number(t.variance[c].front() / (mm * mm)) << " to " << short_number(t.variance[c].back() / (mm * mm)) << ' ' << u
      << "^2; sum of weights / total reflectance - 1 = " << short_number(t.conservation_error[c]);
    if (t.shared_variance) s << "; relative L2 error " << short_number(t.relative_l2_error[c]);
    s << '\n';
  }
  return s.str();
}

}  // namespace bssrdf
