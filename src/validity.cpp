#include "bssrdf/validity.hpp"

namespace bssrdf {

std::string_view to_string(Severity severity) {
  switch (severity) {
    case Severity::note:
      return "note";
    case Severity::warning:
      return "warning";
    case Severity::invalid:
      return "invalid";
  }
  return "note";
}

std::string describe(const ValidityNote& note) {
  return std::string(to_string(note.severity)) + " [" + note.code + "] " + note.message;
}

Severity worst(const ValidityReport& report) {
  Severity result = Severity::note;
  for (const auto& entry : report)
    if (entry.severity > result) result = entry.severity;
  return result;
}

}  // namespace bssrdf
