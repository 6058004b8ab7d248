#include "bssrdf/models/layered.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "bssrdf/error.hpp"
#include "bssrdf/hankel.hpp"
#include "bssrdf/models/diffusion_validity.hpp"
#include "bssrdf/models/image_source.hpp"
#include "bssrdf/quadrature.hpp"

namespace bssrdf::layered {

Stack::Stack(const LayerStack& stack, std::size_t channel, multipole::BoundaryA boundary)
    : semi_infinite_(stack.semi_infinite()) {
  stack.validate();
  if (channel >= stack.channels())
    throw InvalidInput("channel", std::to_string(channel), "< " + std::to_string(stack.channels()));
  const auto& L = stack.layers;
  for (std::size_t i = 0; i < L.size(); ++i) {
    if (L[i].clear(channel))
      throw InvalidInput("layers[" + std::to_string(i) + "].sigma_a + sigma_s[" + stack.channel_names[channel] + "]",
                         "0", "> 0: a clear layer is not diffusive (use the Monte Carlo reference)");
    const double above = i == 0 ? stack.ambient_above : L[i - 1].n;
    const double below = i + 1 == L.size() ? stack.ambient_below : L[i + 1].n;
    media_.push_back(reduce(L[i].sigma_a[channel], L[i].sigma_s[channel], L[i].g[channel], L[i].n / above));
    const double d = L[i].thickness == kSemiInfinite ? 1.0 : L[i].thickness;
    slabs_.push_back(multipole::make_slab(d, L[i].n / above, L[i].n / below, boundary));
    names_.push_back(L[i].name.empty() ? "layers[" + std::to_string(i) + "]" : L[i].name);
  }
}

StackSpectra Stack::spectra(double k) const {
  // Fold from the bottom: (R, T) of everything below the current layer, lit from above.
  const std::size_t n = media_.size();
  StackSpectra below{0, 0};
  std::size_t i = n;
  if (semi_infinite_) {
    const auto& m = media_.back();
    const double s = std::sqrt(m.sigma_tr * m.sigma_tr + k * k), z_b = extrapolation_distance(slabs_.back().A_top, m.D);
    below = {m.albedo_prime * 0.5 * (std::exp(-m.ell * s) + std::exp(image_depth(m.ell, z_b) * s)), 0.0};
    --i;
  }
  bool first = !semi_infinite_;
  while (i-- > 0) {
    const auto down = multipole::spectra_at_k(media_[i], slabs_[i], k);
    if (first) {
      below = {down.reflectance(), down.transmittance()};
      first = false;
      continue;
    }
    const auto up = multipole::spectra_at_k(media_[i], multipole::flipped(slabs_[i]), k);
    const double bounce = 1 / (1 - below.reflectance * up.reflectance());
    below = {down.reflectance() + down.transmittance() * below.reflectance * up.transmittance() * bounce,
             down.transmittance() * below.transmittance * bounce};
  }
  return below;
}

double Stack::reflectance(double r) const {
  return hankel_transform([&](double k) { return spectra(k).reflectance; }, r, 1 / media_[0].ell) /
         (2 * std::numbers::pi);
}

double Stack::transmittance(double r) const {
  if (semi_infinite_) return 0;
  return hankel_transform([&](double k) { return spectra(k).transmittance; }, r, 1 / media_[0].ell) /
         (2 * std::numbers::pi);
}

double Stack::radius_for_fraction(double fraction, bool transmitted) const {
  if (!(fraction > 0 && fraction < 1))
    throw InvalidInput("energy fraction", format_number(fraction), "0 < fraction < 1");
  const double total = transmitted ? total_transmittance() : total_reflectance();
  if (!(total > 0)) return std::numeric_limits<double>::infinity();
  // int_0^rho 2 pi r R dr = rho int_0^inf F(k) J1(k rho) dk: one Hankel-type integral per radius.
  const auto cumulative = [&](double rho) {
    const auto f = [&](double k) {
      const auto s = spectra(k);
      return (transmitted ? s.transmittance : s.reflectance) * std::cyl_bessel_j(1.0, k * rho) * rho;
    };
    double sum = 0, a = 0;
    for (int m = 1; m < 100000; ++m) {
      const double b = (m + 0.25) * std::numbers::pi / rho;  // near the zeros of J1
      const double piece = integrate_adaptive(f, a, b, 1e-9, 1e-12 * total, 200, 1).value;
      sum += piece;
      if (m > 3 && std::abs(piece) < 1e-10 * total) break;
      a = b;
    }
    return sum;
  };
  // Each cumulative value is a Hankel-type integral: 1e-6 relative precision is plenty.
  return radius_where(cumulative, fraction * total, media_[0].ell, 1e-6);
}

ValidityReport Stack::validity() const {
  ValidityReport report;
  const std::size_t finite = semi_infinite_ ? media_.size() - 1 : media_.size();
  for (std::size_t i = 0; i < finite; ++i) {
    const double t = slabs_[i].thickness / media_[i].ell;
    const std::string text = names_[i] + ": d = " + format_number(std::round(t * 1000) / 1000) + " ell";
    if (t < 2)
      report.push_back({Severity::invalid, "thin_layer", text + " < 2 ell: the multipole is not valid in thin layers"});
    else if (t < 4)
      report.push_back({Severity::warning, "thin_layer", text + " < 4 ell: near the multipole's thin-slab limit"});
  }
  const auto totals = spectra(0);
  if (totals.transmittance < 0)
    report.push_back({Severity::invalid, "negative_transmittance",
                      "T_total = " + format_number(std::round(totals.transmittance * 1e5) / 1e5) + " < 0"});
  if (totals.reflectance < 0)
    report.push_back({Severity::invalid, "negative_reflectance",
                      "R_total = " + format_number(std::round(totals.reflectance * 1e5) / 1e5) + " < 0"});
  report.push_back({Severity::note, "layer_adding",
                    "layers combined by the adding equations on multipole spectra (Donner & Jensen 2005): light "
                    "crossing an interface is treated as a new source at one ell; see the README for its measured "
                    "error against Monte Carlo"});
  for (const auto& note : diffusion_validity(media_[0], measured_limits("dipole")))
    if (note.code != "near_field") report.push_back({note.severity, note.code, names_[0] + ": " + note.message});
  return report;
}

}  // namespace bssrdf::layered
