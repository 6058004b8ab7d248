// Length units at the edges of the tool. Inside the library every length is in millimetres and
// every coefficient in 1/mm; inputs and outputs carry a unit and are converted at the boundary.
#pragma once

#include <string>
#include <string_view>

namespace bssrdf {

enum class LengthUnit { micrometre, millimetre, centimetre, metre };

// "um", "µm", "mm", "cm", "m" (case-insensitive). Throws InvalidInput naming `field` otherwise.
LengthUnit parse_length_unit(std::string_view text, const std::string& field = "unit");

// The unit's symbol as written in outputs: "um", "mm", "cm", "m".
std::string_view symbol(LengthUnit unit);

// How many millimetres one `unit` is: a length x [unit] is x * millimetres_per(unit) [mm], and a
// coefficient s [1/unit] is s / millimetres_per(unit) [1/mm].
double millimetres_per(LengthUnit unit);

inline double to_mm(double length, LengthUnit unit) { return length * millimetres_per(unit); }
inline double from_mm(double length_mm, LengthUnit unit) { return length_mm / millimetres_per(unit); }
inline double coefficient_to_per_mm(double coefficient, LengthUnit unit) { return coefficient / millimetres_per(unit); }
inline double coefficient_from_per_mm(double coefficient_per_mm, LengthUnit unit) {
  return coefficient_per_mm * millimetres_per(unit);
}

}  // namespace bssrdf
