// Validity is data: a model reports where its assumptions fail for the given parameters instead of
// silently returning nonsense; callers decide whether to warn, refuse or switch model.
#pragma once

#include <string>
#include <vector>

namespace bssrdf {

enum class Severity {
  note,     // a known, bounded limitation (e.g. near-field error below one transport mfp)
  warning,  // the result is usable but measurably inaccurate here (figures in the message)
  invalid,  // the model's assumptions do not hold: do not use the result
};

struct ValidityNote {
  Severity severity;
  std::string code;     // stable identifier for scripts, e.g. "low_albedo"
  std::string message;  // one line for people, with the numbers that triggered it
};

using ValidityReport = std::vector<ValidityNote>;

std::string_view to_string(Severity severity);

// The most severe entry, or Severity::note for an empty report.
Severity worst(const ValidityReport& report);

// "warning [code] message": how every command prints an entry (profile, materials show, stderr).
std::string describe(const ValidityNote& note);

}  // namespace bssrdf
