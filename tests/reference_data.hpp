// Reads the tab-separated reference tables in tests/data (copied from shared/reference): '#'
// comment lines, one header line, then rows of numbers.
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace bssrdf::test_data {

using Row = std::map<std::string, double>;

inline std::vector<Row> read_tsv(const std::string& name) {
  const std::string path = std::string(BSSRDF_TEST_DATA) + "/" + name;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::string> header;
  std::vector<Row> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string field;
    if (header.empty()) {
      while (std::getline(fields, field, '\t')) header.push_back(field);
      continue;
    }
    Row row;
    for (std::size_t i = 0; std::getline(fields, field, '\t') && i < header.size(); ++i) {
      try {
        row[header[i]] = std::stod(field);
      } catch (const std::exception&) {
        // non-numeric columns (names, sources) are skipped
      }
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace bssrdf::test_data
