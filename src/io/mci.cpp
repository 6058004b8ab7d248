#include "bssrdf/io/mci.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/units.hpp"
#include "data_file.hpp"

namespace bssrdf {
namespace {

// Physical bounds of an MCML run: lengths from 1 nm to 10 m (cm), bins and photons within what a
// run can store and trace.
constexpr double kMinMciLength = 1e-7, kMaxMciLength = 1e3;
constexpr long long kMaxMciBins = 10'000'000, kMaxMciPhotons = 10'000'000'000;

using Record = TextRecord;

class Reader {
 public:
  Reader(const std::string& text, std::string name)
      : records_(comment_stripped_records(text)), name_(std::move(name)) {}

  // The next record, which must have `count` tokens (or at least min_count .. count).
  const Record& next(const std::string& what, std::size_t min_count, std::size_t count) {
    if (index_ >= records_.size()) {
      const int last = records_.empty() ? 0 : records_.back().line;
      throw FileError(name_, last, "unexpected end of file: expected " + what);
    }
    const Record& r = records_[index_++];
    if (r.tokens.size() < min_count || r.tokens.size() > count)
      throw FileError(name_, r.line,
                      "expected " + what + " (" + std::to_string(count) + " value" + (count > 1 ? "s" : "") +
                          "), found " + std::to_string(r.tokens.size()) + " on this line");
    return r;
  }

  double number(const Record& r, std::size_t i, const std::string& field) const {
    const std::string& t = r.tokens[i];
    double v = 0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
      throw FileError(name_, r.line, field + " = '" + t + "': not a finite number");
    return v;
  }
  // Range-checked as a double before the conversion, so 3e9 bins cannot wrap.
  long long integer(const Record& r, std::size_t i, const std::string& field, long long min, long long max) const {
    const double v = number(r, i, field);
    if (v != std::floor(v) || v < static_cast<double>(min) || v > static_cast<double>(max))
      throw FileError(name_, r.line,
                      field + " = " + r.tokens[i] + ": accepted range is a whole number from " + std::to_string(min) +
                          " to " + std::to_string(max));
    return static_cast<long long>(v);
  }
  // A length or index within [min, max] (cm for lengths), so every derived bin width stays a normal number.
  double within(const Record& r, std::size_t i, const std::string& field, double min, double max) const {
    const double v = number(r, i, field);
    if (!(v >= min && v <= max))
      throw FileError(
          name_, r.line,
          field + " = " + r.tokens[i] + ": accepted range is " + format_number(min) + " to " + format_number(max));
    return v;
  }
  bool done() const { return index_ >= records_.size(); }
  int line() const { return index_ < records_.size() ? records_[index_].line : 0; }
  const std::string& name() const { return name_; }

 private:
  std::vector<Record> records_;
  std::size_t index_ = 0;
  std::string name_;
};

}  // namespace

MciFile parse_mci(const std::string& text, const std::string& name) {
  Reader in(text, name);
  MciFile file;
  const Record& version = in.next("the file version", 1, 1);
  file.version = in.number(version, 0, "file version");
  const Record& count = in.next("the number of runs", 1, 1);
  const auto runs = in.integer(count, 0, "number of runs", 1, 10'000);
  const double cm = millimetres_per(LengthUnit::centimetre);
  for (long long k = 0; k < runs; ++k) {
    MciRun run;
    const std::string prefix = "run " + std::to_string(k + 1) + ": ";
    const Record& out = in.next(prefix + "output file name and format (A or B)", 1, 2);
    run.line = out.line;
    run.output_file = out.tokens[0];
    if (out.tokens.size() == 2) {
      const std::string& f = out.tokens[1];
      if (f != "A" && f != "a" && f != "B" && f != "b")
        throw FileError(name, out.line, "output format = '" + f + "': accepted values are A (ASCII) or B (binary)");
      run.output_format = static_cast<char>(std::toupper(static_cast<unsigned char>(f[0])));
    }
    const Record& photons = in.next(prefix + "the number of photons", 1, 1);
    run.photons = static_cast<std::uint64_t>(in.integer(photons, 0, "number of photons", 1, kMaxMciPhotons));
    const Record& grid = in.next(prefix + "dz and dr [cm]", 2, 2);
    run.dz = in.within(grid, 0, "dz", kMinMciLength, kMaxMciLength) * cm;
    run.dr = in.within(grid, 1, "dr", kMinMciLength, kMaxMciLength) * cm;
    const Record& sizes = in.next(prefix + "the numbers of dz, dr and da bins", 3, 3);
    run.nz = static_cast<int>(in.integer(sizes, 0, "number of dz bins", 1, kMaxMciBins));
    run.nr = static_cast<int>(in.integer(sizes, 1, "number of dr bins", 1, kMaxMciBins));
    run.na = static_cast<int>(in.integer(sizes, 2, "number of da bins", 1, kMaxMciBins));
    if (run.nz * run.dz > kMaxMciLength * cm || run.nr * run.dr > kMaxMciLength * cm)
      throw FileError(name, sizes.line,
                      "nz*dz and nr*dr (the grid's depth and radius) = " + format_number(run.nz * run.dz / cm) + ", " +
                          format_number(run.nr * run.dr / cm) + " cm: accepted range is up to " +
                          format_number(kMaxMciLength) + " cm each");
    const Record& layers = in.next(prefix + "the number of layers", 1, 1);
    const auto layer_count = in.integer(layers, 0, "number of layers", 1, 1000);
    run.stack.channel_names = {"mcml"};
    const Record& above = in.next(prefix + "the refractive index above", 1, 1);
    run.stack.ambient_above = in.within(above, 0, "n above", kMinRefractiveIndex, kMaxRefractiveIndex);
    for (long long i = 0; i < layer_count; ++i) {
      const std::string field = "layer " + std::to_string(i + 1);
      const Record& r = in.next(prefix + field + ": n mua mus g d", 5, 5);
      Layer layer;
      layer.name = "layer " + std::to_string(i + 1);
      layer.n = in.within(r, 0, field + " n", kMinRefractiveIndex, kMaxRefractiveIndex);
      const double mua = in.number(r, 1, field + " mua"), mus = in.number(r, 2, field + " mus");
      const double g = in.number(r, 3, field + " g");
      if (mua < 0) throw FileError(name, r.line, field + " mua = " + r.tokens[1] + ": accepted range is >= 0");
      if (mus < 0) throw FileError(name, r.line, field + " mus = " + r.tokens[2] + ": accepted range is >= 0");
      if (!(g > -1 && g < 1))
        throw FileError(name, r.line, field + " g = " + r.tokens[3] + ": accepted range is -1 < g < 1");
      layer.thickness = in.within(r, 4, field + " d", kMinMciLength, kMaxMciLength) * cm;
      layer.sigma_a = {mua / cm};
      layer.sigma_s = {mus / cm};
      layer.g = {g};
      run.stack.layers.push_back(std::move(layer));
    }
    const Record& below = in.next(prefix + "the refractive index below", 1, 1);
    run.stack.ambient_below = in.within(below, 0, "n below", kMinRefractiveIndex, kMaxRefractiveIndex);
    try {
      run.stack.validate();
    } catch (const InvalidInput& e) {
      throw FileError(name, run.line, prefix + e.what());
    }
    file.runs.push_back(std::move(run));
  }
  if (!in.done())
    throw FileError(name, in.line(), "unexpected content after the last of " + std::to_string(runs) + " run(s)");
  return file;
}

MciFile read_mci(const std::filesystem::path& path) {
  return parse_mci(read_data_file(path, "the MCML input file"), path.string());
}

}  // namespace bssrdf
