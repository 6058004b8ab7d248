// A measured reflectance spectrum: a text table of wavelength (nm) and one or more reflectance columns (reflectance
// factor, 0-1), separated by spaces, tabs, commas or semicolons; '#' starts a comment. Column names come from the
// last header line before the data (commented or not) whose first field is not a number, e.g.
//   # wavelength_nm subject_1 subject_2
//   400 0.2012 0.2422
// Without names the columns are 1, 2, ... (after the wavelength).
#pragma once

#include <string>
#include <vector>

namespace bssrdf {

struct ReflectanceSpectrum {
  std::string file, column;  // where it came from
  std::vector<double> wavelength_nm, reflectance;
};

// The names of the reflectance columns (after the wavelength column).
std::vector<std::string> spectrum_columns(const std::string& text, const std::string& file_name);
// `column`: a name or a 1-based number among the reflectance columns; empty: the first. Throws FileError naming the
// file and line for malformed rows, wavelengths outside 200-20000 nm or not increasing, reflectances outside 0-2,
// fewer than 2 rows, and InvalidInput naming "column" (with the names available) for an unknown column.
ReflectanceSpectrum parse_spectrum(const std::string& text, const std::string& file_name, const std::string& column);
ReflectanceSpectrum read_spectrum(const std::string& path, const std::string& column);

}  // namespace bssrdf
