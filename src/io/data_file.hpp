// Reading the project's input files (materials, layers, .mci, CSV, fit results) safely: a directory,
// a special or huge file, JSON nested absurdly deep or holding a number no double can represent is
// a FileError naming the file (and line), never a crash, a hang or an internal error.
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bssrdf {

// Deeper nesting is refused before parsing: no format of ours nests beyond 6 levels, and nesting
// depth costs the parsers time and stack.
inline constexpr int kMaxJsonDepth = 64;
// Input files larger than this (bytes) are refused: the largest real input is a few MB.
inline constexpr std::uintmax_t kMaxInputFileBytes = 256u << 20;

// The whole text of a regular file; `what` says what the file should be ("the materials file").
std::string read_data_file(const std::filesystem::path& path, const std::string& what);
// The file opened for reading, after the same checks (it exists, is no directory, is not too large),
// for a binary format read straight into its arrays.
std::ifstream open_data_file(const std::filesystem::path& path, const std::string& what);

// Parses JSON text; FileError(file, line, ...) for malformed JSON, nesting deeper than
// kMaxJsonDepth and numbers that overflow a double (1e400).
nlohmann::json parse_json_document(const std::string& text, const std::string& file);

// A JSON value for a message: its compact text, shortened to `max_chars` (a value can be megabytes).
std::string json_excerpt(const nlohmann::json& value, std::size_t max_chars = 40);

// The non-empty lines of a whitespace-separated text format ('.mci', '.rxt') with '#' comments
// removed: each line's number (from 1) and its words.
struct TextRecord {
  int line;
  std::vector<std::string> tokens;
};
std::vector<TextRecord> comment_stripped_records(const std::string& text);

}  // namespace bssrdf
