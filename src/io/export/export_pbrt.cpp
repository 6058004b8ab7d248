// pbrt-v4 `subsurface` materials (sigma_a, sigma_s, g, eta, scale) as MakeNamedMaterial blocks,
// coefficients in 1/scene unit with scale 1: "rgb" for RGB media, "spectrum" (wavelength-value pairs) for
// spectral ones, which pbrt-v4 renders spectrally. pbrt-v4 takes one g per material: see single_g().
#include <algorithm>

#include "export_common.hpp"

namespace bssrdf::export_detail {
namespace {
// pbrt-v4's built-in media (src/pbrt/media.cpp, SubsurfaceParameterTable: Jensen et al. 2001 and
// Narasimhan et al. 2006), selected with "string name"; stored as sigma_s' and sigma_a in 1/mm,
// with g forced to 0.
constexpr const char* kPbrtNamedMedia[] = {"Apple",
                                           "Chicken1",
                                           "Chicken2",
                                           "Cream",
                                           "Ketchup",
                                           "Marble",
                                           "Potato",
                                           "Skimmilk",
                                           "Skin1",
                                           "Skin2",
                                           "Spectralon",
                                           "Wholemilk",
                                           "Lowfat Milk",
                                           "Reduced Milk",
                                           "Regular Milk",
                                           "Espresso",
                                           "Mint Mocha Coffee",
                                           "Lowfat Soy Milk",
                                           "Regular Soy Milk",
                                           "Lowfat Chocolate Milk",
                                           "Regular Chocolate Milk",
                                           "Coke",
                                           "Pepsi",
                                           "Sprite",
                                           "Gatorade",
                                           "Chardonnay",
                                           "White Zinfandel",
                                           "Merlot",
                                           "Budweiser Beer",
                                           "Coors Light Beer",
                                           "Clorox",
                                           "Apple Juice",
                                           "Cranberry Juice",
                                           "Grape Juice",
                                           "Ruby Grapefruit Juice",
                                           "White Grapefruit Juice",
                                           "Shampoo",
                                           "Strawberry Shampoo",
                                           "Head & Shoulders Shampoo",
                                           "Lemon Tea Powder",
                                           "Orange Powder",
                                           "Pink Lemonade Powder",
                                           "Cappuccino Powder",
                                           "Salt Powder",
                                           "Sugar Powder",
                                           "Suisse Mocha Powder",
                                           "Pacific Ocean Surface Water"};

bool pbrt_names(const std::string& name) {
  return std::any_of(std::begin(kPbrtNamedMedia), std::end(kPbrtNamedMedia), [&](const char* n) { return name == n; });
}
}  // namespace

// A spectral medium's coefficients as pbrt-v4's interleaved "spectrum" parameter: [ nm value nm value ... ]
// (pbrt-v4 file format, "Spectra"; it interpolates linearly between the given wavelengths).
std::string pbrt_spectrum(const std::vector<double>& nm, const std::vector<double>& values) {
  std::string out;
  for (std::size_t i = 0; i < nm.size(); ++i) {
    if (i) out += ' ';
    out += num(nm[i]);
    out += ' ';
    out += num(values[i]);
  }
  return out;
}

std::string export_pbrt_v4(const std::vector<ExportEntry>& entries, LengthUnit unit) {
  const bool spectral =
      std::all_of(entries.begin(), entries.end(), [](const ExportEntry& e) { return e.material.medium.spectral(); });
  if (!spectral) require_rgb(entries, "pbrt-v4");
  const std::string u(symbol(unit));
  std::string out =
      "# pbrt-v4 subsurface materials exported by bssrdf " BSSRDF_VERSION
      "\n"
      "# Units: sigma_a and sigma_s in 1/" +
      u + " (one scene unit = 1 " + u +
      "), \"scale\" 1.\n"
      "# Distance convention: extinction coefficients; mean free path 1/(sigma_a + sigma_s) per channel,\n"
      "# transport mean free path 1/(sigma_a + sigma_s (1 - g)), listed per material below.\n"
      "# Use: NamedMaterial \"<name>\" before the shape.\n"
      "# pbrt-v4 builds its own photon-beam-diffusion table (100 albedos x 64 radii, for this g and eta)\n"
      "# from these coefficients: it does not read bssrdf's tables. 'bssrdf lut --kind albedo-radius\n"
      "# --layout pbrt' writes the same layout (EXR/JSON, documented in bssrdf's README) for a custom\n"
      "# integrator or a patched pbrt (its TabulatedBSSRDF reads rho, radius, profile, rhoEff, cdf).\n";
  for (const auto& e : entries) {
    const auto& m = e.material.medium;
    const auto one = single_g(m);
    std::vector<double> a, s, mfp, ell;
    for (std::size_t c = 0; c < m.channels(); ++c) {
      a.push_back(coefficient_from_per_mm(m.sigma_a[c], unit));
      s.push_back(coefficient_from_per_mm(one.sigma_s[c], unit));
      mfp.push_back(from_mm(e.derived.channels[c].mfp, unit));
      ell.push_back(from_mm(e.derived.channels[c].transport_mfp, unit));
    }
    out += "\n# " + e.material.name + " (" + e.material.source + "): " + e.material.citation + "\n";
    out += "#   mfp 1/sigma_t [" + u + "]: " + join(mfp, " ") + "; transport mfp 1/sigma_t' [" + u +
           "]: " + join(ell, " ") + "\n";
    if (!one.exact)
      out += "#   per-channel g (" + join(m.g, " ") +
             ") replaced by their mean; sigma_s rescaled to keep sigma_s' = sigma_s (1 - g)\n";
    out += "#   " + validity_summary(e.derived) + "\n";
    if (pbrt_names(e.material.name))
      out += "#   pbrt-v4 has this medium built in: \"string name\" [ \"" + e.material.name +
             "\" ] (its table: sigma_s' and sigma_a in 1/mm, g forced to 0; \"float scale\" [ " +
             num(millimetres_per(unit)) + " ] for 1/" + u + ")\n";
    out += "MakeNamedMaterial \"" + e.material.name + "\"\n";
    out += "    \"string type\" [ \"subsurface\" ]\n";
    if (spectral) {
      out += "    \"spectrum sigma_a\" [ " + pbrt_spectrum(m.wavelength_nm, a) + " ]\n";
      out += "    \"spectrum sigma_s\" [ " + pbrt_spectrum(m.wavelength_nm, s) + " ]\n";
    } else {
      out += "    \"rgb sigma_a\" [ " + join(a, " ") + " ]\n";
      out += "    \"rgb sigma_s\" [ " + join(s, " ") + " ]\n";
    }
    out += "    \"float g\" [ " + num(one.g) + " ]\n";
    out += "    \"float eta\" [ " + num(m.eta) + " ]\n";
    out += "    \"float scale\" [ 1 ]\n";
  }
  return out;
}

}  // namespace bssrdf::export_detail
