// libFuzzer driver for the project's file formats (fuzz_targets.hpp). The format comes from
// $BSSRDF_FUZZ_FORMAT; tools/fuzz.sh runs each format on its corpus:
//
//   BSSRDF_FUZZ_FORMAT=mci build-sanitize/tests/fuzz/fuzz_parser -max_total_time=60 tests/fuzz/corpus/mci
//
// Parsing must return or throw bssrdf::InvalidInput; another exception aborts (a finding).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bssrdf/error.hpp"
#include "fuzz_targets.hpp"

namespace {
const bssrdf::fuzz::Target* target = nullptr;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* name = std::getenv("BSSRDF_FUZZ_FORMAT");
  target = name ? bssrdf::fuzz::find_target(name) : nullptr;
  if (!target) {
    std::fprintf(stderr, "fuzz_parser: set BSSRDF_FUZZ_FORMAT to one of:");
    for (const auto& t : bssrdf::fuzz::targets()) std::fprintf(stderr, " %s", t.name);
    std::fprintf(stderr, "\n");
    std::exit(2);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    target->parse(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const bssrdf::InvalidInput&) {
  }
  return 0;
}
