#include "bssrdf/error.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "bssrdf/check.hpp"

namespace bssrdf {

InvalidInput::InvalidInput(std::string field, std::string value, std::string accepted)
    : std::invalid_argument(field + " = " + value + ": accepted range is " + accepted),
      field_(std::move(field)),
      value_(std::move(value)),
      accepted_(std::move(accepted)) {}

InvalidInput::InvalidInput(const std::string& message) : std::invalid_argument(message) {}

FileError::FileError(const std::string& file, int line, const std::string& what)
    : InvalidInput(line > 0 ? file + ":" + std::to_string(line) + ": " + what : file + ": " + what),
      file_(file),
      line_(line) {}

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string short_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

std::string printable(const std::string& message) {
  std::string out;
  for (const unsigned char c : message) {
    if (c >= 0x20 && c != 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  return out;
}

void check_failed(const char* condition, const char* file, int line) {
  throw InternalError(std::string("internal check failed: ") + condition + " (" + file + ":" + std::to_string(line) +
                      "); please report this as a bug");
}

}  // namespace bssrdf
