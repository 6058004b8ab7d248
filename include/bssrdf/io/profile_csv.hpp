// Measured radial profiles from CSV: the first column is the radius, then one column per channel
// holding R(r) per unit area, optionally with standard-error columns named "<channel>_stderr".
// `bssrdf profile --format csv` writes this form, so profiles round-trip.
//
//   radius_mm,R,G,B,R_stderr,G_stderr,B_stderr      <- header (a unit suffix _um/_mm/_cm/_m on
//   0.01,0.52,0.61,0.64,0.005,0.006,0.006              the radius sets the unit; "_per_mm2"
//   ...                                                 suffixes on channels are ignored)
//
// Lines starting with '#' are comments. Errors are FileError with file and line: a malformed or
// missing number, NaN, a negative value or non-positive standard error, radii that do not
// increase, fewer than 4 points, an empty file.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bssrdf/units.hpp"

namespace bssrdf {

struct MeasuredProfile {
  std::string file;
  LengthUnit unit = LengthUnit::millimetre;  // as stated in the file (or given)
  std::vector<double> radius;                // mm
  // The bins' edges (mm) where the file gives them ('bssrdf reference -f csv': radius_inner_*,
  // radius_outer_*): each value is then R averaged over its annulus, and fits compare it with the
  // model's own average there (near the entry point R ~ 1/r differs from its bin average); else empty.
  std::vector<double> radius_inner, radius_outer;
  struct Channel {
    std::string name;
    std::vector<double> value;           // 1/mm^2
    std::vector<double> standard_error;  // 1/mm^2; empty when not given
  };
  std::vector<Channel> channels;
  // 'bssrdf reference -f csv' output is read as its "<channel>_R_entered" columns with their
  // standard errors; bins no photon reached are skipped and counted here.
  std::size_t empty_bins = 0;
};

// `unit`: the unit when the header does not state one (default mm).
MeasuredProfile read_profile_csv(const std::filesystem::path& path, std::optional<LengthUnit> unit = std::nullopt);
MeasuredProfile parse_profile_csv(const std::string& text, const std::string& name,
                                  std::optional<LengthUnit> unit = std::nullopt);

}  // namespace bssrdf
