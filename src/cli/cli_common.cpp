#include "cli_common.hpp"

#include <unistd.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "bssrdf/error.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_selection.hpp"
#include "bssrdf/profile.hpp"

namespace bssrdf::cli {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// One value per channel: a single value applies to every channel.
std::vector<double> per_channel(std::vector<double> values, std::size_t channels, const std::string& field,
                                const std::string& reference_field) {
  if (values.size() == 1 && channels > 1) return std::vector<double>(channels, values[0]);
  if (values.size() != channels)
    throw InvalidInput(field + ": " + std::to_string(values.size()) + " values given, but " + reference_field +
                       " has " + std::to_string(channels) + " channels (give one value per channel, or one for all)");
  return values;
}

}  // namespace

double parse_number(const std::string& text, const std::string& field) {
  const std::string t = trim(text);
  double value = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (t.empty() || ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(value))
    throw InvalidInput(field, "'" + text + "'", "a finite number");
  return value;
}

double parse_length(const std::string& text, const std::string& field) {
  const double v = parse_number(text, field);
  if (!(std::abs(v) <= kMaxLength))
    throw InvalidInput(field, format_number(v),
                       "at most " + format_number(kMaxLength) + " (in the length unit; omit it for the default)");
  return v;
}

std::vector<double> parse_length_list(const std::string& text, const std::string& field) {
  auto values = parse_number_list(text, field);
  for (double v : values)
    if (!(std::abs(v) <= kMaxLength))
      throw InvalidInput(field, format_number(v),
                         "at most " + format_number(kMaxLength) + " each (in the length unit)");
  return values;
}

std::string count_range(std::int64_t min, std::int64_t max) {
  return std::to_string(min) + " to " + std::to_string(max);
}

std::int64_t parse_count(const std::string& text, const std::string& field, std::int64_t min, std::int64_t max) {
  const std::string t = trim(text);
  const auto refuse = [&] {
    return InvalidInput(field, "'" + text + "'", "a whole number from " + count_range(min, max));
  };
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (!t.empty() && ec == std::errc() && ptr == t.data() + t.size()) {
    if (value < min || value > max) throw refuse();
    return value;
  }
  // "1e6": a whole number written as a decimal; range-checked as a double before conversion.
  double d = 0;
  const auto [dptr, dec] = std::from_chars(t.data(), t.data() + t.size(), d);
  if (t.empty() || dec != std::errc() || dptr != t.data() + t.size() || !(d >= static_cast<double>(min)) ||
      !(d <= static_cast<double>(max)) || d != std::floor(d))
    throw refuse();
  return static_cast<std::int64_t>(d);
}

std::vector<double> parse_number_list(const std::string& text, const std::string& field) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    try {
      values.push_back(parse_number(item, field));
    } catch (const InvalidInput&) {
      throw InvalidInput(field, "'" + text + "'", "a comma-separated list of finite numbers");
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return values;
}

void MediumOptions::add_to(CLI::App& app) {
  auto* mat = app.add_option("--material,-m", material, "Material from the database (case-insensitive), e.g. Skin1");
  auto* sa = app.add_option("--sigma-a", sigma_a, "Absorption coefficient per channel, 1/unit (e.g. 0.032,0.17,0.48)");
  auto* ss = app.add_option("--sigma-s", sigma_s, "Scattering coefficient per channel, 1/unit");
  auto* gg = app.add_option("--g", g, "Henyey-Greenstein anisotropy per channel (or one for all), -1 < g < 1 [0]");
  auto* ch = app.add_option("--channels", channels, "Channel names, comma-separated [R,G,B for three]");
  app.add_option("--eta", eta, "Relative index of refraction n_medium/n_outside [1.3, or the material's]");
  app.add_option("--unit", unit, "Length unit of coefficients, radii and outputs: um, mm, cm, m [mm]");
  app.add_option("--db", db, "Your own materials directory or file, added to the bundled database");
  mat->excludes(sa)->excludes(ss)->excludes(gg)->excludes(ch);
}

MediumOptions::Resolved MediumOptions::resolve() const {
  Resolved out;
  out.unit = parse_length_unit(unit, "--unit");
  if (!material.empty()) {
    const auto database = MaterialDatabase::load_with_user(db);
    out.material = database.find(material);
    out.medium = out.material->medium;
  } else {
    if (sigma_a.empty() || sigma_s.empty())
      throw InvalidInput("medium: give --material NAME, or both --sigma-a and --sigma-s");
    const auto a = parse_number_list(sigma_a, "--sigma-a");
    const std::size_t n = a.size();
    out.medium.sigma_a = a;
    out.medium.sigma_s = per_channel(parse_number_list(sigma_s, "--sigma-s"), n, "--sigma-s", "--sigma-a");
    out.medium.g =
        g.empty() ? std::vector<double>(n, 0.0) : per_channel(parse_number_list(g, "--g"), n, "--g", "--sigma-a");
    if (channels.empty()) {
      out.medium.channel_names = default_channel_names(n);
    } else {
      std::string rest = channels;
      std::vector<std::string> names;
      std::size_t start = 0;
      while (true) {
        const auto comma = rest.find(',', start);
        names.push_back(trim(rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      if (names.size() != n)
        throw InvalidInput("--channels: " + std::to_string(names.size()) + " names given, but --sigma-a has " +
                           std::to_string(n) + " channels");
      out.medium.channel_names = names;
    }
    out.medium.eta = 1.3;
  }
  if (!eta.empty()) out.medium.eta = parse_number(eta, "--eta");
  try {
    out.medium.validate();  // still in the user's unit, so messages quote the numbers typed
  } catch (const InvalidInput& e) {
    // Name the option the user typed ("--sigma-a[G] = -1: ..."), not the library's field.
    std::string message = e.what();
    for (const std::string field : {"sigma_a", "sigma_s", "g", "eta"}) {
      if (message.rfind(field, 0) != 0) continue;
      const char next = message[field.size()];
      if (next != '[' && next != ' ') continue;
      std::string option = "--" + field;
      std::replace(option.begin(), option.end(), '_', '-');
      message =
          (out.material ? "material " + out.material->name + ": " + field : option) + message.substr(field.size());
      if (!out.material) {
        const auto plus = message.find(" + sigma_s[");
        if (plus != std::string::npos) message.replace(plus, 11, " + --sigma-s[");
      }
      break;
    }
    throw InvalidInput(message);
  }
  if (!out.material) {
    // Coefficients arrive in 1/unit; the library works in 1/mm.
    for (auto& v : out.medium.sigma_a) v = coefficient_to_per_mm(v, out.unit);
    for (auto& v : out.medium.sigma_s) v = coefficient_to_per_mm(v, out.unit);
  }
  return out;
}

std::vector<double> slab_thicknesses(const std::string& list, const std::string& d_min, const std::string& d_max,
                                     int samples, LengthUnit unit, const SlabThicknessRange& defaults) {
  if (!list.empty()) {
    if (!d_min.empty() || !d_max.empty()) throw InvalidInput("--thickness: give either --thickness or --d-min/--d-max");
    auto thickness = parse_length_list(list, "--thickness");
    for (double d : thickness)
      if (!(d > 0)) throw InvalidInput("--thickness", format_number(d), "> 0");
    return thickness;
  }
  const double mm = millimetres_per(unit);
  const double a = d_min.empty() ? defaults.d_min / mm : parse_length(d_min, "--d-min");
  const double b = d_max.empty() ? defaults.d_max / mm : parse_length(d_max, "--d-max");
  if (!(a > 0)) throw InvalidInput("--d-min", format_number(a), "> 0");
  if (!(b > a)) throw InvalidInput("--d-max", format_number(b), "> --d-min = " + format_number(a));
  if (samples == 0) samples = kThicknessSamples;
  if (samples < 2 || samples > kMaxThicknessSamples)
    throw InvalidInput("--samples", std::to_string(samples), count_range(2, kMaxThicknessSamples));
  return log_spaced(a, b, static_cast<std::size_t>(samples));
}

CLI::Validator file_name(const std::string& field) {
  return CLI::Validator(
      [field](std::string& text) {
        if (text.empty()) throw InvalidInput(field, "''", "a file name");
        return std::string();
      },
      "FILE");
}

void OutputOptions::add_to(CLI::App& app) {
  app.add_option("--format,-f", format, "Output format: table, json, csv [table on screen; by extension for -o]")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  app.add_option("-o,--output", output, "Write the result to FILE (atomically); the table still goes to stdout")
      ->check(file_name("-o"));
  app.add_flag("-q,--quiet", quiet, "With -o: print nothing on stdout");
}

Format OutputOptions::file_format() const {
  if (format == "json") return Format::json;
  if (format == "csv") return Format::csv;
  if (format == "table") return Format::table;
  if (!output.empty()) {
    const auto ext = std::filesystem::path(output).extension().string();
    if (ext == ".csv") return Format::csv;
    if (ext == ".txt") return Format::table;
    return Format::json;
  }
  return Format::table;
}

void emit(const OutputOptions& options, const std::string& file_content, const std::string& stdout_content) {
  if (!options.output.empty()) {
    write_file_atomically(options.output, file_content);
    if (!options.quiet) std::cout << stdout_content << "\nwritten: " << options.output << '\n';
  } else {
    std::cout << file_content;
  }
  std::cout.flush();
}

void emit(const OutputOptions& options, const std::function<std::string()>& json,
          const std::function<std::string()>& csv, const std::string& table) {
  switch (options.file_format()) {
    case Format::json:
      return emit(options, json(), table);
    case Format::csv:
      return emit(options, csv(), table);
    case Format::table:
      return emit(options, table, table);
  }
}

void warn_validity(const std::string& model, const std::string& channel, const ValidityReport& report) {
  std::string line;
  for (const auto& note : report)
    if (note.severity != Severity::note) line += (line.empty() ? "" : "; ") + describe(note);
  if (!line.empty()) std::cerr << "bssrdf: validity: channel " << channel << ", " << model << ": " << line << '\n';
}

void warn_validity(const Model& model, const Medium& medium) {
  for (std::size_t c = 0; c < medium.channels(); ++c)
    warn_validity(model.name(), medium.channel_names[c], model.validity(medium.reduced(c)));
}

std::function<void(std::uint64_t, std::uint64_t)> progress_bar(const std::string& label) {
  if (!::isatty(STDERR_FILENO)) return nullptr;
  auto last = std::make_shared<int>(-1);
  return [last, label](std::uint64_t done, std::uint64_t total) {
    const int percent = static_cast<int>(100 * done / std::max<std::uint64_t>(1, total));
    if (percent == *last) return;
    *last = percent;
    const int width = 40, filled = percent * width / 100;
    std::fprintf(stderr, "\r%s [%s%s] %3d%%", label.c_str(), std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), percent);
    if (done >= total) std::fprintf(stderr, "\r%*s\r", width + 16 + static_cast<int>(label.size()), "");
    std::fflush(stderr);
  };
}

double parse_accuracy(const std::string& text) {
  const double a = text.empty() ? kDefaultModelAccuracy : parse_number(text, "--accuracy");
  check_model_accuracy(a, "--accuracy");
  return a;
}

ChosenModel resolve_model(const std::string& name, const std::string& accuracy, const Medium& medium) {
  std::optional<double> a;  // without auto any --accuracy is refused as such, whatever its text
  if (!accuracy.empty()) a = name == "auto" ? parse_accuracy(accuracy) : kDefaultModelAccuracy;
  const auto chosen = select_model(name, a, medium, "--accuracy", "--model");
  return {chosen.name, chosen.note};
}

}  // namespace bssrdf::cli
