// The CIE 1931 2-degree standard observer and the illuminants D65, D50, A and E, from the CIE's own tables
// (src/spectral/cie_tables.cpp names each source). Wavelengths in nm.
//
//   auto [x, y, z] = spectral::observer(555.0);            // 0.5121, 1, 0.00575
//   double s = spectral::illuminant_power(Illuminant::d50, 500.0);
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace bssrdf::spectral {

// The observer's range: x̄, ȳ, z̄ are 0 outside it.
inline constexpr double kObserverMin = 360, kObserverMax = 830;
inline constexpr std::string_view kObserverName = "CIE 1931 2-degree";

// x̄, ȳ, z̄ at `nm`, linearly interpolated between the 1 nm entries.
std::array<double, 3> observer(double nm);

enum class Illuminant { d65, d50, a, e };
std::string_view to_string(Illuminant illuminant);  // "D65", "D50", "A", "E"
// "d65" | "d50" | "a" | "e" (any case); InvalidInput naming `field` otherwise.
Illuminant parse_illuminant(const std::string& text, const std::string& field = "illuminant");

// Relative spectral power (arbitrary scale) at `nm` within the observer's range:
//  D65: the CIE table (1 nm); D50: the daylight method of CIE 15:2004 section 3.1 at 5000 K x 1.4388/1.4380
//  (M1, M2 rounded to three decimals as the CIE does), its 5 nm values interpolated linearly; A: Planck's law at
//  2848 K with c2 = 1.435e-2 m K, 100 at 560 nm (CIE 15:2004 eq. 3.1); E: 1.
double illuminant_power(Illuminant illuminant, double nm);

}  // namespace bssrdf::spectral
