// Published chromophore spectra (chromophore_tables.cpp names the sources).
#pragma once

namespace bssrdf::skin::tables {

inline constexpr int kHaemoglobinCount = 376, kWaterCount = 171;
extern const double kHaemoglobinWavelength0, kHaemoglobinStep;                                 // nm
extern const double kOxyHaemoglobin[kHaemoglobinCount], kDeoxyHaemoglobin[kHaemoglobinCount];  // cm^-1 / (mol/L)
extern const double kWaterWavelength[kWaterCount], kWaterAbsorption[kWaterCount];              // nm, 1/cm

}  // namespace bssrdf::skin::tables
