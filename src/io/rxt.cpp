// Reader of iad's .rxt measurement files; see include/bssrdf/io/rxt.hpp.
#include "bssrdf/io/rxt.hpp"

#include <cmath>
#include <sstream>

#include "bssrdf/error.hpp"
#include "data_file.hpp"

namespace bssrdf {

namespace {

struct Token {
  std::string text;
  int line;
};

// Whitespace-separated tokens with '#' comments removed, grouped by line.
std::vector<std::vector<Token>> tokenize(const std::string& text) {
  std::vector<std::vector<Token>> lines;
  for (const auto& record : comment_stripped_records(text)) {
    std::vector<Token> tokens;
    for (const auto& word : record.tokens) tokens.push_back({word, record.line});
    lines.push_back(std::move(tokens));
  }
  return lines;
}

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

}  // namespace

RxtFile parse_rxt(const std::string& text, const std::string& name) {
  const auto lines = tokenize(text);
  RxtFile f;
  f.name = name;
  if (text.rfind("IAD1", 0) != 0) throw FileError(name, 1, "the file must start with 'IAD1' (an iad .rxt file)");
  // Flatten the header tokens (after IAD1) and keep the row lines for later.
  std::vector<Token> header;
  std::size_t line_index = 0, token_index = 1;  // skip IAD1
  auto next = [&](const std::string& field) -> Token {
    while (line_index < lines.size() && token_index >= lines[line_index].size()) ++line_index, token_index = 0;
    if (line_index >= lines.size())
      throw FileError(name, lines.empty() ? 1 : lines.back().back().line, "missing " + field);
    return lines[line_index][token_index++];
  };
  auto field = [&](const std::string& what, double lo, double hi, const std::string& range) {
    const Token t = next(what);
    const double v = number_of(t, name, what);
    if (!(v >= lo && v <= hi))
      throw FileError(name, t.line, what + " = " + format_number(v) + ": accepted range is " + range);
    return v;
  };
  f.sample_n = field("sample index of refraction", 1, 4, "1 to 4");
  f.slide_n = field("slide index of refraction", 1, 4, "1 to 4");
  f.sample_thickness = field("sample thickness", 1e-9, 1e6, "> 0 (mm)");
  f.slide_thickness = field("slide thickness", 0, 1e6, ">= 0 (mm)");
  f.beam_diameter = field("beam diameter", 0, 1e6, ">= 0 (mm)");
  f.standard_reflectance = field("reflectance of the calibration standard", 1e-9, 1, "(0, 1]");
  f.spheres = static_cast<int>(field("number of spheres", 0, 2, "0, 1 or 2"));
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
            name, lines[line_index].front().line,
            which + "ports: their areas exceed the sphere's (diameter " + format_number(sphere->diameter) + " mm)");
    }
  }
  // Number of measurements, or a column line.
  const Token kind = next("number of measurements");
  std::string columns;
  if (kind.text.find_first_not_of("lrtu") == std::string::npos) {
    columns = kind.text;
  } else {
    const double count = number_of(kind, name, "number of measurements");
    if (count == 1)
      throw FileError(name, kind.line,
                      "number of measurements = 1: accepted range is 2 (M_R, M_T) or 3 (M_R, M_T, M_U); "
                      "one measurement cannot separate absorption from scattering");
    if (!(count == 2 || count == 3))
      throw FileError(name, kind.line, "number of measurements = " + kind.text + ": accepted range is 2 or 3");
    columns = count == 2 ? "rt" : "rtu";
  }
  if (!(columns == "rt" || columns == "rtu" || columns == "lrt" || columns == "lrtu"))
    throw FileError(name, kind.line, "columns '" + columns + "': accepted are rt, rtu, lrt, lrtu");
  // Rows: the rest of the file, one line each.
  if (token_index < lines[line_index].size())
    throw FileError(name, kind.line,
                    "unexpected '" + lines[line_index][token_index].text + "' after the number of measurements");
  int row_number = 0;
  for (std::size_t k = line_index + 1; k < lines.size(); ++k) {
    const auto& tokens = lines[k];
    const int line = tokens.front().line;
    const std::size_t measured = columns.find('l') == std::string::npos ? columns.size() : columns.size() - 1;
    bool wavelength = columns[0] == 'l';
    if (columns.size() == measured && tokens.size() == measured + 1)
      wavelength = true;  // numbered format with a wavelength
    if (tokens.size() != measured + (wavelength ? 1 : 0))
      throw FileError(name, line,
                      "row has " + std::to_string(tokens.size()) + " values: accepted is " +
                          (wavelength ? "wavelength, " : "") + "M_R, M_T" + (measured == 3 ? ", M_U" : ""));
    RxtRow row;
    row.line = line;
    std::size_t i = 0;
    row.wavelength = wavelength ? number_of(tokens[i++], name, "wavelength") : ++row_number;
    if (wavelength) ++row_number;
    if (wavelength && !(row.wavelength > 0))
      throw FileError(name, line, "wavelength = " + tokens[0].text + ": accepted range is > 0");
    row.m_r = number_of(tokens[i++], name, "M_R");
    row.m_t = number_of(tokens[i++], name, "M_T");
    if (measured == 3) row.m_u = number_of(tokens[i++], name, "M_U");
    for (const auto& [what, v] : {std::pair{"M_R", row.m_r}, {"M_T", row.m_t}})
      if (!(v >= 0 && v <= 1))
        throw FileError(name, line, std::string(what) + " = " + format_number(v) + ": accepted range is [0, 1]");
    if (row.m_r + row.m_t > 1)
      throw FileError(
          name, line,
          "M_R + M_T = " + format_number(row.m_r + row.m_t) + ": accepted range is <= 1 (more light out than in)");
    if (measured == 3 && !(row.m_u >= 0 && row.m_u <= row.m_t))
      throw FileError(name, line,
                      "M_U = " + format_number(row.m_u) + ": accepted range is 0 to M_T = " + format_number(row.m_t));
    f.has_wavelength = wavelength;
    f.rows.push_back(row);
  }
  f.measurements = static_cast<int>(columns.find('l') == std::string::npos ? columns.size() : columns.size() - 1);
  if (f.rows.empty()) throw FileError(name, lines.back().back().line, "no measurement rows");
  return f;
}

RxtFile read_rxt(const std::filesystem::path& path) {
  return parse_rxt(read_data_file(path, "the .rxt file"), path.string());
}

}  // namespace bssrdf
