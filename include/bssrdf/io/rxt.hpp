// Integrating-sphere measurement files as Prahl's inverse adding-doubling (iad 4) reads them
// (".rxt"; Prahl, "Inverse Adding-Doubling" manual and iad's iad_io.w): read unchanged.
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
//   2                     # the data legend: a count 1-7, or column letters (see below)
//   500  0.30  0.40       # rows
//
// Like iad the header and the rows are streams of numbers: every number may sit on its own line
// or share one, '#' starts a comment anywhere. The legend is the rest of its line (spaces and '-'
// ignored):
//  - a count 1 to 7: each row is M_R [M_T [M_U [r_w [t_w [r_std [t_std]]]]]] (that many values),
//    preceded by a wavelength when the first value exceeds 1;
//  - column letters, one value per letter per row; a value overrides the header from that row on
//    (iad's letters): L wavelength, r M_R, t M_T, u M_U, n sample index, N slide index, d sample
//    thickness, D slide thickness, E slide optical depth, B beam diameter, R and T reflectance and
//    transmittance standards, w and W wall reflectance (w sets both until W is read), c and C the
//    fractions of unscattered reflection and transmission in M_R and M_T, S or M number of
//    spheres, i angle of incidence (degrees), e tolerance, q quadrature points, and the
//    constraints a albedo, b optical thickness, g anisotropy, A mu_a, F mu_s (held for that row only).
// Values are finite numbers; whether a row is physically possible (M_R + M_T <= 1, ...) is the
// fit's decision per row, as in iad. A malformed file raises FileError with the line:
// "sample.rxt:12: M_T = '0.2x': accepted range is a finite number".
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace bssrdf {

struct RxtSphere {
  double diameter = 0, sample_port = 0, third_port = 0, detector_port = 0;  // mm
  double wall_reflectance = 0;
};

// The sample and instrument (iad's measure_type): the header's values, which row columns override.
struct RxtSetup {
  double sample_n = 1, slide_n = 1, sample_thickness = 1, slide_thickness = 0;  // mm
  double slide_optical_depth = 0;  // absorption of each slide, mu_a * thickness (E)
  double beam_diameter = 0, standard_reflectance = 1;
  double standard_transmittance = 1;  // iad's t_std (T): the third-port reflectance in the T sphere
  int spheres = 0;
  RxtSphere reflection, transmission;
  double unscattered_in_m_r = 1, unscattered_in_m_t = 1;  // iad's c and C
  double incidence_degrees = 0;

  bool has_slides() const { return slide_n != 1 && slide_thickness > 0; }
};

// Per-row settings that apply to that row only (iad resets them each row); NaN: not given.
struct RxtConstraints {
  double albedo = NAN, optical_thickness = NAN, g = NAN, mu_a = NAN, mu_s = NAN;  // a b g A F
  double tolerance = NAN;                                                         // e
  int quadrature = 0;                                                             // q (0: not given)
};

struct RxtRow {
  int line = 0;
  double wavelength = 0;  // the row number (1, 2, ...) when the row has no wavelength
  bool has_wavelength = false;
  double m_r = 0, m_t = 0;  // 0: not measured (iad's convention)
  double m_u = 0;           // 0: not measured
  RxtSetup setup;           // the header with the row's columns applied
  RxtConstraints constraints;
};

struct RxtFile : RxtSetup {  // the header's setup
  std::string name;
  int measurements = 2;         // M_R, M_T, M_U among the columns (1 to 3)
  std::string columns;          // the legend's letters; empty for a count
  int legend_count = 0;         // the count (1-7) when the legend is one
  bool has_wavelength = false;  // some row has a wavelength
  std::vector<RxtRow> rows;
};

RxtFile read_rxt(const std::filesystem::path& path);
RxtFile parse_rxt(const std::string& text, const std::string& name);

// The column letters iad reads, each with what it sets ("r M_R", ...), for messages and docs.
const std::string& rxt_column_letters();

}  // namespace bssrdf
