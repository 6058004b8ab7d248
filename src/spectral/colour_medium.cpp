#include "bssrdf/spectral/colour_medium.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/scalar_math.hpp"

namespace bssrdf::spectral {
namespace {

constexpr const char* kChannels[] = {"R", "G", "B"};

// The colour channels of a spectral medium under one model: sums over its wavelengths with the colour weights.
struct Integration {
  std::vector<Reduced<double>> media;  // per wavelength
  std::vector<Vec3> weight;            // per wavelength: its weight in R, G, B
  std::shared_ptr<const Model> model;

  double reflectance(int c, double r) const {
    double sum = 0;
    for (std::size_t i = 0; i < media.size(); ++i) sum += weight[i][c] * model->reflectance(media[i], r);
    return sum;
  }
  double total(int c) const {
    double sum = 0;
    for (std::size_t i = 0; i < media.size(); ++i) sum += weight[i][c] * model->total_reflectance(media[i]);
    return sum;
  }
  double cumulative(int c, double r) const {
    double sum = 0;
    for (std::size_t i = 0; i < media.size(); ++i) sum += weight[i][c] * model->cumulative_reflectance(media[i], r);
    return sum;
  }
};

// The Model face of an Integration: evaluated at the coefficients of one of `rgb`'s channels, it answers for that
// colour channel. Validity: each wavelength's notes, once per kind, naming the first wavelength that has it.
class ColourModel : public Model {
 public:
  ColourModel(Integration integration, Medium rgb, std::vector<double> wavelength_nm)
      : in_(std::move(integration)), rgb_(std::move(rgb)), nm_(std::move(wavelength_nm)) {}

  std::string name() const override { return in_.model->name(); }
  std::string description() const override {
    return in_.model->description() + ", integrated per radius over " + std::to_string(nm_.size()) +
           " wavelengths to colour";
  }
  bool includes_single_scattering() const override { return in_.model->includes_single_scattering(); }
  double reflectance(const Reduced<double>& m, double r) const override { return in_.reflectance(channel(m), r); }
  double total_reflectance(const Reduced<double>& m) const override { return in_.total(channel(m)); }
  double cumulative_reflectance(const Reduced<double>& m, double r) const override {
    return in_.cumulative(channel(m), r);
  }
  double albedo_prime_from_total(double, double, double) const override {
    throw InvalidInput("colour: a colour channel has no albedo of its own to invert (integrate each wavelength)");
  }

 protected:
  ValidityReport check_validity(const Reduced<double>& m) const override {
    channel(m);
    ValidityReport out;
    std::map<std::string, std::size_t> seen;  // code -> index in out
    for (std::size_t i = 0; i < in_.media.size(); ++i)
      for (auto note : in_.model->validity(in_.media[i])) {
        if (seen.count(note.code)) continue;
        seen[note.code] = out.size();
        note.message = "at " + format_number(nm_[i]) + " nm: " + note.message;
        out.push_back(std::move(note));
      }
    return out;
  }

 private:
  int channel(const Reduced<double>& m) const {
    for (int c = 0; c < 3; ++c)
      if (m.sigma_a == rgb_.sigma_a[c] && m.sigma_s == rgb_.sigma_s[c] && m.g == rgb_.g[c]) return c;
    BSSRDF_CHECK(!"a colour model is evaluated at the coefficients of one of its colour channels");
    return 0;
  }

  Integration in_;
  Medium rgb_;
  std::vector<double> nm_;
};

std::string percent(double fraction) {  // three significant digits: a small negative part is not "0 %"
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %%", 100 * fraction);
  return text;
}

}  // namespace

ColourNote colour_note(const std::vector<double>& wavelength_nm, const ColourSettings& settings) {
  return ColourNote{std::string(kObserverName), std::string(to_string(settings.illuminant)),
                    std::string(to_string(settings.space)), wavelength_nm};
}

std::string describe(const ColourNote& note) {
  return note.space + " under " + note.illuminant + ", " + note.observer + " observer, from " +
         std::to_string(note.wavelength_nm.size()) + " wavelengths (" + format_number(note.wavelength_nm.front()) +
         "-" + format_number(note.wavelength_nm.back()) + " nm)";
}

std::vector<double> wavelengths_from_channel_names(const std::vector<std::string>& names) {
  std::vector<double> out;
  for (const auto& name : names) {
    if (name.size() < 3 || name.compare(name.size() - 2, 2, "nm") != 0) return {};
    std::size_t used = 0;
    double nm = 0;
    try {
      nm = std::stod(name.substr(0, name.size() - 2), &used);
    } catch (const std::exception&) {
      return {};
    }
    if (used != name.size() - 2 || !std::isfinite(nm)) return {};
    out.push_back(nm);
  }
  return out;
}

std::string ColourMedium::negative_note() const {
  std::string out;
  for (int c = 0; c < 3; ++c)
    if (negative[c] > 1e-9)
      out += std::string("; ") + kChannels[c] + " < 0 from " + format_number(std::round(negative_from[c] * 1e3) / 1e3) +
             " mm (the light left there has a colour outside " + note.space + "), its negative part " +
             percent(negative[c]) + " of its total";
  return out;
}

std::string ColourMedium::summary() const {
  std::string fit;
  for (int c = 0; c < 3; ++c) fit += std::string(c ? ", " : "") + kChannels[c] + " " + percent(shape_error[c]);
  return describe(note) + "; R_c(r) = sum over 1 nm of R(r, lambda) S(lambda) cbar(lambda) / sum of " +
         "S(lambda) ybar(lambda), per radius, each wavelength's own " + spectral_model +
         " profile; R, G, B coefficients: those whose " + spectral_model +
         " profile has each colour channel's total and median radius (relative L2 shape error " + fit + ")" +
         negative_note();
}

ColourMedium colour_medium(const Medium& medium, std::shared_ptr<const Model> model, const ColourSettings& settings) {
  if (!medium.spectral())
    throw InvalidInput("colour: needs a spectral medium (--wavelengths, or a material with wavelengths)");
  BSSRDF_CHECK(model != nullptr);
  medium.validate();
  const ColourIntegrator colour(medium.wavelength_nm, settings);
  Integration in{{}, colour.rgb_weights(), model};
  for (std::size_t i = 0; i < medium.channels(); ++i) in.media.push_back(medium.reduced(i));
  double g = 0;  // luminance-weighted (the Y weights are >= 0 and sum to 1 over a white reflector)
  for (std::size_t i = 0; i < medium.channels(); ++i) g += colour.xyz_weights()[i][1] * medium.g[i];
  if (std::all_of(medium.g.begin(), medium.g.end(), [&](double x) { return x == medium.g[0]; })) g = medium.g[0];

  ColourMedium out;
  out.spectral_model = model->name();
  out.note = colour_note(medium.wavelength_nm, settings);
  out.rgb.eta = medium.eta;
  const double ell_min = transport_mfp_range(medium).min;
  double r_far = 0;
  for (const auto& m : in.media)
    if (m.sigma_s > 0) r_far = std::max(r_far, model->radius_for_fraction(m, 1 - 1e-5));
  for (int c = 0; c < 3; ++c) {
    const std::string channel = kChannels[c];
    const double total = in.total(c);
    // alpha' (at sigma_t' = 1) whose total is the colour channel's: the total rises with alpha'.
    const auto unit = [&](double albedo_prime) {
      return reduce(1 - albedo_prime, albedo_prime / (1 - g), g, medium.eta);
    };
    const double highest = model->total_reflectance(unit(1 - 1e-12));
    if (!(total > 0 && total < highest))
      throw InvalidInput("colour", "channel " + channel + " total reflectance " + format_number(total),
                         "0 < total < " + format_number(highest) + " (the " + model->name() +
                             " model's largest here); a colour outside the space's gamut has no coefficients");
    const double albedo_prime = model->albedo_prime_from_total(total, medium.eta, g);
    // Scale: profiles of similar media scale as R(r; s sigma) = s^2 R(s r; sigma), so r_50 sets sigma_t'.
    const double r50_colour =
        radius_where([&](double r) { return in.cumulative(c, r); }, 0.5 * total, std::max(ell_min, 1e-9));
    const double r50_unit = model->radius_for_fraction(unit(albedo_prime), 0.5);
    if (!(std::isfinite(r50_colour) && r50_colour > 0))
      throw InvalidInput("colour", "channel " + channel, "a profile that holds half its total at a finite radius");
    const double sigma_t_prime = r50_unit / r50_colour;
    out.rgb.channel_names.push_back(channel);
    out.rgb.sigma_a.push_back((1 - albedo_prime) * sigma_t_prime);
    out.rgb.sigma_s.push_back(albedo_prime * sigma_t_prime / (1 - g));
    out.rgb.g.push_back(g);
    out.total.push_back(total);
    // Distinct coefficients per channel, so the colour model knows which one it is asked about.
    for (int k = 0; k < c; ++k)
      if (out.rgb.sigma_a[k] == out.rgb.sigma_a[c] && out.rgb.sigma_s[k] == out.rgb.sigma_s[c])
        out.rgb.sigma_s[c] = std::nextafter(out.rgb.sigma_s[c], 2 * out.rgb.sigma_s[c] + 1);
    // Shape error and negative part over log-spaced radii from 1e-3 ell to where every wavelength has left 1e-5 of
    // its total: the longest-reaching wavelengths may be of a colour outside the space, negative in some channel.
    const auto m = out.rgb.reduced(static_cast<std::size_t>(c));
    const double r_lo = 1e-3 * std::min(ell_min, m.ell);
    double difference = 0, norm = 0, negative = 0, negative_from = 0;
    const int n = 600;
    for (int k = 0; k <= n; ++k) {  // int r f^2 dr = int r^2 f^2 d(ln r)
      const double r = r_lo * std::pow(r_far / r_lo, static_cast<double>(k) / n);
      const double target = in.reflectance(c, r), fitted = model->reflectance(m, r);
      const double w = (k == 0 || k == n ? 0.5 : 1.0) * r * r;
      difference += w * (fitted - target) * (fitted - target);
      norm += w * target * target;
      if (target < 0 && negative_from == 0) negative_from = r;
      negative -= w * std::min(target, 0.0) * kTwoPi * std::log(r_far / r_lo) / n;
    }
    out.shape_error.push_back(norm > 0 ? std::sqrt(difference / norm) : 0.0);
    out.negative.push_back(negative / total);
    out.negative_from.push_back(negative_from);
  }
  out.rgb.validate();
  out.model = std::make_shared<ColourModel>(std::move(in), out.rgb, medium.wavelength_nm);
  return out;
}

ColourMaterial colour_material(const Material& material, const ColourSettings& settings) {
  ColourMaterial out{material,
                     colour_medium(material.medium, make_model(default_model(material.medium).name), settings)};
  out.material.medium = out.colour.rgb;
  out.material.notes.insert(out.material.notes.begin(), "colour: " + out.colour.summary());
  return out;
}

}  // namespace bssrdf::spectral
