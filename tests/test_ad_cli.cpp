// bssrdf slab and the adding-doubling defaults of transmission and lut --kind transmission:
// JSON names scripts rely on, normalisations, agreement with the library, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "bssrdf/adding_doubling/slab.hpp"
#include "cli_runner.hpp"
#include "exr_reader.hpp"

using namespace bssrdf;
using namespace bssrdf::test_cli;
using json = nlohmann::json;

TEST(CliSlab, JsonPerChannelBothNormalisationsAndSlides) {
  const auto r = run("slab --sigma-a 0.1,0.2 --sigma-s 10,10 --g 0.9 --eta 1.4 --thickness 2 --slides 1.5,1 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["solver"], "adding-doubling");
  EXPECT_EQ(doc["normalization"], "per_incident_flux");
  EXPECT_EQ(doc["slides"]["n"], 1.5);
  ASSERT_EQ(doc["channels"].size(), 2u);
  adding_doubling::Slab slab;
  slab.layers = {{0.1, 10, 0.9, 2}};
  slab.n = 1.4;
  slab.above = slab.below = {{1.5, 1.0, 0.0}};
  const auto t = adding_doubling::solve(slab, adding_doubling::Incidence::collimated);
  const auto& c = doc["channels"][0];
  EXPECT_DOUBLE_EQ(c["diffuse_reflectance"].get<double>(), t.diffuse_reflectance);
  EXPECT_DOUBLE_EQ(c["specular_reflectance"].get<double>(), t.specular_reflectance);
  EXPECT_DOUBLE_EQ(c["total_transmittance"].get<double>(), t.total_transmittance);
  EXPECT_DOUBLE_EQ(c["unscattered_transmittance"].get<double>(), t.unscattered_transmittance);
  EXPECT_EQ(c["per_entered_flux"]["normalization"], "per_entered_flux");
  EXPECT_NEAR(c["per_entered_flux"]["diffuse_reflectance"].get<double>(),
              t.diffuse_reflectance / (1 - t.specular_reflectance), 1e-15);
  EXPECT_GT(c["quadrature_points"].get<int>(), 0);
  // More absorption, less of everything else.
  EXPECT_LT(doc["channels"][1]["diffuse_reflectance"].get<double>(), c["diffuse_reflectance"].get<double>());
  // Energy: R + Rsp + T + absorbed = 1.
  EXPECT_NEAR(c["diffuse_reflectance"].get<double>() + c["specular_reflectance"].get<double>() +
                  c["total_transmittance"].get<double>() + c["absorbed"].get<double>(),
              1, 1e-12);
}

TEST(CliSlab, SemiInfiniteDiffuseIncidenceAndCsv) {
  auto r = run("slab --material Skin1 --incidence diffuse -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_TRUE(doc["thickness"].is_null());
  EXPECT_EQ(doc["incidence"], "diffuse");
  EXPECT_EQ(doc["channels"][0]["total_transmittance"], 0.0);
  r = run("slab --material Skin1 --thickness 1 -f csv");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(count_lines(r.out), 7);  // header + 3 channels x 2 normalisations
}

TEST(CliSlab, BadInputOneLineStatusTwoNoFile) {
  const auto out = temp("never.json");
  for (const std::string args :
       {"--sigma-a 0.1 --sigma-s 1 --thickness 0", "--sigma-a 0.1 --sigma-s 1 --thickness -1",
        "--sigma-a 0.1 --sigma-s 1 --slides 1.5", "--sigma-a 0.1 --sigma-s 1 --slides 1.5,1",
        "--sigma-a 0.1 --sigma-s 1 --thickness 1 --slides 0.5,1", "--sigma-a 0.1 --sigma-s 1 --g 1 --thickness 1",
        "--sigma-a 0.1 --sigma-s 1 --thickness 1 --incidence sideways",
        "--sigma-a 0.1 --sigma-s 1 --thickness 1 --tolerance 0", "--sigma-a 0.1 --sigma-s 1 --thickness nan"}) {
    const auto r = run("slab " + args + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << args << ": " << r.out << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

TEST(CliTransmissionAddingDoubling, NoThinSlabRefusalAndTheMultipoleForComparison) {
  const auto r = run("transmission --sigma-a 0.01 --sigma-s 0.99 --eta 1.3 --thickness 0.5,2,8 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["model"], "adding-doubling");
  for (int j = 0; j < 3; ++j) EXPECT_TRUE(doc["rows"][j]["total_transmittance"][0].is_number()) << j;
  // Diffuse transmittance per entered flux, unscattered removed. The multipole's values at 2 and 8
  // transport mfp (0.464, 0.142) differ from the exact ones by its documented slab error (+31 % at
  // 2 mfp, a few % at 8 mfp against Monte Carlo).
  const double t2 = doc["rows"][1]["total_transmittance"][0], t8 = doc["rows"][2]["total_transmittance"][0];
  EXPECT_GT(t2, t8);
  EXPECT_NEAR(t2 / 0.464, 1, 0.35);
  EXPECT_NEAR(t8 / 0.142, 1, 0.1);
  const auto lut = temp("t.exr");
  const auto l = run("lut --material Skin1 --kind transmission --thickness 0.05,0.5,3 -q -o " + lut.string());
  ASSERT_EQ(l.status, 0) << l.err;
  const auto t = test_exr::read_exr(lut);
  EXPECT_EQ(t.width, 3);  // nothing omitted
  EXPECT_EQ(t.strings.at("bssrdf:sources"), "adding_doubling");
}

TEST(CliSlab, LayerFiles) {
  const auto r = run(std::string("slab --layers ") + BSSRDF_TEST_DATA + "/two_layer_skin.json -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = json::parse(r.out);
  EXPECT_EQ(doc["channels"][0]["total_transmittance"], 0.0);  // semi-infinite dermis
  EXPECT_GT(doc["channels"][0]["diffuse_reflectance"].get<double>(), 0.3);
  const auto bad = run(std::string("slab --layers ") + BSSRDF_TEST_DATA + "/two_layer_skin.json --sigma-a 1");
  EXPECT_EQ(bad.status, 2);
}
