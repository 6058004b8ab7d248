// A two-layer model of human skin: an epidermis holding melanin (eumelanin and pheomelanin) over a semi-infinite
// dermis holding blood (a volume fraction at an oxygen saturation) and water, both on a baseline of bloodless,
// melanin-free tissue, with reduced scattering mu_s' = a (lambda / 500 nm)^-b in both layers, Henyey-Greenstein g and
// one index eta (chromophores.hpp cites every spectrum). The layer absorptions follow Donner and Jensen (2006),
// "A spectral BSSRDF for shading human skin", eqs. 3-7:
//   epidermis  mu_a = M (f mu_eu + (1 - f) mu_pheo) + (1 - M) mu_base
//   dermis     mu_a = B (S mu_oxy + (1 - S) mu_deoxy) + W mu_water + (1 - B - W) mu_base
// Its totals come from adding-doubling (the exact slab solver); profiles from the layer stack (skin_stack) with the
// solvers that take one.
//
//   skin::SkinParameters p;  p.melanin = 0.05;  p.blood = 0.02;
//   auto stack = skin::skin_stack(p, {450, 550, 650});    // a spectral LayerStack
//   auto r = skin::total_reflectance(p, {450, 550, 650});  // diffuse (+ specular) per wavelength
#pragma once

#include <string>
#include <vector>

#include "bssrdf/layers.hpp"
#include "bssrdf/medium.hpp"

namespace bssrdf::skin {

struct SkinParameters {
  double melanin = 0.03;          // M: volume fraction of melanosomes in the epidermis, 0-0.6
  double eumelanin = 0.7;         // f: eumelanin share of the melanin (the rest pheomelanin), 0-1
  double blood = 0.02;            // B: volume fraction of blood in the dermis, 0-0.3
  double oxygenation = 0.75;      // S: oxygen saturation of the haemoglobin, 0-1
  double epidermis_mm = 0.08;     // epidermal thickness, 0.01-0.5 mm
  double scattering_500 = 3.0;    // a: reduced scattering mu_s' at 500 nm, 1/mm, 0.1-20
  double scattering_power = 1.2;  // b: mu_s' falls as lambda^-b, 0-4
  double water = 0.65;            // W: volume fraction of water in the dermis (Jacques 2013: 0.65), 0-0.9
  double g = 0.8;                 // Henyey-Greenstein mean cosine of both layers
  double eta = 1.4;               // index of both layers, in air

  // InvalidInput naming the parameter and its range.
  void validate() const;
};

struct NamedRange {
  const char* name;
  double SkinParameters::*member;
  double min, max;
  const char* unit;
  const char* meaning;
};
// Every parameter with its accepted range: what validate(), the command line and the fit share.
const std::vector<NamedRange>& skin_parameter_ranges();

// The two layers at each wavelength (nm, within kChromophoreMinNm-kChromophoreMaxNm), in air; channels named by
// wavelength. The dermis is semi-infinite.
LayerStack skin_stack(const SkinParameters& p, const std::vector<double>& wavelength_nm);
// The epidermis and dermis as spectral media (for reports and exports).
Medium epidermis_medium(const SkinParameters& p, const std::vector<double>& wavelength_nm);
Medium dermis_medium(const SkinParameters& p, const std::vector<double>& wavelength_nm);

// Total reflectance per wavelength for normally incident light, by adding-doubling with `points` angles per
// hemisphere (0: chosen from a 1e-4 tolerance); with_specular adds the surface's Fresnel reflection.
struct SkinReflectance {
  std::vector<double> diffuse, specular;
  std::vector<double> total(bool with_specular) const;
};
SkinReflectance skin_reflectance(const SkinParameters& p, const std::vector<double>& wavelength_nm, int points = 0);

}  // namespace bssrdf::skin
