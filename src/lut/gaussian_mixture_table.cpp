#include "bssrdf/lut/gaussian_mixture_table.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/profile_report.hpp"

namespace bssrdf {
namespace {
bool scatters(const Medium& medium, std::size_t c) { return medium.sigma_s[c] > 0; }
}  // namespace

std::size_t GaussianMixtureTable::count() const {
  std::size_t n = 0;
  for (const auto& w : weight) n = std::max(n, w.size());
  return n;
}

GaussianMixtureTable quantized_mixture_table(const Medium& medium, const quantized_diffusion::Model& model) {
  return own_mixture_table(medium, model);
}

GaussianMixtureTable own_mixture_table(const Medium& medium, const Model& model) {
  medium.validate();
  const auto& own = model_entry(model.name()).own_gaussians;
  if (!own)
    throw InvalidInput("model", std::string("'").append(model.name()).append("'"),
                       "a model with its own Gaussian mixture (quantized)");
  const auto start = std::chrono::steady_clock::now();
  GaussianMixtureTable t;
  t.method = "the model's own mixture: " + model.description();
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
    const auto mix = own(model, m);
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

LookupTable to_lookup_table(const GaussianMixtureTable& t, const TableContext& context) {
  auto out = described_table("gaussians", t.count(), 1, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  out.set("bssrdf:method", t.method);
  out.set("bssrdf:formula", "R(r) = sum_k w_k G2(v_k, r), G2(v, r) = exp(-r^2 / (2 v)) / (2 pi v); r in " + u +
                                ", v in " + u + "^2, R per entered flux");
  out.set("bssrdf:normalization",
          std::string("per_entered_flux: sum_k w_k is the channel's total diffuse reflectance"));
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
    for (std::size_t k = 0; k < n; ++k)
      o[k] = k < v.size() ? v[k] * fill_scale : repeat && !v.empty() ? v.back() * fill_scale : 0.0;
    return o;
  };
  if (t.shared_variance) {
    out.add_channel("variance", "variance v_k, " + u + "^2", padded(t.variance[0], 1 / (mm * mm), true));
    for (std::size_t c = 0; c < t.channel_names.size(); ++c)
      out.add_channel(t.channel_names[c], "weight w_k (reflectance carried by Gaussian k)",
                      padded(t.weight[c], 1, false));
  } else {
    for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
      out.add_channel("variance." + t.channel_names[c],
                      "variance v_k of channel " + t.channel_names[c] + ", " + u + "^2",
                      padded(t.variance[c], 1 / (mm * mm), true));
      out.add_channel(t.channel_names[c], "weight w_k (reflectance carried by Gaussian k)",
                      padded(t.weight[c], 1, false));
    }
  }
  return out;
}

std::string summary(const GaussianMixtureTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  s << "Gaussian mixture: " << t.count() << " Gaussians (" << (t.shared_variance ? "shared" : "per-channel")
    << " variances) in " << short_number(t.seconds * 1000) << " ms; " << t.method << '\n';
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    if (t.total_reflectance[c] == 0) {
      s << "  " << t.channel_names[c] << ": does not scatter (total reflectance 0): every weight 0\n";
      continue;
    }
    s << "  " << t.channel_names[c] << ": " << t.weight[c].size() << " Gaussians, variances "
      << short_number(t.variance[c].front() / (mm * mm)) << " to " << short_number(t.variance[c].back() / (mm * mm))
      << ' ' << u << "^2; sum of weights / total reflectance - 1 = " << short_number(t.conservation_error[c]);
    if (t.shared_variance) s << "; relative L2 error " << short_number(t.relative_l2_error[c]);
    s << '\n';
  }
  return s.str();
}

}  // namespace bssrdf
