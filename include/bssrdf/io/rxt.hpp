// Integrating-sphere measurement files as Prahl's inverse adding-doubling (iad) reads them
// (".rxt"; Prahl, "Inverse Adding-Doubling" manual): read unchanged.
//
//   IAD1                  # the first four characters
//   1.40                  # index of refraction of the sample
//   1.50                  # index of the top and bottom slides (1, or slide thickness 0: none)
//   1.0                   # [mm] sample thickness
//   1.0                   # [mm] slide thickness
//   5.0                   # [mm] beam diameter
//   0.99                  # reflectance of the calibration standard
//   1                     # number of spheres: 0, 1 or 2
//   203.2 25.4 12.7 1.0 0.96   # reflection sphere: diameter, sample, entrance and detector port
//                              # diameters [mm], wall reflectance
//   203.2 25.4 12.7 1.0 0.96   # transmission sphere: the same (third port: exit)
//   2                     # number of measurements: 2 (M_R, M_T) or 3 (M_R, M_T, M_U); or a
//                         # column line of letters (l wavelength, r M_R, t M_T, u M_U), e.g. "lrt"
//   500  0.30  0.40       # rows: [wavelength] M_R M_T [M_U]; '#' starts a comment
//
// Every number may sit on its own line or share one. A bad file raises FileError with the line:
// "sample.rxt:12: M_R + M_T = 1.2: accepted range is <= 1".
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace bssrdf {

struct RxtSphere {
  double diameter = 0, sample_port = 0, third_port = 0, detector_port = 0;  // mm
  double wall_reflectance = 0;
};

struct RxtRow {
  int line = 0;
  double wavelength = 0;  // the row number (1, 2, ...) when the file has no wavelength column
  double m_r = 0, m_t = 0;
  double m_u = -1;  // < 0: not measured
};

struct RxtFile {
  std::string name;
  double sample_n = 1, slide_n = 1, sample_thickness = 0, slide_thickness = 0;  // mm
  double beam_diameter = 0, standard_reflectance = 1;
  int spheres = 0;
  RxtSphere reflection, transmission;
  int measurements = 2;  // 2 or 3
  bool has_wavelength = false;
  std::vector<RxtRow> rows;

  bool has_slides() const { return slide_n != 1 && slide_thickness > 0; }
};

RxtFile read_rxt(const std::filesystem::path& path);
RxtFile parse_rxt(const std::string& text, const std::string& name);

}  // namespace bssrdf
