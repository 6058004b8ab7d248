// Absorption spectra of the chromophores of human skin, in 1/mm at a wavelength in nm, from their published
// sources (data in src/skin/chromophore_tables.cpp with provenance):
//  - eumelanin 6.6e10 lambda^-3.33 and pheomelanin 2.9e14 lambda^-4.75 (1/mm, lambda in nm), the absorption of the
//    pure pigments in melanosomes: Donner and Jensen (2006), "A spectral BSSRDF for shading human skin", EGSR,
//    eqs. 3-4, after Jacques (1998), "Skin optics", Oregon Medical Laser Center News;
//  - baseline (bloodless, melanin-free) tissue 0.0244 + 8.53 exp(-(lambda - 154)/66.2) (1/mm): Jacques (1998),
//    from Saidi (1992), Rice University thesis; also Donner and Jensen (2006) eq. 5;
//  - whole blood, 150 g/L haemoglobin of molar mass 64 500 g/mol: mu_a = ln(10) e c with Prahl's (1999) molar
//    extinction coefficients e of oxy- and deoxyhaemoglobin (Gratzer; Kollias), 250-1000 nm;
//  - water, Segelstein (1981) as tabulated by Prahl, 200-1100 nm.
#pragma once

namespace bssrdf::skin {

// The range every chromophore covers (the haemoglobin table's): InvalidInput outside.
inline constexpr double kChromophoreMinNm = 250, kChromophoreMaxNm = 1000;

double eumelanin_absorption(double nm);
double pheomelanin_absorption(double nm);
double baseline_absorption(double nm);
double oxy_blood_absorption(double nm);    // whole blood, fully oxygenated
double deoxy_blood_absorption(double nm);  // whole blood, fully deoxygenated
double water_absorption(double nm);

}  // namespace bssrdf::skin
