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
#include "bssrdf/text.hpp"

namespace bssrdf::cli {
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
  app.add_option("--format,-f", format,
                 "Output format: table, json, csv [table on screen; for -o by its extension .txt, .json, .csv]")
      ->check(CLI::IsMember({"table", "json", "csv"}));
  app.add_option("-o,--output", output, "Write the result to FILE (atomically); the table still goes to stdout")
      ->check(file_name("-o"));
  app.add_flag("-q,--quiet", quiet, "With -o: print nothing on stdout");
  // An -o name whose format is unknown is refused when the line is read, before any work is done.
  app.parse_complete_callback([this] { file_format(); });
}

Format OutputOptions::file_format() const {
  if (format == "json") return Format::json;
  if (format == "csv") return Format::csv;
  if (format == "table") return Format::table;
  if (!output.empty()) {
    const auto ext = std::filesystem::path(output).extension().string();
    if (ext == ".csv") return Format::csv;
    if (ext == ".txt") return Format::table;
    if (ext == ".json") return Format::json;
    std::error_code ec;
    if (std::filesystem::is_directory(output, ec))
      throw InvalidInput("-o", "'" + output + "'", "a file, not a directory");
    throw InvalidInput("-o", "'" + output + "'", "a file ending in .json, .csv or .txt (or give -f json|csv|table)");
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
