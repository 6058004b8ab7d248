// Deterministic mutation fuzzing of every file format (tests/fuzz/fuzz_targets.hpp), for builds
// without libFuzzer: each seed in tests/fuzz/corpus/<format>/ is mutated a fixed number of times
// (byte flips, deletions, duplications, truncations, hostile tokens such as 1e400, -1, deep
// brackets, CR and NUL) and every regression input in tests/fuzz/regressions/<format>/ is replayed.
// Each must parse or throw InvalidInput; any other exception fails here, and a crash, hang or
// sanitizer report fails the test binary. tools/fuzz.sh runs the coverage-guided libFuzzer version.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "bssrdf/error.hpp"
#include "fuzz/fuzz_targets.hpp"

namespace {

const std::filesystem::path kFuzzDir = std::filesystem::path(BSSRDF_TEST_DATA).parent_path() / "fuzz";
constexpr int kMutantsPerSeed = 2500;

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::filesystem::path> files_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.is_regular_file()) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// One to three random edits of `text`.
std::string mutate(std::string text, std::mt19937_64& rng) {
  static const std::vector<std::string> tokens = {"1e400",
                                                  "-1e400",
                                                  "1e-400",
                                                  "4.9e-324",
                                                  "1e308",
                                                  "-1",
                                                  "0",
                                                  "-0",
                                                  "3e9",
                                                  "2e9",
                                                  "99999999999999999999999",
                                                  "nan",
                                                  "inf",
                                                  "null",
                                                  "true",
                                                  "\"\"",
                                                  "\"x\"",
                                                  "[]",
                                                  "{}",
                                                  "[[[[[[[[[[[[[[[[",
                                                  "]]]]",
                                                  ",",
                                                  ":",
                                                  "\"",
                                                  "\\",
                                                  "\r",
                                                  "\n",
                                                  std::string(1, '\0'),
                                                  "\xff\xfe",
                                                  "#",
                                                  " ",
                                                  "1.0.0",
                                                  "0x10",
                                                  "1e",
                                                  "-",
                                                  "+5",
                                                  std::string(300, '9')};
  const int edits = 1 + static_cast<int>(rng() % 3);
  for (int e = 0; e < edits; ++e) {
    const std::size_t n = text.size();
    const std::size_t at = n ? rng() % (n + 1) : 0;
    switch (rng() % 6) {
      case 0:
        if (n) text[at % n] = static_cast<char>(rng() % 256);
        break;
      case 1:
        text.erase(at, 1 + rng() % 16);
        break;
      case 2:
        text.insert(at, tokens[rng() % tokens.size()]);
        break;
      case 3:  // replace the number or word at `at` with a hostile token
        if (n) {
          std::size_t b = at % n, end = b;
          while (b > 0 && std::isalnum(static_cast<unsigned char>(text[b - 1]))) --b;
          while (end < n &&
                 (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '.' || text[end] == '-'))
            ++end;
          text.replace(b, end - b, tokens[rng() % tokens.size()]);
        }
        break;
      case 4:
        if (n) text.insert(at, text.substr(rng() % n, 1 + rng() % 64));
        break;
      case 5:
        text.resize(at);
        break;
    }
  }
  return text;
}

// Parses `bytes`; a failure message naming the input unless it parsed or threw InvalidInput.
std::string check(const bssrdf::fuzz::Target& target, const std::string& bytes) {
  try {
    target.parse(bytes);
  } catch (const bssrdf::InvalidInput&) {
  } catch (const std::exception& e) {
    return std::string("uncaught ") + typeid(e).name() + ": " + e.what();
  }
  return "";
}

class FuzzMutations : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzMutations, EveryMutantParsesOrIsRefused) {
  const auto* target = bssrdf::fuzz::find_target(GetParam());
  ASSERT_NE(target, nullptr);
  const auto seeds = files_in(kFuzzDir / "corpus" / GetParam());
  ASSERT_FALSE(seeds.empty()) << "no seed corpus for " << GetParam();
  std::mt19937_64 rng(20261201);
  int refused = 0, total = 0;
  for (const auto& seed : seeds) {
    const std::string original = slurp(seed);
    EXPECT_EQ(check(*target, original), "") << seed;
    for (int k = 0; k < kMutantsPerSeed; ++k) {
      const std::string mutant = mutate(original, rng);
      const std::string failure = check(*target, mutant);
      if (!failure.empty()) {
        // Keep the input, so it can become a regression file.
        const auto saved =
            std::filesystem::temp_directory_path() / ("bssrdf-fuzz-" + GetParam() + "-" + std::to_string(k));
        std::ofstream(saved, std::ios::binary) << mutant;
        ADD_FAILURE() << seed.filename() << " mutant " << k << ": " << failure << " (input saved to " << saved << ")";
      }
      try {
        target->parse(mutant);
      } catch (const bssrdf::InvalidInput&) {
        ++refused;
      } catch (...) {
      }
      ++total;
    }
  }
  // The mutations must reach the validation, not only the syntax: some mutants parse, many do not.
  EXPECT_GT(refused, total / 10) << GetParam();
  EXPECT_LT(refused, total) << GetParam();
  std::printf("%s: %d mutants, %d refused with InvalidInput, the rest parsed\n", GetParam().c_str(), total, refused);
}

TEST_P(FuzzMutations, RegressionInputsAreRefusedCleanly) {
  const auto* target = bssrdf::fuzz::find_target(GetParam());
  ASSERT_NE(target, nullptr);
  for (const auto& input : files_in(kFuzzDir / "regressions" / GetParam()))
    EXPECT_EQ(check(*target, slurp(input)), "") << input;
}

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  for (const auto& t : bssrdf::fuzz::targets()) names.push_back(t.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Formats, FuzzMutations, ::testing::ValuesIn(target_names()),
                         [](const auto& info) { return info.param; });

}  // namespace
