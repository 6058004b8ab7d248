// Radial tables from the Monte Carlo reference (lut --kind radial --reference): for low albedo and
// thin layers, where no diffusion model is valid. The table is the Monte Carlo's bins repackaged:
// its total matches adding-doubling, its CDF is consistent and inverts, it does not depend on the
// thread count, and the command line writes it for a thin-epidermis skin stack the multipole refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/lut/reference_radial_table.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/reduced.hpp"
#include "cli_runner.hpp"
#include "reference_data.hpp"

using namespace bssrdf;

TEST(ReferenceRadialTable, TotalMatchesAddingDoublingAndTheCdfInverts) {
  // Low albedo, where diffusion fails: alpha' = 0.3 at n 1.4, g 0.9 (sigma_t' = 1 /mm).
  for (const auto& row : test_data::read_tsv("ad_semi_infinite.tsv")) {
    if (row.at("n") != 1.4 || row.at("g") != 0.9 || row.at("reduced_albedo") != 0.3) continue;
    const double albedo = albedo_from_reduced(0.3, 0.9), sigma_t = 1 / (1 - albedo * 0.9);
    const auto medium = Medium::single_channel((1 - albedo) * sigma_t, albedo * sigma_t, 0.9, 1.4);
    ReferenceRadialOptions o;
    o.photons = 200000;
    const auto t = build_reference_radial_table(LayerStack::half_space(medium), o);
    EXPECT_NEAR(t.total_reflectance[0], row.at("Rd_entered"), 4 * t.total_stderr[0]);
    EXPECT_GT(t.table_reflectance[0], 0.999 * t.total_reflectance[0]);  // 30 ell holds it
    ASSERT_EQ(t.size(), 64u);
    EXPECT_DOUBLE_EQ(t.cdf[0].back(), 1.0);
    for (std::size_t j = 1; j < t.size(); ++j) {
      EXPECT_GE(t.cdf[0][j], t.cdf[0][j - 1]);
      EXPECT_GE(t.inverse_cdf[0][j], t.inverse_cdf[0][j - 1]);
      EXPECT_EQ(t.r_inner[j], t.r_outer[j - 1]);
      EXPECT_GE(t.reflectance_stderr[0][j], 0);
    }
    // The inverse CDF lands where the CDF, linear in ln r between edges, reaches u.
    for (std::size_t j = 5; j + 1 < t.size(); j += 9) {
      const double r = t.inverse_cdf[0][j];
      const auto i =
          static_cast<std::size_t>(std::lower_bound(t.r_outer.begin(), t.r_outer.end(), r) - t.r_outer.begin());
      ASSERT_GT(i, 0u);
      const double s = std::log(r / t.r_outer[i - 1]) / std::log(t.r_outer[i] / t.r_outer[i - 1]);
      EXPECT_NEAR(t.cdf[0][i - 1] + s * (t.cdf[0][i] - t.cdf[0][i - 1]), t.u[j], 1e-9);
    }
    // One thread or two: the same numbers.
    o.threads = 1;
    const auto one = build_reference_radial_table(LayerStack::half_space(medium), o);
    EXPECT_EQ(one.reflectance, t.reflectance);
    EXPECT_EQ(one.inverse_cdf, t.inverse_cdf);
    return;
  }
  FAIL() << "adding-doubling row not found";
}

TEST(ReferenceRadialTable, ThinSkinLayersWhereTheMultipoleRefuses) {
  const auto layers = test_cli::temp("skin.json");
  std::ofstream(layers) << R"({"format": "bssrdf-layers", "version": 1, "unit": "mm", "channels": ["R", "G", "B"],
    "layers": [{"name": "epidermis", "thickness": 0.1, "n": 1.4, "sigma_a": [0.1, 0.3, 0.6], "sigma_s": [20, 22, 25], "g": 0.8},
               {"name": "dermis", "n": 1.4, "sigma_a": [0.03, 0.1, 0.3], "sigma_s": [12, 14, 16], "g": 0.8}]})";
  auto r = test_cli::run("profile --layers " + layers.string());
  EXPECT_EQ(r.status, 2);  // 0.1 mm is 0.4 transport mfp: the multipole refuses
  EXPECT_NE(r.err.find("--reference"), std::string::npos) << r.err;
  const auto out = test_cli::temp("skin-ref.json");
  r = test_cli::run("lut --layers " + layers.string() + " --kind radial --reference --photons 20000 -q -o " +
                    out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(test_cli::slurp(out));
  EXPECT_EQ(doc["attributes"]["bssrdf:model"], "monte carlo");
  EXPECT_EQ(doc["attributes"]["bssrdf:photons"], 20000.0);
  std::vector<std::string> names;
  for (const auto& c : doc["channels"]) names.push_back(c["name"]);
  for (const char* want :
       {"R", "G", "B", "radius", "r_inner", "r_outer", "stderr.R", "ring.G", "cdf.B", "u", "inverse_cdf.R"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  // Red, the least absorbed, reflects most.
  EXPECT_GT(doc["attributes"]["bssrdf:total_reflectance.R"].get<double>(),
            doc["attributes"]["bssrdf:total_reflectance.B"].get<double>());
  for (const std::string& args : std::vector<std::string>{
           "--layers " + layers.string() + " --kind radial -o x.json",
           "--layers " + layers.string() + " --kind preintegrated --reference -o x.json",
           "--material Skin1 --kind radial --reference --model pbd -o x.json",
           "--material Skin1 --layers " + layers.string() + " --kind radial --reference -o x.json"}) {
    r = test_cli::run("lut " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(test_cli::count_lines(r.err), 1) << args << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists("x.json"));
}
