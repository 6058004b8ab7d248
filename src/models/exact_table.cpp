// Reading and writing the exact model's table (format: data/exact/README.md), and finding the
// bundled one.
#include "bssrdf/models/exact_table.hpp"

#include <bit>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>

#include "../io/data_file.hpp"
#include "bssrdf/error.hpp"

namespace bssrdf {

static_assert(std::endian::native == std::endian::little, "the exact table is stored little-endian");

namespace {

constexpr char kMagic[8] = {'B', 'S', 'S', 'R', 'D', 'F', 'X', '1'};
constexpr char kErrorsMagic[8] = {'B', 'S', 'S', 'R', 'D', 'F', 'E', '1'};
constexpr const char* kField = "exact table";

bool increasing(const std::vector<double>& v) {
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i] > v[i - 1])) return false;
  return !v.empty();
}

template <class Array>
void append_bytes(std::string& out, const Array& values) {
  if (values.empty()) return;  // data() may be null
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(typename Array::value_type));
}

// Reads `count` values of T from `in` straight into `values` (no copy of the file), after checking that
// the file still holds them (`remaining` bytes): a header claiming more is a truncated table, refused
// before anything is allocated.
template <class Array>
void read_array(std::istream& in, std::uintmax_t& remaining, std::size_t count, Array& values,
                const std::string& path) {
  using T = typename Array::value_type;
  if (count > remaining / sizeof(T)) throw InvalidInput(kField, path, "a complete table file (truncated data)");
  values.resize(count);
  if (count == 0) return;  // (a version 1 table has no fine totals)
  const auto bytes = static_cast<std::streamsize>(count * sizeof(T));
  if (!in.read(reinterpret_cast<char*>(values.data()), bytes))
    throw InvalidInput(kField, path, "a complete table file (truncated data)");
  remaining -= static_cast<std::uintmax_t>(bytes);
}

// Steps over `count` values of T (a version-2 table's inline errors, unread), checked as read_array does.
template <class T>
void skip_array(std::istream& in, std::uintmax_t& remaining, std::size_t count, const std::string& path) {
  if (count > remaining / sizeof(T)) throw InvalidInput(kField, path, "a complete table file (truncated data)");
  in.seekg(static_cast<std::streamoff>(count * sizeof(T)), std::ios::cur);
  remaining -= count * sizeof(T);
}

}  // namespace

void ExactTable::validate() const {
  if (!increasing(albedo_prime) || !increasing(g) || !increasing(eta))
    throw InvalidInput(kField, "axes", "non-empty increasing albedo', g and eta nodes");
  if (radii < 2 || !(d_ln_r > 0)) throw InvalidInput(kField, "radii", "at least 2 radii with a positive step");
  const std::size_t n = nodes() * radii;
  if (ln_y.size() != n || (relative_error.size() != n && !relative_error.empty()) || total.size() != nodes())
    throw InvalidInput(kField, "array sizes", std::to_string(n) + " values and " + std::to_string(nodes()) + " totals");
  for (float v : ln_y)
    if (!std::isfinite(v)) throw InvalidInput(kField, "ln_y", "finite values");
  for (double t : total)
    if (!(t > 0 && t < 1)) throw InvalidInput(kField, "total = " + std::to_string(t), "0 < total < 1");
  if (!total_eta.empty()) {
    if (!increasing(total_eta) || total_eta.front() != eta.front() || total_eta.back() != eta.back())
      throw InvalidInput(kField, "total_eta", "increasing eta nodes from the first to the last of eta");
    if (fine_total.size() != total_eta.size() * g.size() * albedo_prime.size())
      throw InvalidInput(kField, "fine_total",
                         std::to_string(total_eta.size() * g.size() * albedo_prime.size()) + " totals");
    for (double t : fine_total)
      if (!(t > 0 && t < 1)) throw InvalidInput(kField, "fine total = " + std::to_string(t), "0 < total < 1");
  } else if (!fine_total.empty()) {
    throw InvalidInput(kField, "fine_total", "none without total_eta");
  }
}

// Writes `bytes` to `path` by way of PATH.partial: never a half-written file under the real name.
void write_atomically(const std::string& path, const std::string& bytes, const char* what) {
  const std::string temporary = path + ".partial";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!file) throw FileError(path, 0, std::string("cannot write the ") + what);
  }
  std::filesystem::rename(temporary, path);
}

void write_exact_table(const ExactTable& table, const std::string& path) {
  table.validate();
  nlohmann::json header;
  header["format"] = "bssrdf-exact-table";
  header["version"] = 3;
  header["albedo_prime"] = table.albedo_prime;
  header["g"] = table.g;
  header["eta"] = table.eta;
  header["ln_r0"] = table.ln_r0;
  header["d_ln_r"] = table.d_ln_r;
  header["radii"] = table.radii;
  if (!table.total_eta.empty()) header["total_eta"] = table.total_eta;
  header["layout"] = std::string("ln_y float32 [eta][g][albedo_prime][radius], total float64 [eta][g][albedo_prime]") +
                     (table.total_eta.empty() ? "" : ", fine_total float64 [total_eta][g][albedo_prime]") +
                     "; little-endian; relative_error uint16 (1e-4 units, 65535 = extrapolated) in ln_y's order in "
                     "the file beside it named as this one plus .errors";
  header["provenance"] = table.provenance.empty() ? nlohmann::json::object() : nlohmann::json::parse(table.provenance);
  const std::string text = header.dump();
  std::string out(kMagic, sizeof kMagic);
  const std::uint64_t length = text.size();
  out.append(reinterpret_cast<const char*>(&length), sizeof length);
  out += text;
  append_bytes(out, table.ln_y);
  append_bytes(out, table.total);
  append_bytes(out, table.fine_total);
  if (!table.relative_error.empty()) {  // first, so that a table never stands beside older errors
    std::string errors(kErrorsMagic, sizeof kErrorsMagic);
    const std::uint64_t count = table.relative_error.size();
    errors.append(reinterpret_cast<const char*>(&count), sizeof count);
    append_bytes(errors, table.relative_error);
    write_atomically(path + ".errors", errors, "exact table's errors");
  } else if (std::error_code ec; std::filesystem::is_regular_file(path + ".errors", ec)) {
    std::filesystem::remove(path + ".errors", ec);  // another table's errors must not stand beside this one
  }
  write_atomically(path, out, "exact table");
}

namespace {

// A version-3 table's relative errors from PATH.errors: exactly `count` of them.
void read_errors(const std::string& path, std::size_t count, ExactTable::NodeArray<std::uint16_t>& values) {
  const std::string file = path + ".errors";
  auto in = open_data_file(file, "the exact-model table's errors");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0);
  char start[16];
  if (size < 16 || !in.read(start, sizeof start) || std::memcmp(start, kErrorsMagic, sizeof kErrorsMagic) != 0)
    throw InvalidInput(kField, file, "the table's errors (magic BSSRDFE1)");
  std::uint64_t stored = 0;
  std::memcpy(&stored, start + 8, sizeof stored);
  if (stored != count)
    throw InvalidInput(kField, file, std::to_string(count) + " errors, one per value of the table beside it");
  auto remaining = static_cast<std::uintmax_t>(size) - 16;
  read_array(in, remaining, count, values, file);
  if (remaining != 0) throw InvalidInput(kField, file, "no data after the errors");
}

}  // namespace

ExactTable read_exact_table(const std::string& path, TableErrors errors) {
  auto in = open_data_file(path, "the exact-model table");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0);
  if (size < 0 || !in) throw InvalidInput(kField, path, "a regular file");
  char start[16];
  if (size < 16 || !in.read(start, sizeof start) || std::memcmp(start, kMagic, sizeof kMagic) != 0)
    throw InvalidInput(kField, path, "a bssrdf exact table (magic BSSRDFX1)");
  std::uint64_t length = 0;
  std::memcpy(&length, start + 8, sizeof length);
  auto remaining = static_cast<std::uintmax_t>(size) - 16;
  if (length > remaining) throw InvalidInput(kField, path, "a complete table file (truncated header)");
  remaining -= length;
  std::string text(static_cast<std::size_t>(length), '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(length)))
    throw InvalidInput(kField, path, "a complete table file (truncated header)");
  const nlohmann::json header = parse_json_document(text, path);
  ExactTable table;
  int version = 0;
  try {
    version = header.at("version").get<int>();
    if (header.at("format") != "bssrdf-exact-table" || version < 1 || version > 3)
      throw InvalidInput(kField, path, "format bssrdf-exact-table version 1, 2 or 3");
    if (version == 2 || (version == 3 && header.contains("total_eta")))
      table.total_eta = header.at("total_eta").get<std::vector<double>>();
    table.albedo_prime = header.at("albedo_prime").get<std::vector<double>>();
    table.g = header.at("g").get<std::vector<double>>();
    table.eta = header.at("eta").get<std::vector<double>>();
    table.ln_r0 = header.at("ln_r0").get<double>();
    table.d_ln_r = header.at("d_ln_r").get<double>();
    table.radii = header.at("radii").get<std::size_t>();
    table.provenance = header.at("provenance").dump();
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(kField, path, std::string("a valid header (") + e.what() + ")");
  }
  if (table.radii > (1u << 20) || table.albedo_prime.size() * table.g.size() * table.eta.size() > (1u << 24) ||
      table.total_eta.size() > (1u << 16))
    throw InvalidInput(kField, path, "a table of plausible size");
  const std::size_t n = table.nodes() * table.radii;
  read_array(in, remaining, n, table.ln_y, path);
  if (version < 3) {  // errors inline: read, or stepped over (still checked to be there)
    if (errors == TableErrors::read)
      read_array(in, remaining, n, table.relative_error, path);
    else
      skip_array<std::uint16_t>(in, remaining, n, path);
  }
  read_array(in, remaining, table.nodes(), table.total, path);
  read_array(in, remaining, table.total_eta.size() * table.g.size() * table.albedo_prime.size(), table.fine_total,
             path);
  if (remaining != 0) throw InvalidInput(kField, path, "no data after the totals");
  if (version == 3 && errors == TableErrors::read) read_errors(path, n, table.relative_error);
  table.prepare();
  return table;
}

namespace {

std::string found_path;

std::vector<std::filesystem::path> candidate_paths() {
  std::vector<std::filesystem::path> paths;
  if (const char* env = std::getenv("BSSRDF_EXACT_TABLE"); env && *env) paths.emplace_back(env);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back(exe.parent_path().parent_path() / "share" / "bssrdf" / "exact" / "exact_profile.bin");
  paths.emplace_back(std::string(BSSRDF_DATA_INSTALL_DIR) + "/exact/exact_profile.bin");
  paths.emplace_back(std::string(BSSRDF_SOURCE_DATA_DIR) + "/exact/exact_profile.bin");
  return paths;
}

}  // namespace

const ExactTable& bundled_exact_table() {
  static std::once_flag once;
  static ExactTable table;
  std::call_once(once, [] {
    std::string searched;
    for (const auto& path : candidate_paths()) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(path, ec)) {
        table = read_exact_table(path.string());
        found_path = path.string();
        return;
      }
      searched += (searched.empty() ? "" : ", ") + path.string();
    }
    throw InvalidInput("exact table", "not found", "a file at one of: " + searched + " (or set $BSSRDF_EXACT_TABLE)");
  });
  return table;
}

std::string bundled_exact_table_path() { return found_path; }

}  // namespace bssrdf
