// Pieces every subcommand shares: the medium options, number-list parsing, output formats and
// writing results to stdout or atomically to a file.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bssrdf/error.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/units.hpp"
#include "bssrdf/validity.hpp"

namespace bssrdf {
struct SlabThicknessRange;
}

namespace bssrdf::cli {

// "1,2.5,3" -> {1, 2.5, 3}; throws InvalidInput naming `field` for anything that is not a number.
std::vector<double> parse_number_list(const std::string& text, const std::string& field);
double parse_number(const std::string& text, const std::string& field);

// Ranges shared by the count options. 1e10 photons is hours of tracing per channel.
constexpr std::int64_t kMaxPhotons = 10'000'000'000, kMaxSeed = INT64_MAX, kMaxThreads = 4096, kMaxBins = 10'000'000;
// "1 to 10000000000", the accepted range of a count.
std::string count_range(std::int64_t min, std::int64_t max);
// A length (thickness, radius) in the user's unit: a finite number of magnitude at most kMaxLength,
// so every derived length, area and bin width stays a normal double; the sign and the lower bound
// are checked where the length is used.
inline constexpr double kMaxLength = 1e6;
double parse_length(const std::string& text, const std::string& field);
std::vector<double> parse_length_list(const std::string& text, const std::string& field);
// A whole number in [min, max] ("1000000" or "1e6"); parsed as signed and range-checked before any
// conversion, so "-1" is refused instead of wrapping to 2^64 - 1. Throws InvalidInput naming `field`.
std::int64_t parse_count(const std::string& text, const std::string& field, std::int64_t min, std::int64_t max);

// A count option (photons, bins, samples, seed, threads) bound to `value` through parse_count; the
// accepted range is appended to the help text and quoted by the error.
template <class Integer>
CLI::Option* add_count_option(CLI::App& app, const std::string& names, Integer& value, std::int64_t min,
                              std::int64_t max, const std::string& help) {
  const auto long_name = names.find("--");  // errors quote the long name when there is one
  const std::string field = long_name == std::string::npos
                                ? names.substr(0, names.find(','))
                                : names.substr(long_name, names.find(',', long_name) - long_name);
  return app.add_option_function<std::string>(
      names,
      [&value, field, min, max](const std::string& text) {
        value = static_cast<Integer>(parse_count(text, field, min, max));
      },
      help + " (" + count_range(min, max) + ")");
}

// --material NAME | --sigma-a with --sigma-s or --sigma-s-prime [--g] [--channels], with --eta, --unit
// and --db: the one parser of a medium on the command line.
struct MediumOptions {
  std::string material, sigma_a, sigma_s, sigma_s_prime, g, eta, unit = "mm", channels, db, wavelengths;
  // The bundled database plus --db, when the caller has loaded it already (lut --all: once for every material, not
  // once per material and kind); null: resolve() loads it.
  const MaterialDatabase* loaded = nullptr;

  void add_to(CLI::App& app);
  // Only the inline coefficients (--sigma-a, --sigma-s, --sigma-s-prime, --g, --channels, --eta), for
  // a command that has its own --unit, --db and material name (materials export).
  void add_coefficients_to(CLI::App& app);

  struct Resolved {
    Medium medium;  // 1/mm
    std::optional<Material> material;
    LengthUnit unit;  // the unit of inputs and outputs
  };
  // Validates everything; throws InvalidInput with the option's name.
  Resolved resolve() const;
};

// --model auto: the cheapest model measured within `accuracy` of the Monte Carlo reference for this
// medium (model_choice.hpp), with a line for people saying why; no --model (an empty name): the
// registry's default (default_model), with its reason when it is not `exact`; any other name is
// returned as given.
struct ChosenModel {
  std::string name;
  std::string note;  // why this model: --model auto's choice, or why the default is not exact; else empty
};
ChosenModel resolve_model(const std::string& name, const std::string& accuracy, const Medium& medium);
// --accuracy: a relative error, 0 < value < 10; empty gives the default 0.1.
double parse_accuracy(const std::string& text);

// Slab thicknesses in --unit: `list` (--thickness, comma-separated), else `samples` thicknesses
// log-spaced from --d-min to --d-max, each empty one taken from `defaults` (mm, the library's rule:
// default_thickness_range). Throws InvalidInput naming the option.
std::vector<double> slab_thicknesses(const std::string& list, const std::string& d_min, const std::string& d_max,
                                     int samples, LengthUnit unit, const SlabThicknessRange& defaults);

// The library's errors name its own fields ("radii", "to", "format"), never a flag: runs f, and an
// InvalidInput naming a field of `flags` is rethrown naming the command line's flag instead.
template <class F>
auto with_flag_names(std::initializer_list<std::pair<std::string_view, std::string_view>> flags, F&& f)
    -> decltype(f()) {
  try {
    return f();
  } catch (const InvalidInput& e) {
    for (const auto& [field, flag] : flags)
      if (e.field() == field) throw InvalidInput(std::string(flag), e.value(), e.accepted());
    throw;
  }
}

// For -o and other file options: refuses an empty name, which would otherwise silently mean "no file".
CLI::Validator file_name(const std::string& field);

enum class Format { table, json, csv };

struct OutputOptions {
  std::string format;  // empty: table on stdout, or from the -o file's extension
  std::string output;  // -o FILE
  bool quiet = false;

  void add_to(CLI::App& app);
  // The format of the file (-o) or of stdout.
  Format file_format() const;
};

// Writes `file_content` to -o atomically (if given) and prints `stdout_content` unless quiet.
void emit(const OutputOptions& options, const std::string& file_content, const std::string& stdout_content);
// The same with the file's content chosen by its format: json() or csv() (computed only then) or the
// table, which is also what stdout shows with -o.
void emit(const OutputOptions& options, const std::function<std::string()>& json,
          const std::function<std::string()>& csv, const std::string& table);

// Validity is never hidden: each channel whose report has a warning or an invalid entry gets one
// line on stderr ("bssrdf: validity: channel G, better-dipole: invalid [code] message; ..."),
// whatever the output format and -q (which silences only the table).
void warn_validity(const std::string& model, const std::string& channel, const ValidityReport& report);
void warn_validity(const Model& model, const Medium& medium);

// A one-line progress bar on stderr, only when stderr is a terminal (nullptr otherwise).
std::function<void(std::uint64_t done, std::uint64_t total)> progress_bar(const std::string& label);

}  // namespace bssrdf::cli
