// Every file format the project reads, by name, as a function of the file's bytes. The libFuzzer
// driver (fuzz_parser.cpp) and the deterministic mutation test (tests/test_fuzz_mutations.cpp) both
// run these; seed inputs live in tests/fuzz/corpus/<name>/, crashes found become
// tests/fuzz/regressions/<name>/ inputs. Adding a format is one line in kFuzzTargets (and a corpus).
//
// A parser passes when it returns or throws bssrdf::InvalidInput (which FileError is): anything
// else (another exception, a crash, a sanitizer report, a hang) is a finding.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bssrdf/fit/fit_import.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/io/mci.hpp"
#include "bssrdf/io/profile_csv.hpp"
#include "bssrdf/io/rxt.hpp"
#include "bssrdf/io/spectrum_file.hpp"
#include "bssrdf/materials.hpp"

namespace bssrdf::fuzz {

struct Target {
  const char* name;  // the corpus folder's name
  std::function<void(const std::string& bytes)> parse;
};

inline const std::vector<Target>& targets() {
  static const std::vector<Target> kFuzzTargets = {
      {"materials", [](const std::string& b) { MaterialDatabase().add_text(b, "fuzz.json"); }},
      {"layers", [](const std::string& b) { parse_layers_json(b, "fuzz.json"); }},
      {"mci", [](const std::string& b) { parse_mci(b, "fuzz.mci"); }},
      {"profile_csv", [](const std::string& b) { parse_profile_csv(b, "fuzz.csv"); }},
      {"rxt", [](const std::string& b) { parse_rxt(b, "fuzz.rxt"); }},
      {"spectrum", [](const std::string& b) { parse_spectrum(b, "fuzz.tsv", ""); }},
      {"fit_import",
       [](const std::string& b) {
         MaterialDatabase().add_text(materials_file_from_fit(b, "fit.json", "X", std::nullopt, "fit"), "m.json");
       }},
  };
  return kFuzzTargets;
}

inline const Target* find_target(const std::string& name) {
  for (const auto& t : targets())
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace bssrdf::fuzz
