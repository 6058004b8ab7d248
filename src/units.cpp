#include "bssrdf/units.hpp"

#include <algorithm>
#include <cctype>

#include "bssrdf/error.hpp"
#include "bssrdf/text.hpp"

namespace bssrdf {

LengthUnit parse_length_unit(std::string_view text, const std::string& field) {
  const std::string lower = bssrdf::lower(text);
  if (lower == "um" || lower == "\xc2\xb5m" || lower == "\xce\xbcm" || lower == "micrometre" || lower == "micrometer")
    return LengthUnit::micrometre;
  if (lower == "mm" || lower == "millimetre" || lower == "millimeter") return LengthUnit::millimetre;
  if (lower == "cm" || lower == "centimetre" || lower == "centimeter") return LengthUnit::centimetre;
  if (lower == "m" || lower == "metre" || lower == "meter") return LengthUnit::metre;
  throw InvalidInput(field, "'" + std::string(text) + "'", "one of um, mm, cm, m");
}

std::string_view symbol(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::micrometre:
      return "um";
    case LengthUnit::millimetre:
      return "mm";
    case LengthUnit::centimetre:
      return "cm";
    case LengthUnit::metre:
      return "m";
  }
  return "mm";
}

double millimetres_per(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::micrometre:
      return 1e-3;
    case LengthUnit::millimetre:
      return 1.0;
    case LengthUnit::centimetre:
      return 10.0;
    case LengthUnit::metre:
      return 1000.0;
  }
  return 1.0;
}

}  // namespace bssrdf
