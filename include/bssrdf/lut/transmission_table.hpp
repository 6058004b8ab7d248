// The transmission table: total diffuse transmittance of a slab of the material against its
// thickness, per channel (options.model "adding-doubling": exact at every thickness, nothing omitted), for thin-object
// translucency in real-time engines (Unreal's 32-texel transmission profile, Unity's thickness remap). Values come from
// the multipole (Donner & Jensen 2005) where it holds; where it does not (thinner than 2 transport mean free paths,
// negative transmittance: the slab's own "invalid" codes, as `bssrdf transmission` uses them) the thickness is either
// filled from the Monte Carlo reference (options.reference) or omitted with a recorded note: never a wrong number. The
// medium's other validity notes (e.g. low_albedo, which concerns the diffusion approximation's accuracy at every
// thickness) are recorded, not acted on.
//
// Convention: per unit flux that entered the slab through the top face, light that scattered at
// least once and left through the bottom face; the ballistic (unscattered) beam e^{-sigma_t d} is
// excluded (it is exact and renderers add it themselves). Both faces see the medium's eta.
//
//   TransmissionTableOptions o;  o.reference = true;  o.photons = 100'000;
//   auto t = build_transmission_table(skin, log_spaced(0.1, 20.0, 32), o);
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bssrdf/lut/lookup_table.hpp"
#include "bssrdf/lut/table_context.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/models/multipole.hpp"

namespace bssrdf {

struct TransmissionTableOptions {
  std::string model = "multipole";    // or "adding-doubling": exact at every thickness, nothing omitted
  bool reference = false;             // Monte Carlo where the multipole is invalid
  bool reference_everywhere = false;  // Monte Carlo at every thickness (implies reference)
  std::uint64_t photons = 100'000;    // Monte Carlo photons per channel and thickness
  std::uint64_t seed = 1;
  unsigned threads = 1;  // Monte Carlo threads (0: all); results never depend on it

  void validate() const;  // throws InvalidInput naming the option
};

enum class TransmissionSource { multipole, monte_carlo, adding_doubling };
std::string_view to_string(TransmissionSource source);

struct TransmissionTable {
  TransmissionTableOptions options;
  std::vector<std::string> channel_names;
  std::vector<double> thickness;                    // mm, increasing: the thicknesses kept
  std::vector<std::vector<double>> transmittance;   // [channel][j]
  std::vector<std::vector<double>> standard_error;  // [channel][j]; 0 where the multipole gave it
  std::vector<TransmissionSource> source;           // [j]: one source per thickness, all channels
  std::vector<double> omitted_thickness;            // mm: invalid under the multipole, no reference
  std::vector<std::string> omitted_reason;          // "thin_slab (G, B)"
  std::vector<std::string> validity;                // [channel]: the multipole's other warnings
  // [channel]: with adding-doubling, its largest error estimate over the thicknesses (the change of T
  // from half the angles, per entered flux); empty otherwise.
  std::vector<double> adding_doubling_error;
  double monte_carlo_seconds = 0;

  std::size_t size() const { return thickness.size(); }
};

// The default thicknesses of a transmission curve: one rule for `bssrdf transmission` and `bssrdf lut
// --kind transmission`. kThicknessSamples thicknesses, log-spaced from
//   d_min = 0.1 ell_min when every thickness gets a value (adding-doubling is exact at every thickness;
//           with options.reference the Monte Carlo reference fills what the multipole cannot), else
//           2 ell_max: the multipole is invalid below 2 ell of a channel (Donner & Jensen 2005: the
//           dipole sources leave the slab), so from there it holds in every channel;
//   d_max = 40 ell_max, the thick end, where the transmittance decays as exp(-sigma_tr d),
// ell = 1 / sigma_t' the transport mean free path, over the channels (transport_mfp_range).
struct SlabThicknessRange {
  double d_min = 0, d_max = 0;  // mm
};
SlabThicknessRange default_thickness_range(const Medium& medium, const TransmissionTableOptions& options);
inline constexpr int kThicknessSamples = 32, kMaxThicknessSamples = 4096;

// The first slab-specific "invalid" validity code of the multipole for this channel ("thin_slab",
// "source_outside_slab", "negative_transmittance", "negative_reflectance"); empty when it holds.
std::string multipole_invalid_code(const multipole::Model& model, const Reduced<double>& m);

// thickness_mm: > 0, any order (sorted and de-duplicated). Throws InvalidInput.
TransmissionTable build_transmission_table(const Medium& medium, std::vector<double> thickness_mm,
                                           const TransmissionTableOptions& options);

// One row: "thickness" (unit) then one channel per colour channel (T_total); with Monte Carlo
// values also "source" (0 multipole, 1 Monte Carlo) and "stderr.<c>". Attributes record the
// convention, the sources and every omitted thickness with its reason.
LookupTable to_lookup_table(const TransmissionTable& table, const TableContext& context);
// A few lines for people: thicknesses and their sources, each channel's T at both ends, omissions.
std::string summary(const TransmissionTable& table, const TableContext& context);

}  // namespace bssrdf
