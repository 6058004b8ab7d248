#include "bssrdf/materials.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bssrdf/error.hpp"
#include "bssrdf/text.hpp"
#include "io/data_file.hpp"

namespace bssrdf {
namespace {

using json = nlohmann::json;

// Reads one file's JSON; errors name the file and the JSON path of the offending field.
class FileReader {
 public:
  explicit FileReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw FileError(file_, 0, path + ": " + what);
  }

  const json& member(const json& object, const std::string& key, const std::string& path) const {
    if (!object.is_object()) fail(path, "expected an object");
    auto it = object.find(key);
    if (it == object.end()) fail(path, "missing required field '" + key + "'");
    return *it;
  }

  std::string string(const json& value, const std::string& path) const {
    if (!value.is_string()) fail(path, "expected a string, found " + std::string(value.type_name()));
    return value.get<std::string>();
  }

  double number(const json& value, const std::string& path) const {
    if (!value.is_number()) fail(path, "expected a number, found " + std::string(value.type_name()));
    return value.get<double>();
  }

  std::vector<double> numbers(const json& value, const std::string& path, std::size_t count) const {
    if (!value.is_array()) fail(path, "expected an array of " + std::to_string(count) + " numbers");
    if (value.size() != count)
      fail(path,
           std::to_string(value.size()) + " values given, the file declares " + std::to_string(count) + " channels");
    std::vector<double> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(number(value[i], path + "[" + std::to_string(i) + "]"));
    return out;
  }

  // A non-empty string (names, keys, citations).
  std::string text(const json& value, const std::string& path) const {
    std::string out = string(value, path);
    if (out.empty()) fail(path, "expected a non-empty string");
    return out;
  }

  // Fields outside the format are errors, not silently ignored: a typo ("sigma_s_prim") would
  // otherwise drop a coefficient. Derived quantities are computed, never read.
  void only_known_fields(const json& object, const std::string& path, std::initializer_list<const char*> known) const {
    for (const auto& [key, value] : object.items()) {
      bool ok = false;
      for (const char* k : known) ok |= key == k;
      if (ok) continue;
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      fail(path + "." + key, "unknown field (the format has: " + list + ")");
    }
  }

  std::vector<std::string> notes(const json& object, const std::string& path) const {
    std::vector<std::string> out;
    auto it = object.find("notes");
    if (it == object.end()) return out;
    if (it->is_string()) return {it->get<std::string>()};
    if (!it->is_array()) fail(path + ".notes", "expected a string or an array of strings");
    for (std::size_t i = 0; i < it->size(); ++i)
      out.push_back(string((*it)[i], path + ".notes[" + std::to_string(i) + "]"));
    return out;
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace

std::vector<std::string> close_matches(std::string_view name, const std::vector<std::string>& names,
                                       std::size_t max_results) {
  const std::string key = lower(name);
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const auto& candidate : names) {
    const std::string c = lower(candidate);
    std::size_t d = edit_distance(key, c);
    if (!key.empty() && (c.find(key) != std::string::npos || key.find(c) != std::string::npos))
      d = std::min<std::size_t>(d, 1);
    if (d <= std::max<std::size_t>(2, key.size() / 3)) scored.emplace_back(d, candidate);
  }
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (const auto& [d, n] : scored) {
    if (out.size() == max_results) break;
    out.push_back(n);
  }
  return out;
}

MaterialDatabase MaterialDatabase::load(const std::filesystem::path& path) {
  MaterialDatabase db;
  db.add_path(path);
  return db;
}

MaterialDatabase MaterialDatabase::load_with_user(const std::filesystem::path& user) {
  auto db = load(default_materials_dir());
  if (!user.empty()) db.add_path(user);
  return db;
}

void MaterialDatabase::add_path(const std::filesystem::path& path) {
  auto& db = *this;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(path))
      if (entry.path().extension() == ".json" && entry.path().filename().string().find("schema") == std::string::npos)
        files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) throw FileError(path.string(), 0, "no material files (*.json) in this directory");
    for (const auto& f : files) db.add_file(f);
  } else {
    db.add_file(path);
  }
}

void MaterialDatabase::add_file(const std::filesystem::path& path) {
  add_text(read_data_file(path, "the materials file"), path.string());
}

void MaterialDatabase::add_text(const std::string& text, const std::string& file_name) {
  const std::filesystem::path path = file_name;
  const FileReader reader(file_name);
  const json root = parse_json_document(text, file_name);

  if (reader.string(reader.member(root, "format", "$"), "$.format") != "bssrdf-materials")
    reader.fail("$.format", "expected \"bssrdf-materials\"");
  if (reader.number(reader.member(root, "version", "$"), "$.version") != 1)
    reader.fail("$.version", "only version 1 is understood");
  reader.only_known_fields(
      root, "$",
      {"format", "version", "source", "citation", "unit", "channels", "wavelength_nm", "notes", "materials"});
  const std::string source = reader.text(reader.member(root, "source", "$"), "$.source");
  const std::string citation = reader.text(reader.member(root, "citation", "$"), "$.citation");
  // Files spell units exactly (the schema's enum); the command line is more lenient.
  const std::string unit_text = reader.string(reader.member(root, "unit", "$"), "$.unit");
  if (unit_text != "um" && unit_text != "\u00b5m" && unit_text != "mm" && unit_text != "cm" && unit_text != "m")
    reader.fail("$.unit", "'" + unit_text + "' is not one of um, \u00b5m, mm, cm, m");
  const LengthUnit unit = parse_length_unit(unit_text, "unit");
  std::vector<std::string> channels;
  const json& channel_list = reader.member(root, "channels", "$");
  if (!channel_list.is_array() || channel_list.empty())
    reader.fail("$.channels", "expected a non-empty array of names");
  for (std::size_t i = 0; i < channel_list.size(); ++i) {
    const std::string where = "$.channels[" + std::to_string(i) + "]";
    channels.push_back(reader.text(channel_list[i], where));
    for (std::size_t j = 0; j + 1 < channels.size(); ++j)
      if (channels[j] == channels.back()) reader.fail(where, "'" + channels.back() + "' is repeated");
  }
  const auto file_notes = reader.notes(root, "$");
  // A spectral file: the wavelength of each channel in nm (Medium::validate checks the values).
  const std::vector<double> wavelength_nm =
      root.contains("wavelength_nm") ? reader.numbers(root["wavelength_nm"], "$.wavelength_nm", channels.size())
                                     : std::vector<double>{};

  const json& list = reader.member(root, "materials", "$");
  if (!list.is_array() || list.empty()) reader.fail("$.materials", "expected a non-empty array");
  for (std::size_t i = 0; i < list.size(); ++i) {
    std::string where = "$.materials[" + std::to_string(i) + "]";
    const json& entry = list[i];
    Material m;
    m.name = reader.text(reader.member(entry, "name", where), where + ".name");
    where += " (" + m.name + ")";
    reader.only_known_fields(entry, where, {"name", "eta", "sigma_a", "sigma_s", "g", "sigma_s_prime", "notes"});
    m.source = source;
    m.citation = citation;
    m.file = path.string();
    m.unit = unit;
    m.notes = file_notes;
    for (auto& n : reader.notes(entry, where)) m.notes.push_back(std::move(n));
    const std::size_t n = channels.size();
    m.medium.channel_names = channels;
    m.medium.wavelength_nm = wavelength_nm;
    m.medium.eta = reader.number(reader.member(entry, "eta", where), where + ".eta");
    m.medium.sigma_a = reader.numbers(reader.member(entry, "sigma_a", where), where + ".sigma_a", n);
    const bool has_prime = entry.contains("sigma_s_prime"), has_sigma_s = entry.contains("sigma_s");
    if (has_prime == has_sigma_s) reader.fail(where, "give exactly one of 'sigma_s' (with 'g') or 'sigma_s_prime'");
    if (has_prime) {
      if (entry.contains("g")) reader.fail(where + ".g", "'g' cannot be given with 'sigma_s_prime'");
      m.reduced_scattering_only = true;
      m.medium.sigma_s = reader.numbers(entry["sigma_s_prime"], where + ".sigma_s_prime", n);
      m.medium.g.assign(n, 0.0);
    } else {
      m.medium.sigma_s = reader.numbers(entry["sigma_s"], where + ".sigma_s", n);
      m.medium.g = entry.contains("g") ? reader.numbers(entry["g"], where + ".g", n) : std::vector<double>(n, 0.0);
    }
    for (auto& v : m.medium.sigma_a) v = coefficient_to_per_mm(v, unit);
    for (auto& v : m.medium.sigma_s) v = coefficient_to_per_mm(v, unit);
    try {
      m.medium.validate();
    } catch (const InvalidInput& e) {
      reader.fail(where, e.what());
    }
    for (const auto& existing : materials_)
      if (lower(existing.name) == lower(m.name))
        reader.fail(where + ".name", "'" + m.name + "' is already defined in " + existing.file);
    materials_.push_back(std::move(m));
  }
}

const Material& MaterialDatabase::find(std::string_view name) const {
  const std::string key = lower(name);
  for (const auto& m : materials_)
    if (lower(m.name) == key) return m;
  std::vector<std::string> names;
  for (const auto& m : materials_) names.push_back(m.name);
  const auto close = close_matches(name, names);
  std::string hint;
  for (const auto& c : close) hint += (hint.empty() ? "" : ", ") + c;
  throw InvalidInput("material", "'" + std::string(name) + "'",
                     hint.empty() ? "a name from 'bssrdf materials list' (" + std::to_string(names.size()) + " known)"
                                  : "a known material; did you mean: " + hint + "?");
}

std::filesystem::path default_materials_dir() {
  if (const char* env = std::getenv("BSSRDF_MATERIALS"); env && *env) return env;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path().parent_path() / "share" / "bssrdf" / "materials";
    if (std::filesystem::is_directory(installed, ec)) return installed;
  }
  return BSSRDF_MATERIALS_DIR;
}

}  // namespace bssrdf
