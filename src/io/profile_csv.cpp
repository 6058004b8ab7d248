#include "bssrdf/io/profile_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "bssrdf/error.hpp"
#include "data_file.hpp"

namespace bssrdf {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) {
    const auto b = field.find_first_not_of(" \t\r");
    const auto e = field.find_last_not_of(" \t\r");
    fields.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

constexpr const char* kMonteCarloChannel = "_R_entered";
// Bounds on R(r) and its standard error (1/unit^2): far beyond any real profile (1e12/mm^2 is the
// peak of a medium with a 1 um mean free path), yet squares and inverse squares stay finite.
constexpr double kMaxProfileValue = 1e30, kMinProfileStderr = 1e-30;

}  // namespace

MeasuredProfile parse_profile_csv(const std::string& text, const std::string& name, std::optional<LengthUnit> unit) {
  MeasuredProfile out;
  out.file = name;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  std::vector<std::string> header;
  std::vector<int> value_column, stderr_column;  // per channel
  std::map<std::string, std::size_t> channel_index;
  std::vector<double> raw_radius, raw_inner, raw_outer;
  int inner_column = -1, outer_column = -1;  // Monte Carlo bins' edges
  bool monte_carlo = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const auto fields = split(line);
    if (header.empty()) {
      header = fields;
      std::string r = header[0];
      if (r.rfind("radius", 0) != 0 && r != "r")
        throw FileError(name, line_number,
                        "the first column must be the radius ('radius' or 'radius_mm', ...), found '" + r + "'");
      const auto underscore = r.find('_');
      if (underscore != std::string::npos) {
        try {
          out.unit = parse_length_unit(r.substr(underscore + 1), "radius unit");
        } catch (const InvalidInput& e) {
          throw FileError(name, line_number, e.what());
        }
      } else {
        out.unit = unit.value_or(LengthUnit::millimetre);
      }
      // 'bssrdf reference -f csv' output: the channels are the "<channel>_R_entered" columns (per
      // entered flux, the models' normalisation); bin edges, per-incident and T(r) columns are not fitted.
      for (const auto& h : header) monte_carlo |= ends_with(h, kMonteCarloChannel);
      for (std::size_t i = 1; i < header.size() && monte_carlo; ++i) {
        if (header[i].rfind("radius_inner", 0) == 0) inner_column = static_cast<int>(i);
        if (header[i].rfind("radius_outer", 0) == 0) outer_column = static_cast<int>(i);
      }
      // Channels first, then their standard errors.
      for (std::size_t i = 1; i < header.size(); ++i) {
        std::string h = header[i];
        if (h.empty()) throw FileError(name, line_number, "column " + std::to_string(i + 1) + " has no name");
        if (ends_with(h, "_stderr") || ends_with(h, "_se")) continue;
        if (monte_carlo) {
          if (!ends_with(h, kMonteCarloChannel)) continue;
          h = h.substr(0, h.size() - std::string(kMonteCarloChannel).size());
        } else if (h.rfind("radius", 0) == 0) {
          throw FileError(name, line_number, "column '" + h + "': only the first column may be a radius");
        }
        const auto per = h.find("_per_");
        if (per != std::string::npos) h = h.substr(0, per);
        channel_index[h] = out.channels.size();
        out.channels.push_back({h, {}, {}});
        value_column.push_back(static_cast<int>(i));
        stderr_column.push_back(-1);
      }
      for (std::size_t i = 1; i < header.size(); ++i) {
        const std::string& h = header[i];
        std::string base;
        if (ends_with(h, "_stderr"))
          base = h.substr(0, h.size() - 7);
        else if (ends_with(h, "_se"))
          base = h.substr(0, h.size() - 3);
        else
          continue;
        if (monte_carlo) {
          if (!ends_with(base, kMonteCarloChannel)) continue;
          base = base.substr(0, base.size() - std::string(kMonteCarloChannel).size());
        }
        const auto it = channel_index.find(base);
        if (it == channel_index.end())
          throw FileError(name, line_number, "standard-error column '" + h + "' has no channel column '" + base + "'");
        stderr_column[it->second] = static_cast<int>(i);
      }
      if (out.channels.empty()) throw FileError(name, line_number, "no channel columns after the radius");
      continue;
    }
    if (fields.size() != header.size())
      throw FileError(name, line_number,
                      std::to_string(fields.size()) + " fields, the header has " + std::to_string(header.size()));
    const auto number = [&](std::size_t column) {
      const std::string& f = fields[column];
      double v = 0;
      const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (f.empty() || ec != std::errc() || ptr != f.data() + f.size() || !std::isfinite(v))
        throw FileError(name, line_number, header[column] + " = '" + f + "': accepted range is a finite number");
      return v;
    };
    const double r = number(0);
    if (r < 0) throw FileError(name, line_number, header[0] + " = " + format_number(r) + ": accepted range is >= 0");
    if (!raw_radius.empty() && !(r > raw_radius.back()))
      throw FileError(name, line_number,
                      header[0] + " = " + format_number(r) + ": accepted range is > " +
                          format_number(raw_radius.back()) + " (radii must increase)");
    // A Monte Carlo bin no photon reached (value and standard error 0) carries no information.
    bool empty_bin = false;
    for (std::size_t c = 0; c < out.channels.size() && monte_carlo; ++c)
      empty_bin |= number(static_cast<std::size_t>(value_column[c])) == 0 && stderr_column[c] >= 0 &&
                   number(static_cast<std::size_t>(stderr_column[c])) == 0;
    if (empty_bin) {
      ++out.empty_bins;
      continue;
    }
    raw_radius.push_back(r);
    if (inner_column >= 0 && outer_column >= 0) {
      const double inner = number(static_cast<std::size_t>(inner_column)),
                   outer = number(static_cast<std::size_t>(outer_column));
      if (!(inner >= 0 && inner <= r && r <= outer && inner < outer))
        throw FileError(name, line_number,
                        "bin " + format_number(inner) + " to " + format_number(outer) +
                            ": accepted is 0 <= inner <= radius <= outer, inner < outer");
      raw_inner.push_back(inner);
      raw_outer.push_back(outer);
    }
    for (std::size_t c = 0; c < out.channels.size(); ++c) {
      const double v = number(static_cast<std::size_t>(value_column[c]));
      if (!(v >= 0 && v <= kMaxProfileValue))
        throw FileError(name, line_number,
                        header[value_column[c]] + " = " + format_number(v) + ": accepted range is 0 to " +
                            format_number(kMaxProfileValue));
      out.channels[c].value.push_back(v);
      if (stderr_column[c] >= 0) {
        const double s = number(static_cast<std::size_t>(stderr_column[c]));
        // Relative to the largest value a profile may hold, so weights 1/s^2 and chi^2 stay finite.
        if (!(s >= kMinProfileStderr && s <= kMaxProfileValue))
          throw FileError(name, line_number,
                          header[stderr_column[c]] + " = " + format_number(s) + ": accepted range is " +
                              format_number(kMinProfileStderr) + " to " + format_number(kMaxProfileValue));
        out.channels[c].standard_error.push_back(s);
      }
    }
  }
  if (header.empty()) throw FileError(name, 0, "empty file: expected a header line and data rows");
  if (raw_radius.size() < 4)
    throw FileError(name, line_number, std::to_string(raw_radius.size()) + " data rows: accepted range is at least 4");
  const double mm = millimetres_per(out.unit);
  for (double r : raw_radius) out.radius.push_back(r * mm);
  for (double r : raw_inner) out.radius_inner.push_back(r * mm);
  for (double r : raw_outer) out.radius_outer.push_back(r * mm);
  for (auto& c : out.channels) {
    for (auto& v : c.value) v /= mm * mm;
    for (auto& s : c.standard_error) s /= mm * mm;
  }
  return out;
}

MeasuredProfile read_profile_csv(const std::filesystem::path& path, std::optional<LengthUnit> unit) {
  return parse_profile_csv(read_data_file(path, "the profile file"), path.string(), unit);
}

}  // namespace bssrdf
