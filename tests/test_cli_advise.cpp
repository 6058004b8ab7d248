// `bssrdf advise` end to end: the JSON names issue 16 fixes, the choice is the cheapest candidate
// within tolerance for the target, the object-size flag, and bad input (exit 2, one line, no output).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli_runner.hpp"

using namespace bssrdf;
using test_cli::count_lines;
using test_cli::run;

TEST(CliAdvise, JsonNamesAndTheChoiceIsTheCheapestWithinTolerance) {
  // Tolerance 5: above the exact reference's own uncertainty (about 2.5 code values for Skin1), so something meets it.
  const auto r = run("advise --material Skin1 --pixel 0.1mm --tolerance 5 -f json -n 100000");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  ASSERT_TRUE(doc.contains("choice"));
  ASSERT_TRUE(doc["candidates"].is_array());
  bool lambertian = false;
  double previous_cost = -1;
  std::optional<std::size_t> first_meeting;
  for (std::size_t i = 0; i < doc["candidates"].size(); ++i) {
    const auto& c = doc["candidates"][i];
    for (const char* key : {"representation", "error", "cost", "meets_tolerance"}) ASSERT_TRUE(c.contains(key)) << key;
    lambertian |= c["representation"] == "lambertian";
    EXPECT_GE(c["cost"].get<double>(), previous_cost);  // cheapest first
    previous_cost = c["cost"].get<double>();
    EXPECT_EQ(c["meets_tolerance"].get<bool>(), c["error"].get<double>() <= 5.0);
    if (!first_meeting && c["meets_tolerance"].get<bool>()) first_meeting = i;
  }
  EXPECT_TRUE(lambertian);
  ASSERT_TRUE(first_meeting);
  EXPECT_EQ(doc["choice"]["representation"], doc["candidates"][*first_meeting]["representation"]);
  EXPECT_LT(doc["reference_noise"].get<double>(), 0.5);
  EXPECT_EQ(doc["choice"]["cost_unit"], "ns");
  // The candidate that is the reference is not judged at 0: it carries the reference's uncertainty.
  ASSERT_TRUE(doc.contains("reference_uncertainty"));
  EXPECT_GT(doc["reference_uncertainty"].get<double>(), 0);
  for (const auto& c : doc["candidates"]) {
    if (c["representation"] == "reference-table" || c["representation"] == "exact") {
      EXPECT_GE(c["error"].get<double>(), doc["reference_uncertainty"].get<double>()) << c["representation"];
    }
  }
  EXPECT_EQ(doc["reference_sources"], nlohmann::json::parse(R"(["exact", "exact", "exact"])"));
}

TEST(CliAdvise, RealtimeTargetChoosesOnlyRealtimeCandidates) {
  const auto r = run("advise --material Marble --pixel 1mm --tolerance 3 --target realtime -f json -n 100000");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  ASSERT_FALSE(doc["choice"].is_null());
  EXPECT_TRUE(doc["choice"]["realtime"].get<bool>());
  // Any offline candidate listed before the choice that meets the tolerance was skipped for the target.
  for (const auto& c : doc["candidates"]) {
    if (c["representation"] == doc["choice"]["representation"]) break;
    EXPECT_TRUE(!c["meets_tolerance"].get<bool>() || !c["realtime"].get<bool>()) << c["representation"];
  }
}

TEST(CliAdvise, LambertianSufficesWhenScatteringIsFarBelowAPixel) {
  // sigma_s' = 100/mm: 0.06 mm diffuse mean free path, 50 mm pixels.
  const auto r = run("advise --sigma-a 1 --sigma-s 100 --channels x --pixel 5cm -f json -n 100000");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["choice"]["representation"], "lambertian");
}

TEST(CliAdvise, WideProfilesOnSmallObjectsAreFlagged) {
  auto r = run("advise --material Skin1 --pixel 1mm --object-size 5mm -n 20000 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto doc = nlohmann::json::parse(r.out);
  ASSERT_EQ(doc["warnings"].size(), 1u);
  EXPECT_NE(doc["warnings"][0].get<std::string>().find("slab"), std::string::npos);
  r = run("advise --material Skin1 --pixel 1mm --object-size 2m -n 20000 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(r.out)["warnings"].empty());
}

TEST(CliAdvise, TableNamesTheChoiceAndWhyCheaperOnesFail) {
  const auto r = run("advise --material Ketchup --pixel 0.5mm -n 50000");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("lambertian"), std::string::npos);
  EXPECT_TRUE(r.out.find("choice:") != std::string::npos || r.out.find("no candidate") != std::string::npos);
}

// Without a choice the table says what would do (the most accurate candidate for the target) and,
// below the reference's own uncertainty U, that such a tolerance cannot be certified.
TEST(CliAdvise, WithoutAChoiceTheTableSaysWhatWouldDo) {
  const auto r = run("advise --material Skin1 --pixel 1mm --tolerance 0.5 -f json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  ASSERT_TRUE(doc["choice"].is_null());
  const double U = doc["reference_uncertainty"].get<double>();
  ASSERT_GT(U, 0.5);
  std::string best;
  double least = 1e300;
  for (const auto& c : doc["candidates"])
    if (c["error"].get<double>() < least) {
      least = c["error"].get<double>();
      best = c["representation"].get<std::string>();
    }
  const auto t = run("advise --material Skin1 --pixel 1mm --tolerance 0.5");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.out.find("no candidate meets the tolerance for this target; the most accurate is " + best),
            std::string::npos)
      << t.out;
  EXPECT_NE(t.out.find("cannot be certified"), std::string::npos) << t.out;
}

TEST(CliAdvise, BadInputExitsTwoWithOneLine) {
  for (const char* args :
       {"--material Skin1 --pixel -1mm", "--material Skin1 --pixel 0.1furlong", "--material Skin1 --pixel 0",
        "--material Skin1 --pixel 0.1 --tolerance 0", "--material Skin1 --pixel 0.1 --tolerance nan",
        "--material Skin1 --pixel 0.1 --target mobile", "--material Skin1 --pixel 0.1 --object-size -3",
        "--material Skin1", "--material Skin1 --pixel 0.1 -n 5", "--all --material Skin1 --pixel 1",
        "--sigma-a 0.1 --sigma-s 10 --g -0.3 --pixel 1 --reference exact"}) {  // g < 0: outside its domain
    const auto r = run(std::string("advise ") + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
}

TEST(CliValidityMap, WritesEveryModelsPanelAndTheCheapestMap) {
  const auto file = test_cli::temp("map.svg");
  for (const char* over : {"albedo,eta", "albedo,g"}) {
    const auto r =
        run(std::string("models --map ") + file.string() + " --over " + over + " --metric total --accuracy 0.05");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string svg = test_cli::slurp(file);
    for (const char* model : {"dipole", "better-dipole", "burley", "pbd", "quantized+ss"})
      EXPECT_NE(svg.find(std::string(">") + model + "<"), std::string::npos) << model;
    EXPECT_NE(svg.find("cheapest within 5 %"), std::string::npos);
    EXPECT_NE(svg.find("total error against the exact model"), std::string::npos);
    EXPECT_NE(svg.find("alpha' (reduced albedo)"), std::string::npos);
    EXPECT_GT(std::count(svg.begin(), svg.end(), '\n'), 100);
  }
}

// PNG: the same map rasterised (a real PNG: signature, IHDR size, and both white and coloured pixels
// are checked through its size); --metric image judges every model against a Monte Carlo run per
// cell, so its map names code values.
TEST(CliValidityMap, WritesPngAndTheImageMetric) {
  const auto png = test_cli::temp("map.png");
  auto r = run("models --map " + png.string() + " --over albedo,g --metric profile");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string bytes = test_cli::slurp(png);
  ASSERT_GT(bytes.size(), 5000u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(bytes[at])) << 24) |
           (static_cast<unsigned char>(bytes[at + 1]) << 16) | (static_cast<unsigned char>(bytes[at + 2]) << 8) |
           static_cast<unsigned char>(bytes[at + 3]);
  };
  EXPECT_GT(be32(16), 1000u);  // width: two pixels a unit of the SVG layout
  EXPECT_GT(be32(20), 300u);
  const auto svg = test_cli::temp("image.svg");
  for (const char* reference : {"exact", "montecarlo"}) {
    r = run("models --map " + svg.string() + " --over albedo,eta --metric image --pixel 1 --tolerance 3 -n 2000 " +
            "--map-reference " + reference);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string text = test_cli::slurp(svg);
    EXPECT_NE(text.find("cheapest within 3 code values"), std::string::npos);
    EXPECT_NE(text.find("cell text: code values"), std::string::npos);
    EXPECT_NE(text.find(">pbd<"), std::string::npos);
    EXPECT_NE(text.find(std::string(reference) == "exact" ? "model exact" : "Monte Carlo"), std::string::npos)
        << reference;
  }
}

TEST(CliValidityMap, BadInputExitsTwoWithoutAFile) {
  const auto file = test_cli::temp("bad.svg");
  for (const std::string& args :
       {"--map " + file.string() + " --over albedo,sigma", "--map " + file.string() + " --metric speed",
        "--map " + test_cli::temp("map.gif").string(), "--map " + file.string() + " --accuracy -1",
        "--map " + file.string() + " --metric image --pixel 0",
        "--map " + file.string() + " --metric image --tolerance -2",
        "--map " + file.string() + " --metric image --map-reference pbd"}) {
    const auto r = run("models " + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(file)) << args;
  }
}

TEST(CliAdvise, WriteProducesTheChosenTable) {
  const auto dir = test_cli::temp("advised");
  // A loose tolerance: the Lambertian albedo, equal to the reference's diffuse reflectance.
  auto r = run("advise --material Skin1 --pixel 1mm --tolerance 300 -n 20000 -f json --write " + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(nlohmann::json::parse(r.out)["choice"]["representation"], "lambertian");
  auto table = nlohmann::json::parse(test_cli::slurp(dir / "Skin1.lambertian.json"));
  EXPECT_EQ(table["format"], "bssrdf-lut");
  EXPECT_EQ(table["kind"], "albedo");
  ASSERT_EQ(table["channels"].size(), 3u);
  const double red = table["channels"][0]["values"][0].get<double>();
  EXPECT_GT(red, 0.3);  // Skin1's red diffuse reflectance, about 0.44
  EXPECT_LT(red, 0.6);
  // A tolerance the 8-radius table meets: its values are the model's R(r) at its radii.
  r = run("advise --material Skin1 --pixel 1mm --tolerance 30 -n 20000 --write " + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_NE(r.out.find("choice: radial-table-8:pbd"), std::string::npos) << r.out;
  table = nlohmann::json::parse(test_cli::slurp(dir / "Skin1.radial-table-8_pbd.json"));
  EXPECT_EQ(table["width"], 8);
  const auto radius = table["channels"][0]["values"][3].get<double>(),
             R = table["channels"][1]["values"][3].get<double>();
  char radii[64];
  std::snprintf(radii, sizeof radii, "%.17g,%.17g", radius, 2 * radius);
  const auto p = run(std::string("profile --material Skin1 --model pbd -f csv --radii ") + radii);
  ASSERT_EQ(p.status, 0) << p.err;
  std::istringstream lines(p.out);
  std::string line;
  while (std::getline(lines, line) && (line.empty() || line[0] == '#' || line[0] == 'r')) {
  }
  const double profile_R = std::stod(line.substr(line.find(',') + 1));  // first row, red channel
  EXPECT_NEAR(R, profile_R, 1e-9 * profile_R);
  // Every node is the model's value, the outermost (30 transport mean free paths) too: the table
  // written is the table judged (a node written as 0 there once lost 3 % of Skin1's red light).
  for (const auto& v : table["channels"][1]["values"]) EXPECT_GT(v.get<double>(), 0);
}

TEST(CliAdvise, WriteWithoutAChoiceFailsWithoutOutput) {
  const auto dir = test_cli::temp("none");
  // Against a Monte Carlo run no candidate is within 0.01 code values (its own noise is larger).
  const auto r = run("advise --material Skin1 --pixel 1mm --tolerance 0.01 --reference montecarlo -n 20000 --write " +
                     dir.string());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_TRUE(r.out.empty());
}

// The whole database with the default reference: one line a material, each naming where every
// channel's reference came from (auto: exact inside its table, a measured shape with the
// adding-doubling total above it, a Monte Carlo run of the channel below it) and its uncertainty U.
TEST(CliAdvise, AllNamesEachMaterialsReference) {
  const auto r = run("advise --all --pixel 10mm -n 20000");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(count_lines(r.out), 48);  // a header and the 47 materials
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_NE(line.find("reference (per channel)"), std::string::npos);
  while (std::getline(lines, line)) {
    const bool named = line.find("exact") != std::string::npos || line.find("montecarlo") != std::string::npos ||
                       line.find("pbd") != std::string::npos || line.find("quantized") != std::string::npos;
    EXPECT_TRUE(named) << line;
    if (line.rfind("Skin1", 0) == 0) {
      EXPECT_NE(line.find("exact,exact,exact"), std::string::npos) << line;
    }
    if (line.rfind("Spectralon", 0) == 0) {  // alpha' 1: the exact model continues to it
      EXPECT_NE(line.find("exact,exact,exact"), std::string::npos) << line;
    }
    if (line.rfind("Coke", 0) == 0) {  // alpha' below 0.001 and 0: the exact model continues there
      EXPECT_NE(line.find("exact,exact,exact"), std::string::npos) << line;
    }
    if (line.rfind("Strawberry Shampoo", 0) == 0) {  // channel B: g 0.994, continued beyond the last g node
      EXPECT_NE(line.find("exact,exact,exact"), std::string::npos) << line;
    }
  }
}
