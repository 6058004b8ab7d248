// The measured-media database: JSON files, one per published source, under materials/. Each file
// records its source, citation, length unit and per-channel coefficients; loading validates every
// entry and converts it to the library's units (1/mm).
//
//   auto db = bssrdf::MaterialDatabase::load(bssrdf::default_materials_dir());
//   const auto& skin = db.find("skin1");    // case-insensitive; unknown names list close matches
//
// File format (materials/README.md has the full description):
//   { "format": "bssrdf-materials", "version": 1, "source": "jensen2001", "citation": "...",
//     "unit": "mm", "channels": ["R","G","B"], "notes": ["..."],
//     "materials": [ { "name": "Apple", "eta": 1.3, "sigma_a": [..],
//                      "sigma_s": [..], "g": [..]   -- or --   "sigma_s_prime": [..],
//                      "notes": "..." } ] }
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "bssrdf/medium.hpp"
#include "bssrdf/units.hpp"

namespace bssrdf {

struct Material {
  std::string name;
  std::string source;                        // short key of the publication, e.g. "jensen2001"
  std::string citation;                      // full reference
  std::string file;                          // the file it was loaded from
  LengthUnit unit = LengthUnit::millimetre;  // unit the file states its coefficients in
  // True when the source published only the reduced scattering sigma_s' (g unknown): the medium
  // then holds sigma_s = sigma_s' and g = 0, which diffusion models treat exactly.
  bool reduced_scattering_only = false;
  Medium medium;  // coefficients in 1/mm
  std::vector<std::string> notes;
};

class MaterialDatabase {
 public:
  // Loads every *.json in a directory (sorted by name), or one file. Throws FileError naming the
  // file, and the line or JSON path, for malformed files or invalid values; duplicate names across
  // files are errors too.
  static MaterialDatabase load(const std::filesystem::path& path);
  // The bundled database plus the user's own directory or file (`--db`); empty: bundled only.
  // A user name that clashes with a bundled one is an error naming both files.
  static MaterialDatabase load_with_user(const std::filesystem::path& user);
  void add_path(const std::filesystem::path& path);  // a directory of *.json, or one file
  void add_file(const std::filesystem::path& file);
  // The text of a materials file; errors name `file_name` (e.g. a file about to be written).
  void add_text(const std::string& text, const std::string& file_name);

  // Case-insensitive lookup; throws InvalidInput listing the closest names when unknown.
  const Material& find(std::string_view name) const;
  const std::vector<Material>& all() const { return materials_; }

 private:
  std::vector<Material> materials_;
};

// $BSSRDF_MATERIALS if set, else ../share/bssrdf/materials next to the executable when installed,
// else the source tree's materials/ directory compiled into the library.
std::filesystem::path default_materials_dir();

// Names within a small edit distance of `name` (case-insensitive), closest first.
std::vector<std::string> close_matches(std::string_view name, const std::vector<std::string>& names,
                                       std::size_t max_results = 5);

}  // namespace bssrdf
