#include "bssrdf/io/spectrum_file.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "bssrdf/error.hpp"
#include "data_file.hpp"

namespace bssrdf {
namespace {

constexpr std::size_t kMaxRows = 1'000'000;

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string current;
  for (char c : line) {
    if (c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r') {
      if (!current.empty()) out.push_back(std::move(current)), current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) out.push_back(std::move(current));
  return out;
}

bool number(const std::string& text, double& value) {
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

struct Table {
  std::vector<std::string> names;  // of the reflectance columns
  std::vector<int> line;
  std::vector<std::vector<double>> rows;
};

Table read_table(const std::string& text, const std::string& file) {
  Table t;
  std::istringstream in(text);
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const bool comment = raw.find('#') != std::string::npos;
    std::string body = raw.substr(0, raw.find('#'));
    auto f = fields(body);
    double v = 0;
    if (f.empty() && comment && t.rows.empty()) {  // a commented header names the columns
      auto h = fields(raw.substr(raw.find('#') + 1));
      if (h.size() >= 2 && !number(h[0], v)) t.names.assign(h.begin() + 1, h.end());
      continue;
    }
    if (f.empty()) continue;
    if (!number(f[0], v)) {
      if (!t.rows.empty()) throw FileError(file, line_number, "'" + f[0].substr(0, 40) + "' is not a wavelength");
      if (f.size() >= 2) t.names.assign(f.begin() + 1, f.end());
      continue;
    }
    std::vector<double> row;
    for (const auto& x : f) {
      if (!number(x, v)) throw FileError(file, line_number, "'" + x.substr(0, 40) + "' is not a finite number");
      row.push_back(v);
    }
    if (row.size() < 2) throw FileError(file, line_number, "expected a wavelength and at least one reflectance");
    if (!t.rows.empty() && row.size() != t.rows.front().size())
      throw FileError(
          file, line_number,
          std::to_string(row.size()) + " columns, but the first row has " + std::to_string(t.rows.front().size()));
    if (t.rows.size() >= kMaxRows) throw FileError(file, line_number, "more than 1000000 rows");
    t.rows.push_back(std::move(row));
    t.line.push_back(line_number);
  }
  if (t.rows.size() < 2) throw FileError(file, 0, "fewer than 2 rows of data (wavelength nm, reflectance)");
  const std::size_t columns = t.rows.front().size() - 1;
  if (t.names.size() != columns) {
    t.names.clear();
    for (std::size_t i = 1; i <= columns; ++i) t.names.push_back(std::to_string(i));
  }
  return t;
}

}  // namespace

std::vector<std::string> spectrum_columns(const std::string& text, const std::string& file_name) {
  return read_table(text, file_name).names;
}

ReflectanceSpectrum parse_spectrum(const std::string& text, const std::string& file_name, const std::string& column) {
  const Table t = read_table(text, file_name);
  std::size_t index = 0;
  if (!column.empty()) {
    std::string all;
    index = t.names.size();
    for (std::size_t i = 0; i < t.names.size(); ++i) {
      if (t.names[i] == column || std::to_string(i + 1) == column) index = i;
      all += (i ? ", " : "") + t.names[i];
    }
    if (index == t.names.size())
      throw InvalidInput("column", "'" + column + "'",
                         "one of " + all + " (or 1-" + std::to_string(t.names.size()) + ")");
  }
  ReflectanceSpectrum s;
  s.file = file_name;
  s.column = t.names[index];
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const double nm = t.rows[r][0], value = t.rows[r][index + 1];
    if (!(nm >= 200 && nm <= 20000))
      throw FileError(file_name, t.line[r], "wavelength " + format_number(nm) + " nm: accepted range is 200 to 20000");
    if (!s.wavelength_nm.empty() && !(nm > s.wavelength_nm.back()))
      throw FileError(file_name, t.line[r], "wavelength " + format_number(nm) + " nm: not increasing");
    if (!(value >= 0 && value <= 2))
      throw FileError(file_name, t.line[r],
                      "reflectance " + format_number(value) + ": accepted range is 0 to 2 (a reflectance factor)");
    s.wavelength_nm.push_back(nm);
    s.reflectance.push_back(value);
  }
  return s;
}

ReflectanceSpectrum read_spectrum(const std::string& path, const std::string& column) {
  return parse_spectrum(read_data_file(path, "the spectrum file"), path, column);
}

}  // namespace bssrdf
