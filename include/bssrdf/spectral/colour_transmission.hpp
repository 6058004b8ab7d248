// A spectral slab's transmittance in colour. Totals are linear in the light, so thickness by thickness
//   T_c(d) = sum_i w_ci T(d, lambda_i)
// with ColourIntegrator's weights w (spectral/colour.hpp: the same integration as every colour output), each
// wavelength's T(d, lambda_i) solved on its own (adding-doubling, or the multipole / Monte Carlo as the table asks).
// Monte Carlo standard errors combine as sqrt(sum_i w_ci^2 se_i^2): each wavelength has its own random stream.
//
//   auto spectral = build_transmission_table(medium, thickness, options);   // one channel per wavelength
//   auto rgb = colour_transmission(spectral, ColourIntegrator(medium.wavelength_nm, {}));   // R, G, B
#pragma once

#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/spectral/colour.hpp"

namespace bssrdf::spectral {

// `table`'s channels are colour.wavelengths() (InternalError otherwise); returns channels R, G, B with the same
// thicknesses, sources and omissions, and per channel the wavelengths' validity notes (each once, naming the first
// wavelength that has it).
TransmissionTable colour_transmission(const TransmissionTable& table, const ColourIntegrator& colour);

// The bssrdf:colour line of `table`, a colour transmission table: the colour, the integration, and for a channel that
// turns negative the thickness from which it does (thick slabs pass mostly deep red, a colour outside linear sRGB;
// never clipped).
std::string colour_transmission_line(const TransmissionTable& table, const ColourIntegrator& colour);

}  // namespace bssrdf::spectral
