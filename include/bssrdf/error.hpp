// Typed errors for bad input. Every message names the field, the value and what is accepted, so
// the command line can print it on one line and exit with status 2.
//
//   throw InvalidInput("sigma_a[G]", "-1", ">= 0 and finite");
//   -> "sigma_a[G] = -1: accepted range is >= 0 and finite"
#pragma once

#include <stdexcept>
#include <string>

namespace bssrdf {

// A value outside its accepted range, or a malformed value, given by the user or a data file.
class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(std::string field, std::string value, std::string accepted);
  // A free-form message for cases that are not one field's range (e.g. mismatched channel counts).
  explicit InvalidInput(const std::string& message);

  const std::string& field() const { return field_; }
  const std::string& value() const { return value_; }
  const std::string& accepted() const { return accepted_; }

 private:
  std::string field_, value_, accepted_;
};

// A data file that cannot be read or parsed; the message carries the file name and line.
class FileError : public InvalidInput {
 public:
  FileError(const std::string& file, int line, const std::string& what);
  // line <= 0: the error concerns the whole file (missing, unreadable, empty).
  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  std::string file_;
  int line_;
};

// Formats a double the way messages and tables show it: shortest round-trip representation.
std::string format_number(double value);
// Four significant digits, for the summary lines people read (files keep full precision).
std::string short_number(double value);
// A message for a terminal or an exception: control bytes from input (a CR in a CSV field, an escape
// sequence, a newline in a name) are shown as \xHH instead of acting, so an error stays one visible line.
std::string printable(const std::string& message);

}  // namespace bssrdf
