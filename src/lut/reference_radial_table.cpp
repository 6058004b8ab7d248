#include "bssrdf/lut/reference_radial_table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/lut/interpolation.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/montecarlo.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#include "bssrdf/spectral/colour_reference.hpp"

namespace bssrdf {

ReferenceRadialTable build_reference_radial_table(const LayerStack& stack, const ReferenceRadialOptions& options) {
  stack.validate();
  if (options.bins < 4 || options.bins > 4096) throw InvalidInput("bins", std::to_string(options.bins), "4 to 4096");
  if (options.photons < 1000) throw InvalidInput("photons", std::to_string(options.photons), ">= 1000");
  const auto ell = transport_mfp_range(stack);
  if (!(ell.max > 0))
    throw InvalidInput("layers", "no attenuation in any layer or channel", "sigma_a + sigma_s > 0 somewhere");
  MonteCarloOptions mc;
  mc.photons = options.photons;
  mc.seed = options.seed;
  mc.threads = options.threads;
  mc.progress = options.progress;
  mc.spacing = BinSpacing::log;
  mc.bins = options.bins;
  mc.r_min = 1e-3 * ell.min;
  mc.r_max = std::max(30 * ell.max, 10 * mc.r_min);
  auto run = run_monte_carlo(stack, mc);
  if (options.colour) {  // each wavelength's run integrated to R, G, B, bin by bin
    const auto nm = spectral::wavelengths_from_channel_names(stack.channel_names);
    if (nm.empty())
      throw InvalidInput("colour: needs channels named by wavelength (e.g. 550nm: --wavelengths, a spectral material)");
    run = spectral::colour_reference(run, nm, *options.colour);
  }

  ReferenceRadialTable t;
  t.options = options;
  for (const auto& channel : run.channels) t.channel_names.push_back(channel.name);
  t.r_inner = run.bin_inner;
  t.r_outer = run.bin_outer;
  t.radius = run.bin_radius;
  const std::size_t N = t.size();
  for (std::size_t j = 0; j < N; ++j) t.u.push_back(static_cast<double>(j) / static_cast<double>(N - 1));
  for (const auto& per_incident : run.channels) {
    const auto c = per_incident.per_entered_flux();
    std::vector<double> ring(N), cum(N), cdf(N), log_r(N);
    double sum = 0;
    for (std::size_t j = 0; j < N; ++j) {
      ring[j] = 2 * std::numbers::pi * t.radius[j] * c.reflectance[j];
      sum += std::numbers::pi * (t.r_outer[j] * t.r_outer[j] - t.r_inner[j] * t.r_inner[j]) * c.reflectance[j];
      cum[j] = sum;
    }
    for (std::size_t j = 0; j < N; ++j) {
      cdf[j] = sum > 0 ? cum[j] / sum : 1.0;
      log_r[j] = std::log(t.r_outer[j]);
    }
    // The CDF is known at the bins' outer edges: interpolated in ln r between them. No light: all at r = 0.
    auto inverse = sum > 0 ? inverse_cdf(
                                 cdf, t.r_outer, log_r, [](double x) { return std::exp(x); }, t.u)
                           : std::vector<double>(N, 0.0);
    t.reflectance.push_back(c.reflectance);
    t.reflectance_stderr.push_back(c.reflectance_stderr);
    t.ring.push_back(std::move(ring));
    t.cdf.push_back(std::move(cdf));
    t.inverse_cdf.push_back(std::move(inverse));
    t.total_reflectance.push_back(c.diffuse_reflectance.value);
    t.total_stderr.push_back(c.diffuse_reflectance.standard_error);
    t.table_reflectance.push_back(sum);
  }
  return t;
}

TableColour reference_table_colour(const ReferenceRadialTable& t, const std::vector<double>& wavelength_nm) {
  BSSRDF_CHECK(t.options.colour.has_value());
  TableColour out{spectral::colour_note(wavelength_nm, *t.options.colour), {}};
  out.line = spectral::describe(out.note) +
             "; per bin R_c = sum over 1 nm of R(lambda) S(lambda) cbar(lambda) / sum of S(lambda) ybar(lambda), each "
             "wavelength's own Monte Carlo run, standard errors sqrt(sum w^2 se^2)";
  // Bins negative beyond two standard errors: a colour outside the space there, not noise (a bin with few photons
  // of wavelengths with negative weights may be negative by chance).
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    std::size_t count = 0, first = 0;
    for (std::size_t j = t.size(); j-- > 0;)
      if (t.reflectance[c][j] < -2 * t.reflectance_stderr[c][j]) ++count, first = j;
    if (count)
      out.line += "; " + t.channel_names[c] + " < 0 beyond 2 standard errors in " + std::to_string(count) +
                  " bins from " + short_number(t.r_inner[first]) + " mm (a colour outside " + out.note.space +
                  "; not clipped: its CDF is not a sampling distribution there)";
  }
  return out;
}

LookupTable to_lookup_table(const ReferenceRadialTable& t, const TableContext& context) {
  auto out = described_table("radial", t.size(), 1, context);
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  const auto scaled = [](std::vector<double> v, double s) {
    for (auto& x : v) x *= s;
    return v;
  };
  out.set("bssrdf:model", std::string("monte carlo"));
  out.set("bssrdf:model_description",
          "Monte Carlo reference (radiative transfer, true Henyey-Greenstein phase function, Fresnel boundaries): " +
              std::to_string(t.options.photons) + " photons per channel, seed " + std::to_string(t.options.seed));
  out.set("bssrdf:includes_single_scattering", std::string("yes"));
  out.set("bssrdf:distance", "radius r on the surface from the point of incidence, in " + u);
  out.set("bssrdf:normalization",
          std::string("per_entered_flux: R is the bin average of the exitance per unit flux that entered the medium"));
  out.set("bssrdf:grid",
          "bins: [0, r_outer_0), then geometric; channel radius holds each bin's centre (geometric mean; r_outer_0 / 2 "
          "for the first), r_inner and r_outer its edges");
  out.set("bssrdf:size", static_cast<int>(t.size()));
  out.set("bssrdf:r_min", t.r_outer.front() / mm);
  out.set("bssrdf:r_max", t.r_outer.back() / mm);
  out.set("bssrdf:photons", static_cast<double>(t.options.photons));
  out.set("bssrdf:seed", static_cast<double>(t.options.seed));
  out.set("bssrdf:error",
          std::string("statistical: stderr.<c> is each bin's standard error (no interpolation tolerance)"));
  out.set(
      "bssrdf:cdf",
      std::string(
          "cdf.<c> at r_outer: int_0^{r_outer} 2 pi r R dr / the table's total; inverse_cdf.<c> at u_j = j / (N - 1)"));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c) {
    const auto& name = t.channel_names[c];
    out.set("bssrdf:total_reflectance." + name, t.total_reflectance[c]);
    out.set("bssrdf:total_reflectance_stderr." + name, t.total_stderr[c]);
    out.set("bssrdf:table_reflectance." + name, t.table_reflectance[c]);
  }
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    out.add_channel(t.channel_names[c], "R(r) bin average, 1/" + u + "^2 per unit entered flux",
                    scaled(t.reflectance[c], mm * mm));
  out.add_channel("radius", "bin centre, " + u, scaled(t.radius, 1 / mm));
  out.add_channel("r_inner", "bin inner edge, " + u, scaled(t.r_inner, 1 / mm));
  out.add_channel("r_outer", "bin outer edge, " + u, scaled(t.r_outer, 1 / mm));
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    out.add_channel("stderr." + t.channel_names[c], "standard error of R, 1/" + u + "^2",
                    scaled(t.reflectance_stderr[c], mm * mm));
  add_sampling_channels(out, t.channel_names, t.ring, t.cdf, t.u, t.inverse_cdf, "CDF of 2 pi r R(r) at r_outer",
                        context.unit);
  return out;
}

std::string summary(const ReferenceRadialTable& t, const TableContext& context) {
  const double mm = millimetres_per(context.unit);
  const std::string u(symbol(context.unit));
  std::ostringstream s;
  s << "radial table from the Monte Carlo reference: " << t.size() << " bins from "
    << short_number(t.r_outer.front() / mm) << " to " << short_number(t.r_outer.back() / mm) << ' ' << u
    << " (logarithmic), " << t.options.photons << " photons per channel, seed " << t.options.seed
    << "; values are bin averages with standard errors (stderr.<c>)\n";
  for (std::size_t c = 0; c < t.channel_names.size(); ++c)
    s << "  " << t.channel_names[c] << ": total reflectance " << short_number(t.total_reflectance[c]) << " +- "
      << short_number(t.total_stderr[c]) << ", "
      << short_number(100 * (t.total_reflectance[c] > 0 ? t.table_reflectance[c] / t.total_reflectance[c] : 1))
      << " % of it inside the table\n";
  return s.str();
}

}  // namespace bssrdf
