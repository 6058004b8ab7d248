#include "bssrdf/skin/chromophores.hpp"

#include <algorithm>
#include <cmath>

#include "bssrdf/error.hpp"
#include "chromophore_tables.hpp"

namespace bssrdf::skin {
namespace {

void check_range(double nm) {
  if (!(nm >= kChromophoreMinNm && nm <= kChromophoreMaxNm))
    throw InvalidInput("wavelength", format_number(nm),
                       format_number(kChromophoreMinNm) + " to " + format_number(kChromophoreMaxNm) +
                           " nm (the haemoglobin spectra's range)");
}

// Whole blood: 150 g/L haemoglobin, 64 500 g/mol; e in cm^-1/(mol/L), base 10 -> mu_a in 1/mm.
double blood(const double* extinction, double nm) {
  check_range(nm);
  const double t = (nm - tables::kHaemoglobinWavelength0) / tables::kHaemoglobinStep;
  const int i = std::min(static_cast<int>(t), tables::kHaemoglobinCount - 2);
  const double e = extinction[i] + (t - i) * (extinction[i + 1] - extinction[i]);
  return std::log(10.0) * e * (150.0 / 64500.0) / 10;
}

}  // namespace

double eumelanin_absorption(double nm) { return check_range(nm), 6.6e10 * std::pow(nm, -3.33); }
double pheomelanin_absorption(double nm) { return check_range(nm), 2.9e14 * std::pow(nm, -4.75); }
double baseline_absorption(double nm) { return check_range(nm), 0.0244 + 8.53 * std::exp(-(nm - 154) / 66.2); }
double oxy_blood_absorption(double nm) { return blood(tables::kOxyHaemoglobin, nm); }
double deoxy_blood_absorption(double nm) { return blood(tables::kDeoxyHaemoglobin, nm); }

double water_absorption(double nm) {
  check_range(nm);
  const double* x = tables::kWaterWavelength;
  const auto* hi = std::upper_bound(x, x + tables::kWaterCount, nm);
  const int i = static_cast<int>(std::clamp<long>(hi - x, 1, tables::kWaterCount - 1)) - 1;
  const double f = (nm - x[i]) / (x[i + 1] - x[i]);
  return (tables::kWaterAbsorption[i] + f * (tables::kWaterAbsorption[i + 1] - tables::kWaterAbsorption[i])) / 10;
}

}  // namespace bssrdf::skin
