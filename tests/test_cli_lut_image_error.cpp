// `bssrdf lut --pixel P [--tolerance T]`: every real-time table kind records how wrong it looks at
// that pixel size (bssrdf:image_error, code values against the model it tabulates), --tolerance
// sizes it (the smallest within), the size options override, and bad input exits 2 with no file.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using namespace bssrdf;
using test_cli::count_lines;
using test_cli::run;

namespace {

nlohmann::json attributes(const std::filesystem::path& file) {
  return nlohmann::json::parse(test_cli::slurp(file))["attributes"];
}

}  // namespace

TEST(CliLutImageError, SeparableTapsComeFromTheToleranceAndTapsOverride) {
  const auto file = test_cli::temp("kernel.json");
  auto r = run("lut --kind separable --material Skin1 --pixel 0.5 --tolerance 2 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  auto a = attributes(file);
  const int loose = a["bssrdf:taps"].get<int>();
  EXPECT_LE(a["bssrdf:image_error"].get<double>(), 2);
  EXPECT_EQ(a["bssrdf:image_error_pixel_mm"].get<double>(), 0.5);
  EXPECT_NE(a["bssrdf:sized_by"].get<std::string>().find("chosen for --tolerance 2"), std::string::npos);
  EXPECT_NE(r.out.find("image error at 0.5 mm pixels"), std::string::npos);
  r = run("lut --kind separable --material Skin1 --pixel 0.5 --tolerance 0.3 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  a = attributes(file);
  EXPECT_GE(a["bssrdf:taps"].get<int>(), loose);
  EXPECT_LE(a["bssrdf:image_error"].get<double>(), 0.3);
  // --taps overrides: 9 taps over the default band, and its (larger) error is stated.
  r = run("lut --kind separable --material Skin1 --pixel 0.5 --tolerance 2 --taps 9 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  a = attributes(file);
  EXPECT_EQ(a["bssrdf:taps"].get<int>(), 9);
  EXPECT_GT(a["bssrdf:image_error"].get<double>(), 2);
  EXPECT_FALSE(a.contains("bssrdf:sized_by"));
}

TEST(CliLutImageError, RadialGaussianAndPreintegratedTablesStateTheirError) {
  const auto file = test_cli::temp("table.json");
  auto r = run("lut --kind radial --material Ketchup --pixel 0.2 --tolerance 0.5 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LE(attributes(file)["bssrdf:image_error"].get<double>(), 0.5);
  // Without --tolerance the table is the default one, and still says how wrong it looks.
  r = run("lut --kind gaussians --material Ketchup --pixel 0.2 --count 2 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const double two = attributes(file)["bssrdf:image_error"].get<double>();
  r = run("lut --kind gaussians --material Ketchup --pixel 0.2 --count 6 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LT(attributes(file)["bssrdf:image_error"].get<double>(), two);
  r = run("lut --kind preintegrated --material Skin1 --pixel 1 --tolerance 1 -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto a = attributes(file);
  EXPECT_NE(a["bssrdf:sized_by"].get<std::string>().find("size "), std::string::npos);
  // The LUT carries no light across a shadow edge: at 1 mm Skin1's edge is tens of code values off.
  EXPECT_GT(a["bssrdf:image_error"].get<double>(), 10);
}

TEST(CliLutImageError, BadInputExitsTwoWithOneLineAndNoFile) {
  const auto file = test_cli::temp("bad.json");
  for (const std::string args :
       {"--kind separable --tolerance 2", "--kind separable --pixel 0", "--kind gaussians --pixel -1",
        "--kind preintegrated --pixel 1 --tolerance 0", "--kind radial --pixel 1 --tolerance x"}) {
    const auto r = run("lut --material Skin1 " + args + " -o " + file.string());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(file)) << args;
  }
}
