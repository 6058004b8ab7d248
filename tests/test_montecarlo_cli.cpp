// bssrdf reference: output formats, determinism across thread counts, and bad input (exit 2, one
// line, no partial output file).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using namespace bssrdf::test_cli;

namespace {

const std::string kMedium = "reference --sigma-a 0.1 --sigma-s 5 --g 0.8 --eta 1.4 --photons 20000 --seed 3 ";

}  // namespace

TEST(MonteCarloCli, JsonHasTheDocumentedFields) {
  const auto r = run(kMedium + "--thickness 2 --format json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no progress bar when stderr is not a terminal
  const auto doc = nlohmann::json::parse(r.out);
  for (const char* key : {"photons", "seed", "threads", "seconds", "photons_per_second", "radius", "unit"})
    EXPECT_TRUE(doc.contains(key)) << key;
  const auto& c = doc["channels"][0];
  for (const char* key : {"diffuse_reflectance", "total_transmittance", "single_scattering_reflectance"}) {
    EXPECT_TRUE(c[key].contains("value")) << key;
    EXPECT_TRUE(c[key].contains("stderr")) << key;
  }
  for (const char* key : {"specular_reflectance", "normalization", "radius", "reflectance", "reflectance_stderr",
                          "transmittance", "transmittance_stderr", "per_entered_flux"})
    EXPECT_TRUE(c.contains(key)) << key;
  EXPECT_EQ(c["normalization"], "per_incident_flux");
  EXPECT_EQ(c["per_entered_flux"]["normalization"], "per_entered_flux");
  EXPECT_EQ(c["reflectance"].size(), 100u);
  EXPECT_EQ(doc["photons"], 20000);
}

TEST(MonteCarloCli, SameSeedSameOutputForOneAndTwoThreads) {
  const auto one = run(kMedium + "--threads 1 --bins 20 --bin-spacing log --format json");
  const auto two = run(kMedium + "--threads 2 --bins 20 --bin-spacing log --format json");
  ASSERT_EQ(one.status, 0) << one.err;
  ASSERT_EQ(two.status, 0) << two.err;
  auto a = nlohmann::json::parse(one.out), b = nlohmann::json::parse(two.out);
  EXPECT_EQ(a["threads"], 1);
  EXPECT_EQ(b["threads"], 2);
  for (auto* d : {&a, &b})
    for (const char* key : {"threads", "seconds", "photons_per_second"}) d->erase(key);
  EXPECT_EQ(a.dump(), b.dump());
  EXPECT_EQ(run(kMedium + "--threads 1 --bins 20 --format csv").out,
            run(kMedium + "--threads 2 --bins 20 --format csv").out);
}

TEST(MonteCarloCli, RunsMcmlFilesAndLayerFiles) {
  const auto mci = temp("case.mci");
  std::ofstream(mci) << "1.0\n1\nx.mco A\n2000\n0.01 0.01\n10 20 1\n1\n1.0\n1.4 1 100 0.9 1\n1.0\n";
  auto r = run("reference --mci " + mci.string() + " --mco-dir " + scratch().string() +
               " --format json");  // x.mco in the scratch folder
  ASSERT_EQ(r.status, 0) << r.err;
  auto doc = nlohmann::json::parse(r.out);
  ASSERT_EQ(doc["runs"].size(), 1u);
  EXPECT_EQ(doc["runs"][0]["unit"], "cm");
  EXPECT_EQ(doc["runs"][0]["photons"], 2000);
  EXPECT_EQ(doc["runs"][0]["channels"][0]["reflectance"].size(), 20u);  // nr bins of dr
  EXPECT_DOUBLE_EQ(doc["runs"][0]["r_max"].get<double>(), 0.2);

  const auto layers = temp("stack.json");
  std::ofstream(layers) << R"({"format": "bssrdf-layers", "version": 1, "unit": "mm", "channels": ["R", "G"],
    "layers": [{"thickness": 0.2, "n": 1.4, "sigma_a": [0.5, 1], "sigma_s": 20, "g": 0.8},
               {"thickness": null, "n": 1.4, "sigma_a": 0.05, "sigma_s": [10, 5], "g": 0.9}]})";
  r = run("reference --layers " + layers.string() + " --photons 2000 --format json");
  ASSERT_EQ(r.status, 0) << r.err;
  doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["channels"].size(), 2u);
  EXPECT_FALSE(doc["channels"][0].contains("transmittance"));  // semi-infinite: no T(r)
}

TEST(MonteCarloCli, BadInputExitsTwoWithOneLineAndNoPartialFile) {
  const auto out = temp("result.json");
  std::filesystem::remove(out);
  const auto bad_mci = temp("bad.mci");
  std::ofstream(bad_mci) << "1.0\n1\nx.mco A\n2000\n0.01 0.01\n10 20 1\n1\n1.0\n1.4 1 oops 0.9 1\n1.0\n";
  auto r = run("reference --mci " + bad_mci.string() + " -o " + out.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(bad_mci.string() + ":9:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));

  const auto bad_layers = temp("bad.json");
  std::ofstream(bad_layers)
      << "{\"format\": \"bssrdf-layers\", \"version\": 1,\n \"layers\": [\n {\"sigma_a\": -1, \"sigma_s\": 1}]}\n";
  r = run("reference --layers " + bad_layers.string() + " -o " + out.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(bad_layers.string() + ":3:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));

  for (const std::string args :
       {"--photons 0", "--thickness -1", "--r-max 0", "--bins 1", "--g 1.5", "--layers /nonexistent.json",
        "--bin-spacing cubic", "--roulette-threshold 1", "--roulette-survival 0", "--roulette-survival 1.5"}) {
    r = run("reference --sigma-a 0.1 --sigma-s 1 " + args + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

TEST(MonteCarloCli, RouletteSettingsAreOptions) {
  // MCML's values on request; recorded in the JSON and the report.
  const auto r = run(kMedium + "--thickness 2 --roulette-threshold 1e-4 --roulette-survival 0.1 --format json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["roulette_threshold"], 1e-4);
  EXPECT_EQ(doc["roulette_survival"], 0.1);
  const auto table = run(kMedium + "--thickness 2 --roulette-threshold 0.01 --roulette-survival 0.25");
  ASSERT_EQ(table.status, 0) << table.err;
  EXPECT_NE(table.out.find("roulette below weight 0.01 with survival 0.25"), std::string::npos) << table.out;
}
