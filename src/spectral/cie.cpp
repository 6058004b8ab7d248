#include "bssrdf/spectral/cie.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "bssrdf/check.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/text.hpp"
#include "cie_tables.hpp"

namespace bssrdf::spectral {
namespace {

// Linear interpolation in a table of `count` entries from `first` nm every `step` nm; 0 outside.
double lerp_table(const double* table, int count, double first, double step, double nm) {
  const double t = (nm - first) / step;
  if (!(t >= 0) || t > count - 1) return 0;
  const int i = std::min(static_cast<int>(t), count - 2);
  const double f = t - i;
  return table[i] * (1 - f) + table[i + 1] * f;
}

// The daylight weights M1, M2 of CIE 15:2004 eqs. 3.3-3.5 at correlated colour temperature T (4000-7000 K),
// rounded to three decimals as the CIE's tabulated D illuminants are.
std::array<double, 2> daylight_weights(double T) {
  const double x = -4.6070e9 / (T * T * T) + 2.9678e6 / (T * T) + 0.09911e3 / T + 0.244063;
  const double y = -3.000 * x * x + 2.870 * x - 0.275;
  const double m = 0.0241 + 0.2562 * x - 0.7341 * y;
  const double m1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / m;
  const double m2 = (0.0300 - 31.4424 * x + 30.0717 * y) / m;
  return {std::round(m1 * 1000) / 1000, std::round(m2 * 1000) / 1000};
}

}  // namespace

std::array<double, 3> observer(double nm) {
  using namespace tables;
  return {lerp_table(kCmfX, kCmfCount, kCmfFirst, 1, nm), lerp_table(kCmfY, kCmfCount, kCmfFirst, 1, nm),
          lerp_table(kCmfZ, kCmfCount, kCmfFirst, 1, nm)};
}

std::string_view to_string(Illuminant illuminant) {
  switch (illuminant) {
    case Illuminant::d65:
      return "D65";
    case Illuminant::d50:
      return "D50";
    case Illuminant::a:
      return "A";
    case Illuminant::e:
      return "E";
  }
  return "?";
}

Illuminant parse_illuminant(const std::string& text, const std::string& field) {
  const std::string lower = bssrdf::lower(text);
  if (lower == "d65") return Illuminant::d65;
  if (lower == "d50") return Illuminant::d50;
  if (lower == "a") return Illuminant::a;
  if (lower == "e") return Illuminant::e;
  throw InvalidInput(field, "'" + text + "'", "d65, d50, a or e");
}

double illuminant_power(Illuminant illuminant, double nm) {
  using namespace tables;
  switch (illuminant) {
    case Illuminant::d65:
      return lerp_table(kD65, kD65Count, kD65First, 1, nm);
    case Illuminant::d50: {
      static const auto m = daylight_weights(5000 * 1.4388 / 1.4380);
      return lerp_table(kDaylightS0, kDaylightCount, kDaylightFirst, 5, nm) +
             m[0] * lerp_table(kDaylightS1, kDaylightCount, kDaylightFirst, 5, nm) +
             m[1] * lerp_table(kDaylightS2, kDaylightCount, kDaylightFirst, 5, nm);
    }
    case Illuminant::a: {
      const double c2 = 1.435e7;  // nm K
      return 100 * std::pow(560 / nm, 5) * std::expm1(c2 / (2848 * 560)) / std::expm1(c2 / (2848 * nm));
    }
    case Illuminant::e:
      return 1;
  }
  BSSRDF_CHECK(false);
  return 0;
}

}  // namespace bssrdf::spectral
