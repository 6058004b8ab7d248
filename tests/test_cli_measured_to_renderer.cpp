// Measured data to a renderer in three commands (fit, materials import, materials export): every
// fit of sigma_a and sigma_s' writes a complete medium (unit, eta, and sigma_s and g per channel with
// their 1-sigma), `materials import` turns every such kind into a material, and `materials export`
// and `lut` take a medium on the command line as `profile` does.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bssrdf/materials.hpp"
#include "cli_runner.hpp"

using bssrdf::MaterialDatabase;
using bssrdf::test_cli::run;
using bssrdf::test_cli::slurp;
using bssrdf::test_cli::temp;
using json = nlohmann::json;

namespace {

// A measured profile: the exact model's R(r) of a known forward-scattering medium, as a CSV.
std::filesystem::path measured_profile() {
  const auto csv = temp("measured.csv");
  const auto r = run("profile --sigma-a 0.05,0.1,0.2 --sigma-s 5,4,3 --g 0.8 --eta 1.4 --samples 40 -f csv -o " +
                     csv.string() + " -q");
  EXPECT_EQ(r.status, 0) << r.err;
  return csv;
}

}  // namespace

TEST(MeasuredToRenderer, FitProfileJsonIsACompleteMedium) {
  const auto fit = temp("fit.json");
  auto r = run("fit profile " + measured_profile().string() + " --eta 1.4 --g 0.8 -f json -o " + fit.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(slurp(fit));
  EXPECT_EQ(doc["unit"], "mm");
  EXPECT_EQ(doc["eta"]["value"], 1.4);
  EXPECT_EQ(doc["eta"]["fitted"], false);
  ASSERT_EQ(doc["channels"].size(), 3u);
  const double truth_s[] = {5, 4, 3}, truth_a[] = {0.05, 0.1, 0.2};
  for (std::size_t c = 0; c < 3; ++c) {
    const auto& ch = doc["channels"][c];
    EXPECT_EQ(ch["g"]["value"], 0.8);
    EXPECT_EQ(ch["g"]["fitted"], false);
    // sigma_s = sigma_s' / (1 - g): the forward medium comes back, not sigma_s' with g = 0.
    EXPECT_NEAR(ch["sigma_s"]["value"].get<double>(), ch["sigma_s_prime"]["value"].get<double>() / 0.2, 1e-9);
    EXPECT_NEAR(ch["sigma_s"]["value"].get<double>(), truth_s[c], 0.01 * truth_s[c]) << c;
    EXPECT_NEAR(ch["sigma_a"]["value"].get<double>(), truth_a[c], 0.01 * truth_a[c]) << c;
    EXPECT_TRUE(ch["sigma_s"].contains("stderr"));
  }
}

TEST(MeasuredToRenderer, FitImportExportWithoutRetyping) {
  const auto fit = temp("fit3.json");
  const auto db = temp("my-materials");
  auto r = run("fit profile " + measured_profile().string() + " --eta 1.4 --g 0.8 -f json -o " + fit.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("materials import " + fit.string() + " --name \"My wax\" --db " + db.string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(db / "my-wax.json")) << r.out;
  const auto m = MaterialDatabase::load(db).find("my wax");
  EXPECT_EQ(m.medium.eta, 1.4);
  EXPECT_FALSE(m.reduced_scattering_only);
  for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(m.medium.g[c], 0.8);
  EXPECT_NEAR(m.medium.sigma_s[2], 3, 0.03);
  // The imported material exports as the measured medium does when typed in: same file, but the name.
  r = run("materials export \"my wax\" --db " + db.string() + " --to json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto exported = json::parse(r.out);
  const auto& e = exported["materials"][0];
  EXPECT_EQ(e["eta"], 1.4);
  EXPECT_EQ(e["g"][1], 0.8);
  r = run("materials export \"my wax\" --db " + db.string() + " --to blender -o " + temp("wax.py").string());
  EXPECT_EQ(r.status, 0) << r.err;
  // Importing again under the same name would write over the material: refused, file untouched.
  const auto before = slurp(db / "my-wax.json");
  r = run("materials import " + fit.string() + " --name \"My wax\" --db " + db.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("does not exist yet"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(db / "my-wax.json"), before);
}

TEST(MeasuredToRenderer, EveryFitKindImports) {
  const auto db = temp("kinds");
  const struct {
    std::string fit, name;
    double eta, g1;
  } kinds[] = {
      {"fit albedo --albedo 0.6,0.4,0.2 --distance 1,0.8,0.5 --eta 1.33 --g 0.5", "From albedo", 1.33, 0.5},
      {"fit slab --reflectance 0.4 --transmittance 0.2 --thickness 1 --eta 1.5 --g 0.7", "From slab", 1.5, 0.7},
      {"fit slab --rxt " + std::string(BSSRDF_TEST_DATA) + "/iad_basic_B.rxt", "From rxt", 1.4, 0.0},
  };
  int i = 0;
  for (const auto& k : kinds) {
    const auto fit = temp("kind" + std::to_string(i++) + ".json");
    auto r = run(k.fit + " -f json -o " + fit.string());
    ASSERT_EQ(r.status, 0) << k.fit << ": " << r.err;
    r = run("materials import " + fit.string() + " --name \"" + k.name + "\" --db " + db.string());
    ASSERT_EQ(r.status, 0) << k.fit << ": " << r.err;
    const auto m = MaterialDatabase::load(db).find(k.name);
    EXPECT_EQ(m.medium.eta, k.eta) << k.fit;
    EXPECT_EQ(m.medium.g.back(), k.g1) << k.fit;
  }
  // The .rxt rows: one channel each, sigma_s = mu_s' / (1 - g) = 5 / mm at the first row (iad's truth).
  const auto rxt = MaterialDatabase::load(db).find("from rxt");
  ASSERT_EQ(rxt.medium.channels(), 25u);
  EXPECT_NEAR(rxt.medium.sigma_s[0], 5, 0.05);
  EXPECT_NEAR(rxt.medium.sigma_a[0], 0.1, 0.002);
}

TEST(MeasuredToRenderer, ExportAndLutTakeAnInlineMedium) {
  // --sigma-s-prime with --g is sigma_s = sigma_s' / (1 - g), exactly as profile reads it.
  auto r = run("materials export Mine --sigma-a 0.1,0.2 --sigma-s-prime 1,2 --g 0.5 --eta 1.4 --to json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m = json::parse(r.out)["materials"][0];
  EXPECT_EQ(m["name"], "Mine");
  EXPECT_NEAR(m["sigma_s"][1].get<double>(), 4, 1e-12);
  EXPECT_EQ(m["eta"], 1.4);
  // In 1/cm with --unit cm: the same medium as in 1/mm times 10.
  r = run("materials export --sigma-a 1,2 --sigma-s 20,40 --g 0.5 --eta 1.4 --unit cm --to json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(json::parse(r.out)["materials"][0]["sigma_s"][1].get<double>(), 40, 1e-9);
  r = run("materials export --sigma-a 0.1,0.2,0.3 --sigma-s-prime 1,1,1 --g 0.5 --to blender -o " +
          temp("m.py").string());
  EXPECT_EQ(r.status, 0) << r.err;
  r = run("lut --sigma-a 0.1 --sigma-s-prime 1 --g 0.5 --kind radial -o " + temp("l.json").string());
  EXPECT_EQ(r.status, 0) << r.err;
  const auto prime = json::parse(slurp(temp("l.json")));
  r = run("lut --sigma-a 0.1 --sigma-s 2 --g 0.5 --kind radial -o " + temp("l2.json").string());
  EXPECT_EQ(r.status, 0) << r.err;
  const auto plain = json::parse(slurp(temp("l2.json")));
  ASSERT_TRUE(prime.contains("channels"));
  EXPECT_EQ(prime["channels"], plain["channels"]);
  r = run("profile --sigma-a 0.1 --sigma-s 1 --sigma-s-prime 1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
  r = run("materials export Skin1 --all --sigma-a 1 --to json");
  EXPECT_EQ(r.status, 2);
}
