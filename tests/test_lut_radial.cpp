// Radial lookup tables: the adaptive grid meets its tolerance against the model evaluated directly
// between the samples (several materials, models and tolerances); the CDF and inverse CDF agree;
// the OpenEXR file reads back (OpenEXR API) with the values and attributes written; exports are
// reproducible byte for byte.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/io/atomic_file.hpp"
#include "bssrdf/io/exr_table.hpp"
#include "bssrdf/lut/radial_table.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model_registry.hpp"

using namespace bssrdf;

namespace {

const MaterialDatabase& database() {
  static const auto db = MaterialDatabase::load(default_materials_dir());
  return db;
}

// Worst relative error of the table against the model at 7 points inside every interval, within
// each channel's checked range.
double worst_error_between_samples(const RadialTable& t, const Medium& medium, const Model& model) {
  double worst = 0;
  for (std::size_t c = 0; c < medium.channels(); ++c)
    for (std::size_t j = 0; j + 1 < t.size(); ++j)
      for (int k = 1; k < 8; ++k) {
        const double x0 = t.grid_coordinate(t.radius[j]), x1 = t.grid_coordinate(t.radius[j + 1]);
        const double x = x0 + (x1 - x0) * k / 8.0;
        // invert x(r) by bisection: the test must not share the table's Newton solver
        double lo = t.radius[j], hi = t.radius[j + 1];
        for (int i = 0; i < 100; ++i) (t.grid_coordinate(0.5 * (lo + hi)) < x ? lo : hi) = 0.5 * (lo + hi);
        const double r = 0.5 * (lo + hi);
        if (r < t.range_min[c] || r > t.range_max[c]) continue;
        const double exact = model.reflectance(medium.reduced(c), r);
        worst = std::max(worst, std::abs(t.interpolate(c, r) / exact - 1));
      }
  return worst;
}

}  // namespace

TEST(RadialTable, MeetsItsToleranceBetweenSamples) {
  for (const char* material : {"Skin1", "Marble", "Wholemilk", "Ketchup"})
    for (const char* model_name : {"pbd", "better-dipole", "burley"})
      for (double tolerance : {1e-2, 1e-3}) {
        const auto& medium = database().find(material).medium;
        const auto model = make_model(model_name);
        RadialTableOptions options;
        options.tolerance = tolerance;
        const auto t = build_radial_table(medium, *model, options);
        const double worst = worst_error_between_samples(t, medium, *model);
        // The check points are where Catmull-Rom's error peaks; allow 1.25x for points beside them.
        EXPECT_LE(worst, 1.25 * tolerance) << material << ' ' << model_name << ' ' << tolerance << " N=" << t.size();
        EXPECT_LE(t.max_error, tolerance);
        SCOPED_TRACE(material);
        for (std::size_t c = 0; c < medium.channels(); ++c) {
          EXPECT_NEAR(t.cdf[c].back(), 1.0, 1e-12);
          for (std::size_t j = 1; j < t.size(); ++j) EXPECT_GE(t.cdf[c][j], t.cdf[c][j - 1]);
          // The range holds the requested energy: the table holds at least that much of the total.
          EXPECT_GE(t.table_reflectance[c] / t.total_reflectance[c], options.energy - 1e-3);
        }
      }
}

// The table is the smallest that meets its tolerance, to within the search's 3 %: the same grid
// with 4 % fewer radii, evaluated from the model directly, misses it somewhere in the range.
TEST(RadialTable, FourPercentFewerRadiiMissTheTolerance) {
  for (const char* material : {"Skin1", "Ketchup", "Marble"})
    for (const char* model_name : {"pbd", "better-dipole"}) {
      const auto& medium = database().find(material).medium;
      const auto model = make_model(model_name);
      const auto t = build_radial_table(medium, *model, {});
      const std::size_t n = t.size() * 96 / 100;
      const double x0 = t.grid_coordinate(t.radius.front()), x1 = t.grid_coordinate(t.radius.back());
      const auto radius_at = [&](double x) {
        double lo = t.radius.front() * 0.5, hi = t.radius.back() * 2;
        for (int i = 0; i < 200; ++i) (t.grid_coordinate(0.5 * (lo + hi)) < x ? lo : hi) = 0.5 * (lo + hi);
        return 0.5 * (lo + hi);
      };
      std::vector<double> x(n);
      for (std::size_t j = 0; j < n; ++j) x[j] = x0 + (x1 - x0) * static_cast<double>(j) / static_cast<double>(n - 1);
      double worst = 0;
      for (std::size_t c = 0; c < medium.channels(); ++c) {
        std::vector<double> R(n);
        for (std::size_t j = 0; j < n; ++j) R[j] = model->reflectance(medium.reduced(c), radius_at(x[j]));
        for (std::size_t j = 0; j + 1 < n; ++j)
          for (double k : kCheckPoint) {
            const double xc = x[j] + k * (x[j + 1] - x[j]), r = radius_at(xc);
            if (r < t.range_min[c] || r > t.range_max[c]) continue;
            worst = std::max(worst, std::abs(interpolate(x, R, xc) / model->reflectance(medium.reduced(c), r) - 1));
          }
      }
      EXPECT_GT(worst, t.options.tolerance) << material << ' ' << model_name << " N=" << t.size() << " -> " << n;
    }
}

TEST(RadialTable, TighterToleranceNeedsMoreSamplesAndLinearMoreThanCubic) {
  const auto& medium = database().find("Skin1").medium;
  const auto model = make_model("better-dipole");
  RadialTableOptions loose, tight, linear;
  loose.tolerance = 1e-2;
  tight.tolerance = 1e-4;
  linear.tolerance = 1e-2;
  linear.interpolation = Interpolation::linear;
  const auto a = build_radial_table(medium, *model, loose), b = build_radial_table(medium, *model, tight),
             c = build_radial_table(medium, *model, linear);
  EXPECT_LT(a.size(), b.size());
  EXPECT_LT(a.size(), c.size());
  EXPECT_LE(worst_error_between_samples(b, medium, *model), 1.25e-4);
  EXPECT_LE(worst_error_between_samples(c, medium, *model), 1e-2);
}

// Coke's blue channel does not scatter (sigma_s = 0): R = 0 there, all of its CDF at r = 0, and
// the grid is built for the other channels; a medium that scatters nowhere is refused.
TEST(RadialTable, ChannelWithoutScatteringIsZeroAndDoesNotShapeTheGrid) {
  const auto& coke = database().find("Coke").medium;
  const auto model = make_model("pbd");
  const auto t = build_radial_table(coke, *model, {});
  EXPECT_EQ(t.total_reflectance[2], 0);
  EXPECT_EQ(t.table_reflectance[2], 0);
  EXPECT_EQ(t.range_max[2], 0);
  for (std::size_t j = 0; j < t.size(); ++j) {
    EXPECT_EQ(t.reflectance[2][j], 0);
    EXPECT_EQ(t.cdf[2][j], 1);
    EXPECT_EQ(t.inverse_cdf[2][j], 0);
  }
  EXPECT_EQ(t.radius.front(), std::min(t.range_min[0], t.range_min[1]));
  EXPECT_LE(worst_error_between_samples(t, coke, *model), 1.25e-3);
  Medium absorbing = coke;
  absorbing.sigma_s = {0, 0, 0};
  EXPECT_THROW(build_radial_table(absorbing, *model, {}), InvalidInput);
}

TEST(RadialTable, InverseCdfInvertsTheCdf) {
  const auto& medium = database().find("Skin1").medium;
  const auto t = build_radial_table(medium, *make_model("pbd"), {});
  std::vector<double> x;
  for (double r : t.radius) x.push_back(t.grid_coordinate(r));
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t j = 1; j + 1 < t.size(); j += 7) {
      const double r = t.inverse_cdf[c][j];
      const double cdf = interpolate(x, t.cdf[c], t.grid_coordinate(r), Interpolation::linear);
      EXPECT_NEAR(cdf, t.u[j], 2e-3) << c << ' ' << j;
    }
}

TEST(RadialTable, ExrReadsBackWithValuesAndAttributes) {
  const auto& material = database().find("Skin1");
  const auto model = make_model("pbd");
  const auto t = build_radial_table(material.medium, *model, {});
  const auto table = to_lookup_table(t, {material, &material.medium, model.get(), LengthUnit::millimetre});
  const auto path = std::filesystem::temp_directory_path() / ("bssrdf-lut-" + std::to_string(::getpid()) + ".exr");
  const auto bytes = encode_exr(table);
  write_file_atomically(path, bytes);
  EXPECT_EQ(bytes, encode_exr(to_lookup_table(build_radial_table(material.medium, *model, {}),
                                              {material, &material.medium, model.get(), LengthUnit::millimetre})));

  Imf::InputFile file(path.c_str());
  const auto& header = file.header();
  const auto dw = header.dataWindow();
  const int width = dw.max.x - dw.min.x + 1;
  ASSERT_EQ(width, static_cast<int>(t.size()));
  ASSERT_EQ(dw.max.y - dw.min.y + 1, 1);
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"bssrdf:material", "Skin1"},
                                                        {"bssrdf:model", "pbd"},
                                                        {"bssrdf:unit", "mm"},
                                                        {"bssrdf:kind", "radial"},
                                                        {"bssrdf:tool", std::string("bssrdf ") + BSSRDF_VERSION}}) {
    const auto* a = header.findTypedAttribute<Imf::StringAttribute>(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->value(), value);
  }
  for (const char* name : {"bssrdf:normalization", "bssrdf:distance", "bssrdf:grid", "bssrdf:interpolation"})
    EXPECT_NE(header.findTypedAttribute<Imf::StringAttribute>(name), nullptr) << name;
  EXPECT_DOUBLE_EQ(header.findTypedAttribute<Imf::DoubleAttribute>("bssrdf:tolerance")->value(), 1e-3);
  EXPECT_EQ(header.findTypedAttribute<Imf::IntAttribute>("bssrdf:size")->value(), width);
  EXPECT_DOUBLE_EQ(header.findTypedAttribute<Imf::DoubleAttribute>("bssrdf:total_reflectance.R")->value(),
                   t.total_reflectance[0]);

  for (const char* name : {"R", "G", "B", "radius", "ring.R", "cdf.G", "inverse_cdf.B", "u"})
    ASSERT_NE(header.channels().findChannel(name), nullptr) << name;
  std::vector<float> R(width), radius(width), ring(width), cdf(width);
  Imf::FrameBuffer frame;
  frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(R.data()), sizeof(float), 0));
  frame.insert("radius", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(radius.data()), sizeof(float), 0));
  frame.insert("ring.R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(ring.data()), sizeof(float), 0));
  frame.insert("cdf.B", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(cdf.data()), sizeof(float), 0));
  file.setFrameBuffer(frame);
  file.readPixels(dw.min.y, dw.max.y);
  for (int j = 0; j < width; ++j) {
    EXPECT_EQ(R[j], static_cast<float>(t.reflectance[0][j]));
    EXPECT_EQ(radius[j], static_cast<float>(t.radius[j]));
    EXPECT_EQ(ring[j], static_cast<float>(t.ring[0][j]));
    EXPECT_EQ(cdf[j], static_cast<float>(t.cdf[2][j]));
  }
  std::filesystem::remove(path);
}

TEST(RadialTable, JsonCarriesTheSameContentInTheOutputUnit) {
  const auto& material = database().find("Marble");
  const auto model = make_model("better-dipole");
  const auto t = build_radial_table(material.medium, *model, {});
  const auto doc = nlohmann::json::parse(
      to_json(to_lookup_table(t, {material, &material.medium, model.get(), LengthUnit::centimetre})));
  EXPECT_EQ(doc["kind"], "radial");
  EXPECT_EQ(doc["attributes"]["bssrdf:unit"], "cm");
  EXPECT_EQ(doc["width"], t.size());
  for (const auto& c : doc["channels"]) {
    if (c["name"] == "radius") {
      EXPECT_NEAR(c["values"][3].get<double>(), t.radius[3] / 10, 1e-15);
    }
    if (c["name"] == "R") {
      EXPECT_NEAR(c["values"][3].get<double>(), t.reflectance[0][3] * 100, 1e-12 * t.reflectance[0][3] * 100);
    }
  }
}

TEST(RadialTable, RejectsBadOptions) {
  const auto& medium = database().find("Skin1").medium;
  RadialTableOptions o;
  o.tolerance = 0;
  EXPECT_THROW(build_radial_table(medium, *make_model("dipole"), o), InvalidInput);
  o.tolerance = 1e-3;
  o.energy = 1;
  EXPECT_THROW(build_radial_table(medium, *make_model("dipole"), o), InvalidInput);
}
