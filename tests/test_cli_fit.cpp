// `bssrdf fit` end to end: a profile written by `bssrdf profile -f csv` fits back to its
// coefficients; JSON reports carry {value, stderr} per channel; bad data exit 2 with one line.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using namespace bssrdf;
using test_cli::count_lines;
using test_cli::run;
using json = nlohmann::json;

namespace {
std::string temp(const std::string& name) { return test_cli::temp(name).string(); }
void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }
}  // namespace

TEST(CliFit, ProfileRoundTripThroughFiles) {
  const auto csv = temp("skin.csv");
  ASSERT_EQ(run("profile --material Skin1 --model dipole --samples 48 -f csv -o " + csv + " -q").status, 0);
  const auto r = run("fit profile " + csv + " --model dipole -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["source"], "fit");
  EXPECT_EQ(doc["kind"], "profile");
  EXPECT_EQ(doc["channels"].size(), 3u);
  EXPECT_NEAR(doc["channels"][1]["sigma_a"]["value"].get<double>(), 0.17, 1e-6);
  EXPECT_NEAR(doc["channels"][2]["sigma_s_prime"]["value"].get<double>(), 1.01, 1e-6);
  EXPECT_TRUE(doc["channels"][0]["sigma_a"].contains("stderr"));
  EXPECT_EQ(doc["converged"], true);
  // The table report for people.
  const auto t = run("fit profile " + csv + " --model dipole");
  EXPECT_NE(t.out.find("sigma_s_prime"), std::string::npos);
  EXPECT_NE(t.out.find("CONVERGENCE"), std::string::npos);
}

TEST(CliFit, AlbedoSlabGaussiansBurley) {
  auto r = run("fit albedo --albedo 0.8,0.5,0.3 --distance 1,0.5,0.2 --convention transport-mfp -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto doc = json::parse(r.out);
  // transport mfp 1 mm: sigma_t' = 1, so sigma_a + sigma_s' = 1 exactly.
  EXPECT_NEAR(
      doc["channels"][0]["sigma_a"]["value"].get<double>() + doc["channels"][0]["sigma_s_prime"]["value"].get<double>(),
      1.0, 1e-12);
  r = run("fit slab --reflectance 0.4 --transmittance 0.3 --thickness 2 --eta 1.4 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  doc = json::parse(r.out);
  EXPECT_GT(doc["channels"][0]["sigma_a"]["stderr"].get<double>(), 0.0);
  r = run("fit gaussians --material Skin1 -n 4 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  doc = json::parse(r.out);
  EXPECT_TRUE(doc["shared"].contains("variance_4"));
  r = run("fit burley --material Marble --model pbd -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  doc = json::parse(r.out);
  EXPECT_GT(doc["channels"][0]["burley_d"]["value"].get<double>(), 0.0);
}

TEST(CliFit, BadDataGivesOneLineAndStatusTwo) {
  const auto bad = temp("bad.csv");
  const auto out = temp("out.json");
  const std::pair<std::string, std::string> cases[] = {
      {"radius_mm,R\n0.1,1\n0.2,-3\n0.3,1\n0.4,1\n", "bad.csv:3: R = -3: accepted range is 0 to 1e+30"},
      {"radius_mm,R\n0.1,1\n0.2,nan\n0.3,1\n0.4,1\n", "bad.csv:3: R = 'nan'"},
      {"radius_mm,R\n0.3,1\n0.2,1\n0.3,1\n0.4,1\n", "bad.csv:3: radius_mm = 0.2"},
      {"radius_mm,R\n0.1,1\n", "1 data rows: accepted range is at least 4"},
      {"", "empty file"},
  };
  for (const auto& [text, expected] : cases) {
    write(bad, text);
    std::filesystem::remove(out);
    const auto r = run("fit profile " + bad + " -o " + out);
    EXPECT_EQ(r.status, 2) << text;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"fit albedo --albedo 1.5 --distance 1", "--albedo[c0] = 1.5: accepted range is [0, 1]"},
           {"fit albedo --albedo 0.5,0.4 --distance 1,2,3", "--distance: 3 values for 2 channels"},
           {"fit albedo --albedo 0.5 --distance -1", "distance = -1"},
           {"fit slab --reflectance 0.6 --transmittance 0.5 --thickness 2", "more light out than in"},
           {"fit slab --reflectance 0.3 --transmittance 0.5 --thickness 0", "thickness = 0"},
           {"fit profile /nonexistent.csv", "cannot open"},
           {"fit gaussians --material Skin1 -n 0", "--count = '0': accepted range is a whole number from 1 to 32"},
           {"fit profile x.csv --loss weird", "--loss"},
       }) {
    const auto r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
  }
}
