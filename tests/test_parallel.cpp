// The one parallel loop (parallel.hpp) and the one slab-thickness rule (default_thickness_range),
// which `bssrdf transmission` and `bssrdf lut --kind transmission` share.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/parallel.hpp"
#include "cli_runner.hpp"

namespace {

using namespace bssrdf;

TEST(ParallelFor, RunsEveryItemOnceWhateverTheThreadCount) {
  for (std::size_t n : {0u, 1u, 7u, 1000u})
    for (unsigned threads : {0u, 1u, 2u, 3u, 16u}) {
      std::vector<std::atomic<int>> runs(n);
      parallel_for(n, threads, [&](std::size_t i) { ++runs[i]; });
      for (std::size_t i = 0; i < n; ++i)
        EXPECT_EQ(runs[i].load(), 1) << "n " << n << ", threads " << threads << ", item " << i;
    }
  EXPECT_EQ(worker_count(5, 16), 5u);
  EXPECT_EQ(worker_count(0, 4), 1u);
  EXPECT_GE(worker_count(100, 0), 1u);
}

TEST(ParallelFor, TheSmallestFailingItemsErrorIsRethrownWhateverTheThreadCount) {
  for (unsigned threads : {1u, 2u, 4u, 8u}) {
    std::atomic<int> below_failure{0};
    try {
      parallel_for(200, threads, [&](std::size_t i) {
        if (i == 37 || i == 150 || i == 199) throw std::runtime_error("item " + std::to_string(i));
        if (i < 37) ++below_failure;
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "item 37") << threads << " threads";
    }
    EXPECT_EQ(below_failure.load(), 37) << "every item before the failure still runs";
  }
}

TEST(SlabThicknessRule, StartsWhereTheModelGivesAValueAndEndsAtFortyTransportMfp) {
  const auto database = MaterialDatabase::load(default_materials_dir());
  const auto& skin = database.find("Skin1").medium;
  const auto ell = transport_mfp_range(skin);
  ASSERT_GT(ell.max, ell.min);
  TransmissionTableOptions options;
  options.model = "adding-doubling";
  auto range = default_thickness_range(skin, options);
  EXPECT_DOUBLE_EQ(range.d_min, 0.1 * ell.min);
  EXPECT_DOUBLE_EQ(range.d_max, 40 * ell.max);
  options.model = "multipole";  // alone it is invalid below 2 ell of any channel
  EXPECT_DOUBLE_EQ(default_thickness_range(skin, options).d_min, 2 * ell.max);
  options.reference = true;  // the Monte Carlo reference fills the thin slabs
  EXPECT_DOUBLE_EQ(default_thickness_range(skin, options).d_min, 0.1 * ell.min);
}

TEST(SlabThicknessRule, TransmissionAndLutAgreeOnTheDefaultThicknesses) {
  for (const std::string model : {"adding-doubling", "multipole"}) {
    const auto t = test_cli::run("transmission --material Skin1 --model " + model + " -f json");
    ASSERT_EQ(t.status, 0) << t.err;
    const auto rows = nlohmann::json::parse(t.out)["rows"];
    const auto out = test_cli::temp("rule-" + model + ".json");
    const auto l =
        test_cli::run("lut --material Skin1 --kind transmission --model " + model + " -q -o " + out.string());
    ASSERT_EQ(l.status, 0) << l.err;
    const auto table = nlohmann::json::parse(test_cli::slurp(out));
    std::vector<double> lut_thickness;
    for (const auto& c : table["channels"])
      if (c["name"] == "thickness") lut_thickness = c["values"].get<std::vector<double>>();
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(kThicknessSamples)) << model;
    ASSERT_EQ(lut_thickness.size(), rows.size()) << model;  // the default range holds no omitted thickness
    for (std::size_t i = 0; i < rows.size(); ++i)
      EXPECT_NEAR(lut_thickness[i], rows[i]["thickness"].get<double>(), 1e-12 * lut_thickness[i])
          << model << " row " << i;
  }
}

}  // namespace
