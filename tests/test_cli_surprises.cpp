// The surprises a new user met (issue 24), each refused or explained on one line with exit status 2,
// or accepted as meant: -o with --all, unknown extensions, channel counts that disagree, errors that
// name options never given, case in enum-like values, one output-format option, typos in options,
// and a unit typed as a separate word.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using bssrdf::test_cli::count_lines;
using bssrdf::test_cli::Run;
using bssrdf::test_cli::run;
using bssrdf::test_cli::temp;
using json = nlohmann::json;

namespace {

void expect_refused(const Run& r, const std::string& says) {
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
}

}  // namespace

TEST(CliSurprises, OutputWithAllIsADirectory) {
  const auto dir = temp("all-out");
  std::filesystem::create_directories(dir);
  const auto before = std::filesystem::current_path();
  expect_refused(run("lut --all --kind radial -o " + temp("x.exr").string()), "a directory with --all");
  EXPECT_FALSE(std::filesystem::exists(temp("x.exr")));
  expect_refused(run("lut --all -o " + dir.string() + " --output-dir " + dir.string()), "give one of them");
  // A small database: one imported material; -o DIR puts its table there.
  const auto db = temp("one.json");
  auto r = run("materials export One --sigma-a 0.1 --sigma-s 1 --to json -o " + db.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("lut --all --db " + db.string() + " --kind radial -f json -q -o " + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "one-radial.json"));
  // A --db holding a copy of a bundled file: its names clash with the bundled ones, one error, no table
  // (it once skipped every material, one stderr line each, and exited 0).
  const auto clash = temp("clash-db"), clash_out = temp("clash-out");
  std::filesystem::create_directories(clash);
  std::filesystem::create_directories(clash_out);
  std::filesystem::copy_file(std::string(BSSRDF_TEST_DATA) + "/../../materials/jensen2001.json",
                             clash / "jensen2001.json", std::filesystem::copy_options::overwrite_existing);
  expect_refused(run("lut --all --db " + clash.string() + " --kind radial -q -o " + clash_out.string()),
                 "'Apple' is already defined");
  EXPECT_TRUE(std::filesystem::is_empty(clash_out));
}

TEST(CliSurprises, UnknownExtensionsAreRefused) {
  const auto xml = temp("x.xml");
  expect_refused(run("profile --material Skin1 -o " + xml.string()), "a file ending in .json, .csv or .txt");
  EXPECT_FALSE(std::filesystem::exists(xml));
  // With -f the extension is the user's choice.
  const auto r = run("profile --material Skin1 -f json -q -o " + xml.string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(json::accept(bssrdf::test_cli::slurp(xml)));
  expect_refused(run("lut --material Skin1 -o " + temp("x.xml").string() + "x"), ".exr, .json, .csv");
}

TEST(CliSurprises, ChannelCountsThatDisagreeNameBothCounts) {
  // A decimal comma: two absorption values, one scattering value.
  expect_refused(run("profile --sigma-a 0,1 --sigma-s 10"), "--sigma-s: 1 value given, but --sigma-a has 2 channels");
  expect_refused(run("lut --sigma-a 0.1,0.2,0.3 --sigma-s-prime 1,2 -o " + temp("c.exr").string()),
                 "--sigma-s-prime: 2 values given, but --sigma-a has 3 channels");
}

TEST(CliSurprises, ErrorsNameOnlyOptionsTheUserGave) {
  auto r = run("profile --sigma-a 1 --sigma-s 0");
  expect_refused(r, "sigma_s = 0 in every channel");
  EXPECT_EQ(r.err.find("r_max"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("r_min"), std::string::npos) << r.err;
  r = run("profile --sigma-a 0.1 --sigma-s 1 --r-max 1e-9");
  expect_refused(r, "--r-max = 1e-09");
  EXPECT_EQ(r.err.find("--r-min"), std::string::npos) << r.err;
}

TEST(CliSurprises, EnumValuesIgnoreCase) {
  const auto lower = run("profile --material Skin1 --model exact --unit mm -f json");
  const auto upper = run("profile --material Skin1 --model Exact --unit MM -f JSON");
  ASSERT_EQ(upper.status, 0) << upper.err;
  EXPECT_EQ(upper.out, lower.out);
  EXPECT_EQ(run("lut --material Skin1 --kind RADIAL -F json -o " + temp("k.json").string()).status, 2);  // -F: no
  const auto kind = run("lut --material Skin1 --kind RADIAL -f JSON -q -o " + temp("k.json").string());
  EXPECT_EQ(kind.status, 0) << kind.err;
  const auto to = run("materials export Skin1 --to JSON");
  EXPECT_EQ(to.status, 0) << to.err;
}

TEST(CliSurprises, OneOutputFormatOption) {
  const auto f = run("models -f json");
  ASSERT_EQ(f.status, 0) << f.err;
  EXPECT_TRUE(json::parse(f.out).is_array());
  EXPECT_EQ(run("models --json").out, f.out);  // kept for scripts, hidden from --help
  // Every command that prints a result takes -f.
  for (const char* command : {"profile --material Skin1", "models", "materials list", "materials show Skin1",
                              "fit albedo --albedo 0.5 --distance 1", "slab --material Skin1 --thickness 1",
                              "transmission --material Skin1 --thickness 1", "advise --material Skin1 --pixel 1mm"}) {
    const auto r = run(std::string(command) + " -f json");
    EXPECT_EQ(r.status, 0) << command << ": " << r.err;
    EXPECT_TRUE(json::accept(r.out)) << command;
  }
}

TEST(CliSurprises, UnknownOptionsGetTheNearestOne) {
  expect_refused(run("profile --materail Skin1"),
                 "unknown option '--materail' for 'profile'; did you mean '--material'?");
  expect_refused(run("lut --materail Skin1 -o x.exr"), "did you mean '--material'?");
  expect_refused(run("materials export Skin1 --too json"), "did you mean '--to'?");
  expect_refused(run("profile --material Skin1 --zzzzzzzzz 1"), "see 'bssrdf profile --help'");
}

TEST(CliSurprises, AUnitAsASeparateWordGetsAHint) {
  expect_refused(run("advise --material Skin1 --pixel 1 mm"), "write the unit joined to the number, '--pixel 1mm'");
  expect_refused(run("lut --material Skin1 --kind radial --pixel 1 mm -o " + temp("p.exr").string()),
                 "give '--unit mm'");
}
