// The real-time tables sized by the image-space error (image/realtime_tables.hpp): a screen-space
// tap kernel renders as a direct sum says, kernels and tables converge to the model they represent
// as they grow, and a tighter tolerance never buys a smaller table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "bssrdf/advise/advise.hpp"
#include "bssrdf/advise/advise_files.hpp"
#include "bssrdf/image/image_error.hpp"
#include "bssrdf/image/realtime_tables.hpp"
#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"

using namespace bssrdf;

namespace {

const Medium& material(const std::string& name) {
  static const auto database = MaterialDatabase::load_with_user("");
  return database.find(name).medium;
}

// The model as the reference, rendered on its annuli: what a table of that model converges to.
struct Judged {
  ReferenceProfiles reference;
  RealtimeJudge judge;
  const ImageErrorMeter& meter;
  Judged(const Medium& medium, const Model& model, double pixel)
      : reference(ModelReference(make_model(model.name())).profiles(medium)),
        judge(judge_against(medium, ModelReference(make_model(model.name())), pixel)),
        meter(judge.meter) {}
};

}  // namespace

// Each pixel of a tap kernel, summed directly: sum_i w_i I(x_k + o_i) with I linear between pixel
// centres (0 on the dark side, 1 on the lit one).
TEST(RealtimeTables, TapKernelImageIsTheDirectSumOfBilinearReads) {
  const std::vector<double> edges{0, 0.5, 1, 2, 4};
  const double pixel = 0.3;
  const ImageErrorMeter meter(edges, pixel);
  const std::vector<double> offset{0, -0.71, 0.71, -0.2, 0.2, -0.05, 0.45},
      weight{0.3, 0.05, 0.1, 0.15, 0.15, 0.1, 0.15};
  const PatternImage image = meter.render_taps(offset, weight, 0.6);
  ASSERT_EQ(image.edge.size(), 2 * meter.pixels_each_side());
  for (std::size_t k = 0; k < image.edge.size(); ++k) {
    const double x = meter.pixel_centre(k);
    double v = 0;
    for (std::size_t i = 0; i < offset.size(); ++i) {
      // Pixel centres at (j + 1/2) p hold 1 for j >= 0, 0 below.
      const double t = (x + offset[i]) / pixel - 0.5;  // in pixel-centre index units
      const double lower = std::floor(t), frac = t - lower;
      const auto value = [](double j) { return j >= 0 ? 1.0 : 0.0; };
      v += weight[i] * ((1 - frac) * value(lower) + frac * value(lower + 1));
    }
    EXPECT_NEAR(image.edge[k], 0.6 * v, 1e-12) << "pixel " << k;
    EXPECT_NEAR(image.line[k], image.edge[k] - (k > 0 ? image.edge[k - 1] : 0.0), 1e-15);
  }
  EXPECT_EQ(image.flat, 0.6);
}

// More taps approach the model's own image (the model as reference); the chosen kernel meets the
// tolerance, and a tighter tolerance needs at least as many taps.
TEST(RealtimeTables, SeparableKernelConvergesAndIsSizedByTheTolerance) {
  const auto model = make_model("pbd");
  const Judged j(material("Skin1"), *model, 0.2);
  const auto projections = project_channels(material("Skin1"), *model);
  double previous = INFINITY;
  for (int taps : {5, 17, 65, 255}) {
    SeparableKernelOptions options;
    options.taps = taps;
    options.band = 0.999;
    const double e =
        j.judge.error(render_separable(j.meter, build_separable_kernel(material("Skin1"), projections, options))).error;
    EXPECT_LT(e, previous) << taps << " taps";
    previous = e;
  }
  EXPECT_LT(previous, 2.0);
  const auto loose = choose_separable_kernel(material("Skin1"), projections, j.judge, 8);
  const auto tight = choose_separable_kernel(material("Skin1"), projections, j.judge, 3);
  ASSERT_TRUE(loose.meets_tolerance);
  ASSERT_TRUE(tight.meets_tolerance);
  EXPECT_LE(loose.image.error, 8);
  EXPECT_LE(tight.image.error, 3);
  EXPECT_LE(loose.options.taps, tight.options.taps);
  EXPECT_GT(tight.options.range, 0);
}

// A tolerance no kernel meets returns the most accurate one tried, flagged.
TEST(RealtimeTables, UnreachableToleranceReturnsTheMostAccurateFlagged) {
  const auto model = make_model("pbd");
  const Judged j(material("Ketchup"), *model, 0.01);
  const auto projections = project_channels(material("Ketchup"), *model);
  const auto choice = choose_separable_kernel(material("Ketchup"), projections, j.judge, 1e-6);
  EXPECT_FALSE(choice.meets_tolerance);
  EXPECT_GT(choice.image.error, 1e-6);
}

// The pre-integrated LUT's bilinear error against the table twice as fine falls with its size; on
// the flat patterns it is a Lambertian surface, so its error is at least nearly the Lambertian's.
TEST(RealtimeTables, PreintegratedTableErrorFallsWithSizeAndFlatPatternsAreLambertian) {
  const auto model = make_model("pbd");
  const Medium& skin = material("Skin1");
  const Judged j(skin, *model, 0.5);
  const auto projections = project_channels(skin, *model);
  std::vector<double> errors;
  double curvature_max = 0;
  for (std::size_t n : {16, 32, 64, 128}) {
    PreintegratedOptions o, f;
    o.width = o.height = n;
    o.curvature_max = curvature_max;
    const auto table = build_preintegrated_table(skin, projections, o);
    curvature_max = table.options.curvature_max;
    f.width = f.height = 2 * n;
    f.curvature_max = curvature_max;
    errors.push_back(preintegrated_table_error(table, build_preintegrated_table(skin, projections, f), j.judge.albedo));
  }
  for (std::size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], 0.7 * errors[i - 1]) << i;
  std::vector<AnnularProfile> lambertian;
  for (const auto& p : j.reference.channels) lambertian.push_back(point_profile(p.edges, p.total()));
  const double lambertian_error = j.judge.error(lambertian).error;
  const auto choice = choose_preintegrated_table(skin, projections, j.judge, 2);
  // It grows only while its interpolation is worse than both the tolerance and the flat patterns.
  EXPECT_LE(choice.table_error, std::max(2.0, choice.image.error));
  EXPECT_GE(choice.image.error, 0.9 * lambertian_error);
  EXPECT_FALSE(choice.meets_tolerance);  // a shadow edge at 0.5 mm needs transport across it
}

// Gaussian sums and radial tables: more terms, smaller errors; the chosen size is the first within.
TEST(RealtimeTables, GaussianCountAndRadialSizeAreTheSmallestWithinTolerance) {
  const auto model = make_model("better-dipole");
  const Medium& marble = material("Marble");
  const Judged j(marble, *model, 0.3);
  const auto radial = choose_radial_table_size(marble, *model, j.judge, 1);
  ASSERT_TRUE(radial.meets_tolerance);
  ASSERT_GT(radial.count, kRadialTableSizes.front());
  EXPECT_GT(j.judge.error(radial_table_profiles(marble, *model, radial.count / 2, j.meter.edges())).error, 1);
  const auto gaussians = choose_gaussian_count(marble, *model, j.judge, 5);
  if (gaussians.meets_tolerance && gaussians.count > 1) {
    EXPECT_GT(
        j.judge.error(gaussian_sum_profiles(marble, *model, static_cast<int>(gaussians.count) / 2, j.meter.edges()))
            .error,
        5);
  }
  EXPECT_GE(gaussians.image.error,
            choose_gaussian_count(marble, *model, j.judge, 1e-3).image.error - 1e-9);  // the most accurate
}

// advise() offers the separable kernel and the pre-integrated LUT with their chosen sizes, and
// --write of a chosen kernel writes those taps and that range, whose weights (read back from the
// JSON, rendered by a direct sum here) show the error the advice predicted.
TEST(RealtimeTables, AdvisedKernelIsWrittenWithItsTapsRangeAndError) {
  const Medium& skin = material("Skin1");
  const ModelReference reference(make_model("pbd"));
  AdviseOptions options;
  options.pixel = 1;
  options.tolerance = 5;
  Advice advice = advise(skin, reference, options);
  std::optional<std::size_t> kernel, lut;
  for (std::size_t i = 0; i < advice.candidates.size(); ++i) {
    if (advice.candidates[i].representation.rfind("separable-", 0) == 0) kernel = i;
    if (advice.candidates[i].representation.rfind("preintegrated-", 0) == 0) lut = i;
  }
  ASSERT_TRUE(kernel && lut);
  const auto& k = advice.candidates[*kernel];
  EXPECT_TRUE(k.meets_tolerance);
  EXPECT_EQ(k.representation, "separable-" + std::to_string(static_cast<int>(k.parameters[0].second)) + ":pbd");
  advice.choice = kernel;  // as if it were the cheapest
  const auto dir = std::filesystem::temp_directory_path() / "bssrdf_test_realtime_tables";
  std::filesystem::remove_all(dir);
  const auto path = write_advised_file(dir, "skin1", skin, std::nullopt, advice, {});
  std::ifstream in(path);
  const auto doc = nlohmann::json::parse(in);
  std::filesystem::remove_all(dir);
  const auto attribute = [&](const std::string& name) { return doc["attributes"][name]; };
  EXPECT_EQ(attribute("bssrdf:taps").get<int>(), static_cast<int>(k.parameters[0].second));
  EXPECT_NEAR(attribute("bssrdf:range").get<double>(), k.parameters[1].second, 1e-12);
  EXPECT_NEAR(attribute("bssrdf:image_error").get<double>(), k.image.error, 1e-12);
  // Independent of render_separable: the image from the file's weights and offsets, each pixel a
  // direct sum of bilinear reads, against the reference rendered by the meter.
  const ReferenceProfiles ref = reference.profiles(skin);
  const ImageErrorMeter meter(ref.channels.front().edges, options.pixel);
  double worst = 0;
  for (std::size_t c = 0; c < skin.channels(); ++c) {
    const auto& name = skin.channel_names[c];
    std::vector<double> w, o;
    for (const auto& ch : doc["channels"])
      if (ch["name"] == name)
        w = ch["values"].get<std::vector<double>>();
      else if (ch["name"] == "offset")
        o = ch["values"].get<std::vector<double>>();
    ASSERT_EQ(w.size(), o.size());
    const double albedo = attribute("bssrdf:total_reflectance." + name).get<double>(),
                 range = attribute("bssrdf:range").get<double>();
    const PatternImage r = meter.render(ref.channels[c]);
    for (std::size_t px = 0; px < r.edge.size(); ++px) {
      double v = 0;
      for (std::size_t i = 0; i < w.size(); ++i)
        v += w[i] * std::clamp((meter.pixel_centre(px) + o[i] * range) / options.pixel + 0.5, 0.0, 1.0);
      worst = std::max(worst, 255 * std::abs(srgb_encode(albedo * v) - srgb_encode(r.edge[px])));
    }
  }
  EXPECT_LE(worst, k.image.error + 1e-9);  // the edge pattern: the line and flat may be the worse
  EXPECT_GT(worst, 0.5 * k.image.error);
}
