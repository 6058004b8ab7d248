#include "bssrdf/skin/skin_model.hpp"

#include <cmath>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/skin/chromophores.hpp"

namespace bssrdf::skin {

const std::vector<NamedRange>& skin_parameter_ranges() {
  static const std::vector<NamedRange> ranges = {
      {"melanin", &SkinParameters::melanin, 0, 0.6, "", "volume fraction of melanosomes in the epidermis"},
      {"eumelanin", &SkinParameters::eumelanin, 0, 1, "", "eumelanin share of the melanin (rest pheomelanin)"},
      {"blood", &SkinParameters::blood, 0, 0.3, "", "volume fraction of blood in the dermis"},
      {"oxygenation", &SkinParameters::oxygenation, 0, 1, "", "oxygen saturation of the haemoglobin"},
      {"epidermis", &SkinParameters::epidermis_mm, 0.01, 0.5, "mm", "epidermal thickness"},
      {"scattering", &SkinParameters::scattering_500, 0.1, 20, "1/mm", "reduced scattering at 500 nm"},
      {"scattering-power", &SkinParameters::scattering_power, 0, 4, "", "b in mu_s' = a (lambda/500 nm)^-b"},
      {"water", &SkinParameters::water, 0, 0.9, "", "volume fraction of water in the dermis"},
      {"g", &SkinParameters::g, 0, 0.95, "", "Henyey-Greenstein mean cosine"},
      {"eta", &SkinParameters::eta, 1, 2, "", "refractive index of skin, in air"},
  };
  return ranges;
}

void SkinParameters::validate() const {
  for (const auto& r : skin_parameter_ranges()) {
    const double v = this->*r.member;
    if (!(v >= r.min && v <= r.max))
      throw InvalidInput(r.name, format_number(v), format_number(r.min) + " to " + format_number(r.max));
  }
  if (blood + water > 1) throw InvalidInput("blood + water", format_number(blood + water), "at most 1");
}

namespace {

double reduced_scattering(const SkinParameters& p, double nm) {
  return p.scattering_500 * std::pow(nm / 500, -p.scattering_power);
}

Medium layer_medium(const SkinParameters& p, const std::vector<double>& wavelength_nm, bool epidermis) {
  p.validate();
  Medium m;
  m.wavelength_nm = wavelength_nm;
  m.channel_names = wavelength_channel_names(wavelength_nm);
  m.eta = p.eta;
  for (double nm : wavelength_nm) {
    const double base = baseline_absorption(nm);
    const double mu_a =
        epidermis
            ? p.melanin * (p.eumelanin * eumelanin_absorption(nm) + (1 - p.eumelanin) * pheomelanin_absorption(nm)) +
                  (1 - p.melanin) * base
            : p.blood * (p.oxygenation * oxy_blood_absorption(nm) + (1 - p.oxygenation) * deoxy_blood_absorption(nm)) +
                  p.water * water_absorption(nm) + (1 - p.blood - p.water) * base;
    m.sigma_a.push_back(mu_a);
    m.sigma_s.push_back(reduced_scattering(p, nm) / (1 - p.g));
    m.g.push_back(p.g);
  }
  m.validate();
  return m;
}

}  // namespace

Medium epidermis_medium(const SkinParameters& p, const std::vector<double>& wavelength_nm) {
  return layer_medium(p, wavelength_nm, true);
}
Medium dermis_medium(const SkinParameters& p, const std::vector<double>& wavelength_nm) {
  return layer_medium(p, wavelength_nm, false);
}

LayerStack skin_stack(const SkinParameters& p, const std::vector<double>& wavelength_nm) {
  const Medium epidermis = epidermis_medium(p, wavelength_nm), dermis = dermis_medium(p, wavelength_nm);
  LayerStack stack;
  stack.channel_names = epidermis.channel_names;
  stack.layers = {Layer::of(epidermis, p.epidermis_mm, "epidermis"), Layer::of(dermis, kSemiInfinite, "dermis")};
  stack.validate();
  return stack;
}

std::vector<double> SkinReflectance::total(bool with_specular) const {
  std::vector<double> out = diffuse;
  if (with_specular)
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += specular[i];
  return out;
}

SkinReflectance skin_reflectance(const SkinParameters& p, const std::vector<double>& wavelength_nm, int points) {
  const Medium epidermis = epidermis_medium(p, wavelength_nm), dermis = dermis_medium(p, wavelength_nm);
  adding_doubling::Options options;
  options.points = points;
  SkinReflectance out;
  for (std::size_t i = 0; i < wavelength_nm.size(); ++i) {
    adding_doubling::Slab slab;
    slab.n = p.eta;
    slab.layers = {{epidermis.sigma_a[i], epidermis.sigma_s[i], p.g, p.epidermis_mm},
                   {dermis.sigma_a[i], dermis.sigma_s[i], p.g, kSemiInfinite}};
    const auto t = adding_doubling::solve(slab, adding_doubling::Incidence::collimated, options);
    out.diffuse.push_back(t.diffuse_reflectance);
    out.specular.push_back(t.specular_reflectance);
  }
  return out;
}

}  // namespace bssrdf::skin
