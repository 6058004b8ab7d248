// The CIE's tables (cie_tables.cpp, with their sources): observer 360-830 nm at 1 nm, D65 300-830 nm at 1 nm,
// daylight components 300-830 nm at 5 nm.
#pragma once

namespace bssrdf::spectral::tables {

inline constexpr int kCmfFirst = 360, kCmfCount = 471;            // nm, 1 nm steps
inline constexpr int kD65First = 300, kD65Count = 531;            // nm, 1 nm steps
inline constexpr int kDaylightFirst = 300, kDaylightCount = 107;  // nm, 5 nm steps
extern const double kCmfX[kCmfCount], kCmfY[kCmfCount], kCmfZ[kCmfCount];
extern const double kD65[kD65Count];
extern const double kDaylightS0[kDaylightCount], kDaylightS1[kDaylightCount], kDaylightS2[kDaylightCount];

}  // namespace bssrdf::spectral::tables
