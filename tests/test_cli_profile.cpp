// `bssrdf profile` end to end: valid runs give parseable output that agrees with the library;
// every kind of bad input gives exit status 2, a one-line message and no output file.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "cli_runner.hpp"

using namespace bssrdf;
using test_cli::count_lines;
using test_cli::run;
using json = nlohmann::json;

TEST(CliProfile, JsonForABundledMaterial) {
  const auto r = run("profile --material skin1 --model dipole --format json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["model"], "dipole");
  EXPECT_EQ(doc["unit"], "mm");
  EXPECT_EQ(doc["normalization"], "per_entered_flux");
  EXPECT_EQ(doc["eta"], 1.3);
  EXPECT_EQ(doc["material"]["name"], "Skin1");
  ASSERT_EQ(doc["channels"].size(), 3u);
  const auto skin = MaterialDatabase::load(default_materials_dir()).find("Skin1").medium;
  const auto model = make_model("dipole");
  for (std::size_t c = 0; c < 3; ++c) {
    const auto& ch = doc["channels"][c];
    for (const char* key : {"name", "sigma_a", "sigma_s", "g", "sigma_s_prime", "albedo_prime", "total_reflectance",
                            "radius_99", "radius", "reflectance", "validity"})
      EXPECT_TRUE(ch.contains(key)) << key;
    EXPECT_EQ(ch["radius"].size(), 64u);
    EXPECT_EQ(ch["reflectance"].size(), 64u);
    EXPECT_DOUBLE_EQ(ch["sigma_a"].get<double>(), skin.sigma_a[c]);
    EXPECT_NEAR(ch["total_reflectance"].get<double>(), model->total_reflectance(skin.reduced(c)), 1e-12);
    const double r0 = ch["radius"][10].get<double>();
    EXPECT_NEAR(ch["reflectance"][10].get<double>(), model->reflectance(skin.reduced(c), r0), 1e-12);
    for (const auto& v : ch["reflectance"]) EXPECT_GE(v.get<double>(), 0.0);
  }
  EXPECT_EQ(doc["channels"][0]["name"], "R");
  // Skin1 blue has alpha' = 0.68: the dipole's total is off by up to 29 % there, and it says so.
  bool warned = false;
  for (const auto& v : doc["channels"][2]["validity"])
    warned |= v["severity"] == "warning" || v["severity"] == "invalid";
  EXPECT_TRUE(warned);
}

TEST(CliProfile, WritesTheFileAndPrintsTheTable) {
  const auto path = test_cli::temp("profile.json");
  std::filesystem::remove(path);
  const auto r = run("profile --material Marble -o " + path.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("R_total"), std::string::npos);
  const auto doc = json::parse(test_cli::slurp(path));
  EXPECT_EQ(doc["model"], "exact");  // the registry's default inside its domain
  EXPECT_EQ(doc["eta"], 1.5);
}

TEST(CliProfile, UnitsConvertAtTheEdge) {
  // The same medium in 1/mm and in 1/cm: identical totals, radii scaled by 10, R(r) by 1/100.
  const auto mm = json::parse(run("profile --sigma-a 0.1 --sigma-s 2 --g 0.5 --eta 1.4 --radii 0.5,1,2 -f json").out);
  const auto cm =
      json::parse(run("profile --sigma-a 1 --sigma-s 20 --g 0.5 --eta 1.4 --radii 0.05,0.1,0.2 --unit cm -f json").out);
  ASSERT_EQ(mm["channels"].size(), 1u);
  EXPECT_EQ(cm["unit"], "cm");
  EXPECT_NEAR(mm["channels"][0]["total_reflectance"].get<double>(),
              cm["channels"][0]["total_reflectance"].get<double>(), 1e-12);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(cm["channels"][0]["reflectance"][i].get<double>(),
                100 * mm["channels"][0]["reflectance"][i].get<double>(),
                1e-9 * cm["channels"][0]["reflectance"][i].get<double>());
  EXPECT_NEAR(cm["channels"][0]["radius_99"].get<double>() * 10, mm["channels"][0]["radius_99"].get<double>(), 1e-9);
}

TEST(CliProfile, ModelSpecificForms) {
  // Quantized diffusion exposes its Gaussian mixture; its weights sum to the total.
  auto doc = json::parse(run("profile --material Skin1 --model quantized --samples 8 -f json").out);
  for (const auto& ch : doc["channels"]) {
    double sum = 0;
    for (const auto& w : ch["gaussians"]["weight"]) sum += w.get<double>();
    EXPECT_NEAR(sum, ch["total_reflectance"].get<double>(), 1e-12);
    EXPECT_EQ(ch["gaussians"]["variance"].size(), ch["gaussians"]["weight"].size());
  }
  // Burley with a given surface albedo: total = A, and d is reported.
  doc = json::parse(run("profile --material Skin1 --model burley --surface-albedo 0.4 --samples 8 -f json").out);
  for (const auto& ch : doc["channels"]) {
    EXPECT_DOUBLE_EQ(ch["total_reflectance"].get<double>(), 0.4);
    EXPECT_GT(ch["burley_d"].get<double>(), 0.0);
  }
  // --single-scattering adds the exact term: totals grow by the single-scattering total.
  const auto ms = json::parse(run("profile --material Skin1 --model better-dipole --samples 8 -f json").out);
  const auto with =
      json::parse(run("profile --material Skin1 --model better-dipole --samples 8 --single-scattering -f json").out);
  EXPECT_EQ(with["model"], "better-dipole+ss");
  EXPECT_EQ(with["includes_single_scattering"], true);
  EXPECT_GT(with["channels"][0]["total_reflectance"].get<double>(),
            ms["channels"][0]["total_reflectance"].get<double>());
}

TEST(CliProfile, CsvAndGrids) {
  // A linear grid from r = 0 needs a model finite there (exact's single scattering is 1/r).
  const auto r =
      run("profile --sigma-a 0.01,0.02 --sigma-s 1,1 --channels a,b --model better-dipole --spacing linear --r-max 5 "
          "--samples 11 -f csv");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string body = r.out.substr(r.out.find('\n') + 1);  // after "# model: better-dipole"
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "# model: better-dipole");
  EXPECT_EQ(body.substr(0, body.find('\n')), "radius_mm,a_per_mm2,b_per_mm2");
  EXPECT_EQ(count_lines(body), 12);
  EXPECT_EQ(body.substr(body.find('\n') + 1, 2), "0,");
  // The default model refuses r = 0 with the reason.
  const auto zero = run("profile --sigma-a 0.01 --sigma-s 1 --spacing linear --r-max 5 --samples 11 -f csv");
  EXPECT_EQ(zero.status, 2);
  EXPECT_NE(zero.err.find("infinite at r = 0"), std::string::npos) << zero.err;
}

TEST(CliProfile, VersionAndHelp) {
  auto r = run("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("bssrdf " BSSRDF_VERSION), std::string::npos);
  r = run("--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("profile"), std::string::npos);
  r = run("profile --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--sigma-a"), std::string::npos);
  r = run("models");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("better-dipole"), std::string::npos);
  // The reference model states its own measured band, not "not measured".
  const auto exact_at = r.out.find("\nexact\n");
  ASSERT_NE(exact_at, std::string::npos) << r.out;
  const std::string exact_entry = r.out.substr(exact_at, 600);  // its three lines
  EXPECT_NE(exact_entry.find("against fresh Monte Carlo: total within"), std::string::npos) << exact_entry;
  r = run("profile --help");
  EXPECT_NE(r.out.find("burley-dmfp, exact,"), std::string::npos) << r.out;  // the registry's names
  r = run("materials list");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(count_lines(r.out), 47);  // Jensen 2001 (12) + Narasimhan 2006 (35)
  r = run("materials list --source jensen2001");
  EXPECT_EQ(count_lines(r.out), 12);
}

TEST(CliProfile, MultipoleSlabGivesReflectanceAndTransmittance) {
  const auto r = run("profile --sigma-a 0.01 --sigma-s 1 --eta 1.3 --thickness 3 --samples 16 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["model"], "multipole");
  EXPECT_EQ(doc["geometry"], "slab");
  EXPECT_EQ(doc["thickness"], 3.0);
  const auto& ch = doc["channels"][0];
  for (const char* key : {"reflectance", "total_reflectance", "transmittance", "total_transmittance", "dipole_pairs"})
    EXPECT_TRUE(ch.contains(key)) << key;
  EXPECT_EQ(ch["transmittance"].size(), 16u);
  EXPECT_NEAR(ch["total_reflectance"].get<double>(), 0.5253, 1e-4);
  EXPECT_NEAR(ch["total_transmittance"].get<double>(), 0.3694, 1e-4);
  EXPECT_GE(ch["dipole_pairs"].get<int>(), 3);
  for (const auto& v : ch["transmittance"]) EXPECT_GE(v.get<double>(), 0.0);
  bool warned = false;  // 3 ell: near the thin-slab limit, and it says so
  for (const auto& v : ch["validity"]) warned |= v["code"] == "thin_slab" && v["severity"] == "warning";
  EXPECT_TRUE(warned);
  const auto csv = run("profile --sigma-a 0.01 --sigma-s 1 --thickness 3 --samples 4 -f csv");
  EXPECT_EQ(csv.out.substr(0, csv.out.find('\n')), "# model: multipole");
  const std::string body = csv.out.substr(csv.out.find('\n') + 1);
  EXPECT_EQ(body.substr(0, body.find('\n')), "radius_mm,c0_per_mm2,c0_transmittance_per_mm2");
}

TEST(CliProfile, LayerStackFromTheFileSharedWithTheReference) {
  const std::string file = std::string(BSSRDF_TEST_DATA) + "/two_layer_skin.json";
  const auto r = run("profile --layers " + file + " --radii 0.1,1,3 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["geometry"], "layers");
  EXPECT_EQ(doc["layers"].size(), 2u);
  EXPECT_FALSE(doc["channels"][0].contains("transmittance"));  // semi-infinite: no T
  EXPECT_GT(doc["channels"][0]["total_reflectance"].get<double>(), 0.5);
  const auto mc = run("reference --layers " + file + " --photons 200 -f json");
  EXPECT_EQ(mc.status, 0) << mc.err;  // the same file runs through the Monte Carlo reference
}

TEST(CliTransmission, TotalTransmittanceAgainstThickness) {
  const auto r =
      run("transmission --model multipole --sigma-a 0.01 --sigma-s 0.99 --eta 1.3 --thickness 0.5,2,8 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  ASSERT_EQ(doc["rows"].size(), 3u);
  EXPECT_TRUE(doc["rows"][0]["total_transmittance"][0].is_null());  // 0.5 ell: invalid, no number
  EXPECT_EQ(doc["rows"][0]["invalid"][0], "source_outside_slab");
  // Donner & Jensen 2005's slab check (tests/data/REFERENCE_CHECKS.md).
  EXPECT_NEAR(doc["rows"][1]["total_transmittance"][0].get<double>(), 0.464, 1e-3);
  EXPECT_NEAR(doc["rows"][2]["total_transmittance"][0].get<double>(), 0.142, 1e-3);
  const auto table = run("transmission --material Skin1 --samples 5");
  EXPECT_EQ(table.status, 0) << table.err;
  EXPECT_NE(table.out.find("T_total G"), std::string::npos);
}

struct BadInput {
  const char* arguments;
  const char* expected;  // a fragment the one-line message must contain
};

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, ExitsTwoWithOneLineAndNoFile) {
  const auto path = test_cli::temp("bad-input.json");
  std::filesystem::remove(path);
  const auto r = run(std::string(GetParam().arguments) + " -o " + path.string());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(GetParam().expected), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  EXPECT_FALSE(std::filesystem::exists(path));
}

INSTANTIATE_TEST_SUITE_P(
    Profile, CliBadInput,
    ::testing::Values(
        BadInput{"profile --sigma-a 0.1,-1,0.1 --sigma-s 1,1,1", "--sigma-a[G] = -1: accepted range is >= 0"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --g 1.2", "--g[c0] = 1.2: accepted range is -1 < g < 1"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --eta 0", "--eta = 0"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --eta -1.3", "--eta = -1.3"},
        BadInput{"profile --sigma-a 0,0 --sigma-s 0,1", "--sigma-a[c0] + --sigma-s[c0] = 0"},
        BadInput{"profile --sigma-a abc --sigma-s 1", "--sigma-a = 'abc'"},
        BadInput{"profile --sigma-a 0.1,0.2,0.3 --sigma-s 1,2", "--sigma-s: 2 values given, but --sigma-a has 3"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --channels a,b", "--channels: 2 names given"},
        BadInput{"profile --material nosuchthing", "material = 'nosuchthing'"},
        BadInput{"profile --material skim", "Skimmilk"}, BadInput{"profile --material Skin1 --sigma-a 1", "excludes"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --frobnicate", "frobnicate"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --model tripole", "one of dipole, better-dipole, pbd"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --radii 0.5,0.1", "--radii: radius[1] = 0.1"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --radii 0.5,x", "--radii = '0.5,x'"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --unit inch", "--unit = 'inch'"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --samples 1",
                 "--samples = '1': accepted range is a whole number from 2 to 1000000"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --r-min 5 --r-max 1", "--r-max = 1"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --format xml", "--format"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --model burley --surface-albedo 1.5", "--surface-albedo = 1.5"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --surface-albedo 0.5", "only the burley models"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --model pbd --single-scattering", "pbd already includes it"},
        BadInput{"profile --sigma-s 1", "give --material NAME, or --sigma-a with --sigma-s (or --sigma-s-prime)"},
        BadInput{"profile --material skin1 --db /nonexistent/db.json", "cannot open"},
        BadInput{"frobnicate", "unknown command 'frobnicate'"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --thickness 0", "--thickness = 0: accepted range is > 0"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --thickness -2", "--thickness = -2"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --thickness x", "--thickness = 'x'"},
        BadInput{"profile --sigma-a 0.01 --sigma-s 1 --thickness 1", "use 'bssrdf reference --thickness 1'"},
        BadInput{"profile --sigma-a 0.01 --sigma-s 1 --thickness 0.5", "real source (depth ell) lies outside"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --model multipole", "give --thickness D"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --model dipole --thickness 5", "--model = 'dipole'"},
        BadInput{"profile --sigma-a 0.1 --sigma-s 1 --thickness 5 --pair-tolerance 2", "--pair-tolerance = 2"},
        BadInput{"profile --layers " BSSRDF_TEST_DATA "/two_layer_skin.json --thickness 2", "excludes"},
        BadInput{"profile --layers " BSSRDF_TEST_DATA "/two_layer_skin.json --sigma-a 1",
                 "--layers describes the medium"},
        BadInput{"profile --layers /nonexistent.json", "cannot open"},
        BadInput{"transmission --sigma-a 0.01 --sigma-s 1 --thickness 0,1", "--thickness = 0"},
        BadInput{"transmission --sigma-a 0.01 --sigma-s 1 --d-min 5 --d-max 1", "--d-max = 1"},
        BadInput{"profile --layers " BSSRDF_TEST_DATA "/thin_epidermis.json", "epidermis: d = 0.505 ell < 2 ell"}));
