// `bssrdf lut` end to end: files in every format, byte-for-byte reproducible; bad input gives exit
// status 2, one line on stderr and no file.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using namespace bssrdf;
using test_cli::count_lines;
using test_cli::run;
using test_cli::slurp;

namespace {

using test_cli::temp;

}  // namespace

TEST(CliLut, RadialExrJsonCsvAreReproducible) {
  for (const char* ext : {"exr", "json", "csv"}) {
    const auto a = temp(std::string("a.") + ext), b = temp(std::string("b.") + ext);
    auto r = run("lut --material Skin1 --kind radial -o " + a.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("radial table"), std::string::npos);
    r = run("lut --material Skin1 --kind radial -q -o " + b.string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_EQ(slurp(a), slurp(b)) << ext;
    EXPECT_GT(slurp(a).size(), 100u);
  }
  const auto doc = nlohmann::json::parse(slurp(temp("a.json")));
  EXPECT_EQ(doc["format"], "bssrdf-lut");
  EXPECT_EQ(doc["attributes"]["bssrdf:material"], "Skin1");
}

TEST(CliLut, BadInputIsOneLineExitTwoAndNoFile) {
  const auto out = temp("bad.exr");
  for (const std::string args :
       {"--material Skin1 --kind nonsense", "--material Skin1 --tolerance 0", "--material Skin1 --tolerance -1",
        "--material Skin1 --tolerance abc", "--material Skin1 --energy 1", "--material Skin1 --model nope",
        "--material Nobody", "--sigma-a -1 --sigma-s 1", "--material Skin1 --interpolation cubic",
        "--material Skin1 --format png"}) {
    std::filesystem::remove(out);
    const auto r = run("lut " + args + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const auto r = run("lut --material Skin1 -o /nonexistent-dir/x.exr");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1);
  const auto no_ext = run("lut --material Skin1 -o " + temp("table.txt").string());
  EXPECT_EQ(no_ext.status, 2);
  EXPECT_FALSE(std::filesystem::exists(temp("table.txt")));
}
