#include "data_file.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "bssrdf/error.hpp"

namespace bssrdf {
namespace {

int line_at(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

// nlohmann's messages start "[json.exception.parse_error.101] parse error at line L, column C: ...".
std::string without_prefix(const std::string& what) {
  const auto colon = what.find(": ");
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

// Offset of the first bracket nested deeper than kMaxJsonDepth (outside strings), or npos.
std::size_t too_deep_at(const std::string& text) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

}  // namespace

std::ifstream open_data_file(const std::filesystem::path& path, const std::string& what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw FileError(path.string(), 0, "cannot open " + what + ": no such file");
  if (std::filesystem::is_directory(status))
    throw FileError(path.string(), 0, "cannot read " + what + ": it is a directory");
  if (std::filesystem::is_regular_file(status) && std::filesystem::file_size(path, ec) > kMaxInputFileBytes)
    throw FileError(path.string(), 0, what + " is larger than " + std::to_string(kMaxInputFileBytes >> 20) + " MB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), 0, "cannot open " + what);
  return in;
}

std::string read_data_file(const std::filesystem::path& path, const std::string& what) {
  auto in = open_data_file(path, what);
  std::error_code ec;
  const std::uintmax_t size =
      std::filesystem::is_regular_file(path, ec) ? std::filesystem::file_size(path, ec) : std::uintmax_t{0};
  std::string text;
  // A regular file is read at once into its final place (read in pieces, the string's regrowth copied
  // a 2 MB file twice over); then whatever it grew by since, as a FIFO or device is read.
  if (!ec && size > 0 && size <= kMaxInputFileBytes) {
    text.resize(static_cast<std::size_t>(size));
    in.read(text.data(), static_cast<std::streamsize>(size));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (in.bad()) throw FileError(path.string(), 0, "cannot read " + what);
    in.clear();
  }
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxInputFileBytes)  // a FIFO or device has no size to check up front
      throw FileError(path.string(), 0, what + " is larger than " + std::to_string(kMaxInputFileBytes >> 20) + " MB");
  }
  if (in.bad()) throw FileError(path.string(), 0, "cannot read " + what);
  return text;
}

nlohmann::json parse_json_document(const std::string& text, const std::string& file) {
  if (const auto at = too_deep_at(text); at != std::string::npos)
    throw FileError(file, line_at(text, at), "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw FileError(file, line_at(text, e.byte), "malformed JSON: " + without_prefix(e.what()));
  } catch (const nlohmann::json::out_of_range& e) {
    // "number overflow parsing '1e400'": find the number to name its line.
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    const std::string token = open != std::string::npos && close > open ? what.substr(open + 1, close - open - 1) : "";
    const auto at = token.empty() ? std::string::npos : text.find(token);
    throw FileError(file, at == std::string::npos ? 0 : line_at(text, at),
                    "number " + (token.size() > 40 ? token.substr(0, 40) + "..." : token) +
                        ": accepted range is a finite number within +-1.8e308");
  }
}

std::string json_excerpt(const nlohmann::json& value, std::size_t max_chars) {
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > max_chars) text = text.substr(0, max_chars) + "...";
  return text;
}

std::vector<TextRecord> comment_stripped_records(const std::string& text) {
  std::vector<TextRecord> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    TextRecord r{number, {}};
    for (std::string word; words >> word;) r.tokens.push_back(word);
    if (!r.tokens.empty()) out.push_back(std::move(r));
  }
  return out;
}

}  // namespace bssrdf
