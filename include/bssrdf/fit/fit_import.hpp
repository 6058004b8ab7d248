// A fit result ('bssrdf fit profile|albedo|slab ... -f json', or 'fit slab --rxt' with one channel
// per converged row) as a bssrdf materials file with one entry: sigma_a, sigma_s and g per channel, as fitted
// or held (a result without g, from an older version, gives g = 0 and sigma_s = sigma_s').
// A 'fit slab --rxt' result whose kept rows have wavelengths (200-20000 nm, strictly increasing) becomes a spectral
// material ("wavelength_nm", docs/spectral.md); rows that did not converge are skipped, each listed in the file's
// notes and in `skipped` ("line 40 (610 nm): not unique: ..."); none converged, or a repeated wavelength: FileError.
//
//   const std::string text = bssrdf::materials_file_from_fit(json_text, "fit.json", "My wax", std::nullopt, "fit");
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace bssrdf {

// `eta`: the relative index to record; nullopt takes the fit's own (fitted or recorded). Throws
// FileError naming `fit_file` for anything that is not such a result (malformed JSON, wrong types,
// missing coefficients), InvalidInput when no eta is known.
std::string materials_file_from_fit(const std::string& fit_text, const std::string& fit_file, const std::string& name,
                                    std::optional<double> eta, const std::string& source,
                                    std::vector<std::string>* skipped = nullptr);

}  // namespace bssrdf
