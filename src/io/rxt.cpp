// Reader of iad's .rxt measurement files; see include/bssrdf/io/rxt.hpp. It follows iad 4's
// Read_Header, Read_Data_Legend and Read_Data_Line (iad_io.w): numbers as a stream, the legend
// as the rest of its line, per-row overrides that persist and constraints that do not.
#include "bssrdf/io/rxt.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "bssrdf/error.hpp"
#include "data_file.hpp"

namespace bssrdf {

namespace {

struct Token {
  std::string text;
  int line;
  std::size_t record;  // index of its line among the non-empty lines
};

double number_of(const Token& t, const std::string& file, const std::string& field) {
  std::size_t used = 0;
  double v = NAN;
  try {
    v = std::stod(t.text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != t.text.size() || !std::isfinite(v))
    throw FileError(file, t.line, field + " = '" + t.text + "': accepted range is a finite number");
  return v;
}

void check_range(const std::string& file, int line, const std::string& field, double v, double lo, double hi,
                 const std::string& range) {
  if (!(v >= lo && v <= hi))
    throw FileError(file, line, field + " = " + format_number(v) + ": accepted range is " + range);
}

// What a column letter sets; "" for letters iad does not know.
const std::map<char, std::string>& letters() {
  static const std::map<char, std::string> m = {{'L', "wavelength"},
                                                {'l', "wavelength (bssrdf's earlier spelling of L)"},
                                                {'r', "M_R"},
                                                {'t', "M_T"},
                                                {'u', "M_U"},
                                                {'n', "sample index of refraction"},
                                                {'N', "slide index of refraction"},
                                                {'d', "sample thickness"},
                                                {'D', "slide thickness"},
                                                {'E', "slide optical depth"},
                                                {'B', "beam diameter"},
                                                {'R', "reflectance standard"},
                                                {'T', "transmittance standard"},
                                                {'w', "wall reflectance"},
                                                {'W', "transmission sphere wall reflectance"},
                                                {'c', "unscattered fraction in M_R"},
                                                {'C', "unscattered fraction in M_T"},
                                                {'S', "number of spheres"},
                                                {'M', "number of spheres"},
                                                {'i', "angle of incidence"},
                                                {'e', "tolerance"},
                                                {'q', "quadrature points"},
                                                {'a', "albedo"},
                                                {'b', "optical thickness"},
                                                {'g', "anisotropy"},
                                                {'A', "mu_a"},
                                                {'F', "mu_s"}};
  return m;
}

// One value of a labelled row applied to the row (iad's Read_Data_Line_Per_Labels).
void apply_column(char c, double x, RxtRow& row, bool& w_read_transmission, const std::string& file, int line) {
  auto& s = row.setup;
  auto& k = row.constraints;
  auto unit = [&](const char* field) { check_range(file, line, field, x, 0, 1, "[0, 1]"); };
  switch (c) {
    case 'L':
    case 'l':
      row.wavelength = x;
      row.has_wavelength = true;
      break;
    case 'r':
      row.m_r = x;
      break;
    case 't':
      row.m_t = x;
      break;
    case 'u':
      row.m_u = x;
      break;
    case 'n':
      check_range(file, line, "sample index of refraction (n)", x, 1, 4, "1 to 4");
      s.sample_n = x;
      break;
    case 'N':
      check_range(file, line, "slide index of refraction (N)", x, 0, 4, "0 (none) or 1 to 4");
      s.slide_n = x < 1 ? 1 : x;
      break;
    case 'd':
      check_range(file, line, "sample thickness (d)", x, 1e-9, 1e6, "> 0 (mm)");
      s.sample_thickness = x;
      break;
    case 'D':
      check_range(file, line, "slide thickness (D)", x, 0, 1e6, ">= 0 (mm)");
      s.slide_thickness = x;
      break;
    case 'E':
      check_range(file, line, "slide optical depth (E)", x, 0, 1e3, "0 to 1000");
      s.slide_optical_depth = x;
      break;
    case 'B':
      check_range(file, line, "beam diameter (B)", x, 0, 1e6, ">= 0 (mm)");
      s.beam_diameter = x;
      break;
    case 'R':
      check_range(file, line, "reflectance standard (R)", x, 1e-9, 1, "(0, 1]");
      s.standard_reflectance = x;
      break;
    case 'T':
      check_range(file, line, "transmittance standard (T)", x, 0, 1, "[0, 1]");
      s.standard_transmittance = x;
      break;
    case 'w':
      unit("wall reflectance (w)");
      s.reflection.wall_reflectance = x;
      if (!w_read_transmission) s.transmission.wall_reflectance = x;
      break;
    case 'W':
      unit("transmission sphere wall reflectance (W)");
      s.transmission.wall_reflectance = x;
      w_read_transmission = true;
      break;
    case 'c':
      unit("unscattered fraction in M_R (c)");
      s.unscattered_in_m_r = x;
      break;
    case 'C':
      unit("unscattered fraction in M_T (C)");
      s.unscattered_in_m_t = x;
      break;
    case 'S':
    case 'M':
      if (!(x == 0 || x == 1 || x == 2))
        throw FileError(
            file, line,
            std::string("number of spheres (") + c + ") = " + format_number(x) + ": accepted range is 0, 1 or 2");
      s.spheres = static_cast<int>(x);
      break;
    case 'i':
      check_range(file, line, "angle of incidence (i)", x, 0, 90, "0 to 90 degrees");
      s.incidence_degrees = x;
      break;
    case 'e':
      check_range(file, line, "tolerance (e)", x, 1e-12, 1, "(0, 1]");
      k.tolerance = x;
      break;
    case 'q':
      check_range(file, line, "quadrature points (q)", x, 4, 256, "4 to 256");
      k.quadrature = static_cast<int>(x);
      break;
    case 'a':
      unit("albedo (a)");
      k.albedo = x;
      break;
    case 'b':
      check_range(file, line, "optical thickness (b)", x, 0, 1e6, ">= 0");
      k.optical_thickness = x;
      break;
    case 'g':
      check_range(file, line, "anisotropy (g)", x, -0.999999, 0.999999, "-1 < g < 1");
      k.g = x;
      break;
    case 'A':
      check_range(file, line, "mu_a (A)", x, 0, 1e6, ">= 0 (1/mm)");
      k.mu_a = x;
      break;
    case 'F':
      check_range(file, line, "mu_s (F)", x, 0, 1e6, ">= 0 (1/mm)");
      k.mu_s = x;
      break;
  }
}

// The legacy row M_R [M_T [M_U [r_w [t_w [r_std [t_std]]]]]] (iad's Read_Data_Line).
void apply_legacy(int index, double x, RxtRow& row, const std::string& file, int line) {
  auto& s = row.setup;
  switch (index) {
    case 0:
      row.m_r = x;
      break;
    case 1:
      row.m_t = x;
      break;
    case 2:
      row.m_u = x;
      break;
    case 3:
      check_range(file, line, "wall reflectance (r_w)", x, 0, 1, "[0, 1]");
      s.reflection.wall_reflectance = s.transmission.wall_reflectance = x;
      break;
    case 4:
      check_range(file, line, "transmission sphere wall reflectance (t_w)", x, 0, 1, "[0, 1]");
      s.transmission.wall_reflectance = x;
      break;
    case 5:
      check_range(file, line, "reflectance standard (r_std)", x, 1e-9, 1, "(0, 1]");
      s.standard_reflectance = x;
      break;
    case 6:
      check_range(file, line, "transmittance standard (t_std)", x, 0, 1, "[0, 1]");
      s.standard_transmittance = x;
      break;
  }
}

}  // namespace

const std::string& rxt_column_letters() {
  static const std::string text = [] {
    std::string s;
    for (const auto& [c, what] : letters()) s += (s.empty() ? "" : ", ") + std::string(1, c) + " " + what;
    return s;
  }();
  return text;
}

RxtFile parse_rxt(const std::string& text, const std::string& name) {
  if (text.rfind("IAD1", 0) != 0) throw FileError(name, 1, "the file must start with 'IAD1' (an iad .rxt file)");
  const auto records = comment_stripped_records(text.substr(4));
  std::vector<Token> tokens;
  for (std::size_t k = 0; k < records.size(); ++k)
    for (const auto& word : records[k].tokens) tokens.push_back({word, records[k].line, k});
  std::size_t at = 0;
  const int last_line = records.empty() ? 1 : records.back().line;
  auto next = [&](const std::string& field) -> const Token& {
    if (at >= tokens.size()) throw FileError(name, last_line, "missing " + field);
    return tokens[at++];
  };
  auto field = [&](const std::string& what, double lo, double hi, const std::string& range) {
    const Token& t = next(what);
    const double v = number_of(t, name, what);
    check_range(name, t.line, what, v, lo, hi, range);
    return v;
  };
  RxtFile f;
  f.name = name;
  f.sample_n = field("sample index of refraction", 1, 4, "1 to 4");
  f.slide_n = field("slide index of refraction", 0, 4, "0 (none) or 1 to 4");
  f.sample_thickness = field("sample thickness", 1e-9, 1e6, "> 0 (mm)");
  f.slide_thickness = field("slide thickness", 0, 1e6, ">= 0 (mm)");
  // iad: a slide of thickness 0, or of index 0 or 1, is no slide.
  if (f.slide_n < 1 || f.slide_thickness == 0) f.slide_n = 1;
  if (f.slide_n == 1) f.slide_thickness = 0;
  f.beam_diameter = field("beam diameter", 0, 1e6, ">= 0 (mm)");
  f.standard_reflectance = field("reflectance of the calibration standard", 1e-9, 1, "(0, 1]");
  const double count = field("number of spheres", 0, 2, "0, 1 or 2");
  if (count != std::floor(count))
    throw FileError(name, tokens[at - 1].line,
                    "number of spheres = " + tokens[at - 1].text + ": accepted range is 0, 1 or 2");
  f.spheres = static_cast<int>(count);
  for (auto* sphere : {&f.reflection, &f.transmission}) {
    const std::string which = sphere == &f.reflection ? "reflection sphere " : "transmission sphere ";
    sphere->diameter = field(which + "diameter", 0, 1e6, ">= 0 (mm)");
    sphere->sample_port = field(which + "sample port diameter", 0, 1e6, ">= 0 (mm)");
    sphere->third_port = field(which + "entrance/exit port diameter", 0, 1e6, ">= 0 (mm)");
    sphere->detector_port = field(which + "detector port diameter", 0, 1e6, ">= 0 (mm)");
    sphere->wall_reflectance = field(which + "wall reflectance", 0, 1, "[0, 1]");
    if (f.spheres > 0) {
      const double ports =
          std::pow(sphere->sample_port, 2) + std::pow(sphere->third_port, 2) + std::pow(sphere->detector_port, 2);
      if (!(sphere->diameter > 0) || !(ports < 4 * sphere->diameter * sphere->diameter))
        throw FileError(
            name, tokens[at - 1].line,
            which + "ports: their areas exceed the sphere's (diameter " + format_number(sphere->diameter) + " mm)");
    }
  }
  // The legend: a count, or column letters on the rest of its line without spaces and '-'
  // (iad's Read_Data_Legend).
  const Token& first = next("the data legend (a number of measurements or column letters)");
  if (std::isdigit(static_cast<unsigned char>(first.text[0])) || first.text[0] == '.') {
    const double count = number_of(first, name, "number of measurements");
    if (!(count >= 1 && count <= 7 && count == std::floor(count)))
      throw FileError(name, first.line, "number of measurements = " + first.text + ": accepted range is 1 to 7");
    // Values after the count on its line are rows (the terse layout); iad 4 ignores them.
    f.legend_count = static_cast<int>(count);
    f.measurements = std::min(f.legend_count, 3);
  } else {
    std::string legend;
    --at;
    while (at < tokens.size() && tokens[at].record == first.record) legend += tokens[at++].text;
    legend.erase(std::remove(legend.begin(), legend.end(), '-'), legend.end());
    for (char c : legend)
      if (!letters().count(c))
        throw FileError(
            name, first.line,
            std::string("column '") + c + "' in '" + legend + "': accepted letters are " + rxt_column_letters());
    f.columns = legend;
    f.measurements = 0;
    for (char c : {'r', 't', 'u'}) f.measurements += f.columns.find(c) != std::string::npos;
    if (f.measurements == 0)
      throw FileError(name, first.line, "columns '" + legend + "': accepted are columns with at least one of r, t, u");
  }
  // Rows: a stream of numbers, one group per row.
  RxtSetup running = f;
  int row_number = 0;
  while (at < tokens.size()) {
    RxtRow row;
    row.line = tokens[at].line;
    row.setup = running;
    ++row_number;
    auto value = [&](const std::string& what, int k, int of) {
      if (at >= tokens.size())
        throw FileError(name, row.line,
                        "row " + std::to_string(row_number) + " ends after " + std::to_string(k) + " of " +
                            std::to_string(of) + " values (missing " + what + ")");
      return number_of(tokens[at++], name, what);
    };
    if (f.columns.empty()) {
      double x = value("M_R", 0, f.legend_count);
      if (x > 1) {  // iad: a first value above 1 is a wavelength
        row.wavelength = x;
        row.has_wavelength = true;
        x = value("M_R", 0, f.legend_count);
      }
      static const char* names[] = {"M_R", "M_T", "M_U", "r_w", "t_w", "r_std", "t_std"};
      for (int k = 0; k < f.legend_count; ++k)
        apply_legacy(k, k == 0 ? x : value(names[k], k, f.legend_count), row, name, row.line);
    } else {
      bool w_read_transmission = false;
      const int n = static_cast<int>(f.columns.size());
      for (int k = 0; k < n; ++k) {
        const char c = f.columns[k];
        const int line = at < tokens.size() ? tokens[at].line : row.line;
        apply_column(c, value(std::string(1, c) + " (" + letters().at(c) + ")", k, n), row, w_read_transmission, name,
                     line);
      }
    }
    if (!row.has_wavelength) row.wavelength = row_number;
    if (row.has_wavelength && !(row.wavelength > 0))
      throw FileError(name, row.line, "wavelength = " + format_number(row.wavelength) + ": accepted range is > 0");
    f.has_wavelength = f.has_wavelength || row.has_wavelength;
    running = row.setup;
    f.rows.push_back(row);
  }
  if (f.rows.empty()) throw FileError(name, last_line, "no measurement rows");
  return f;
}

RxtFile read_rxt(const std::filesystem::path& path) {
  return parse_rxt(read_data_file(path, "the .rxt file"), path.string());
}

}  // namespace bssrdf
