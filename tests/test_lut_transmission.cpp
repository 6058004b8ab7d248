// --kind transmission: the multipole's totals exactly where it holds, decreasing with thickness,
// invalid thicknesses omitted with a note (or filled by the Monte Carlo reference), and the EXR /
// JSON / CSV files carry the values and attributes.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/lut/transmission_table.hpp"
#include "bssrdf/materials.hpp"
#include "cli_runner.hpp"
#include "exr_reader.hpp"

using namespace bssrdf;

namespace {

Medium skin() { return MaterialDatabase::load(default_materials_dir()).find("Skin1").medium; }

using test_cli::temp;

}  // namespace

TEST(TransmissionTable, MatchesTheMultipoleAndDecreasesWhereItHolds) {
  const auto medium = skin();
  const auto t = build_transmission_table(medium, log_spaced(0.2, 40.0, 24), {});
  ASSERT_GT(t.size(), 10u);
  ASSERT_FALSE(t.omitted_thickness.empty());  // thin slabs: the multipole is invalid there
  for (std::size_t j = 0; j < t.size(); ++j) {
    EXPECT_EQ(t.source[j], TransmissionSource::multipole);
    const multipole::Model model(t.thickness[j]);
    for (std::size_t c = 0; c < medium.channels(); ++c) {
      EXPECT_EQ(t.transmittance[c][j], model.total_transmittance(medium.reduced(c)));
      EXPECT_TRUE(multipole_invalid_code(model, medium.reduced(c)).empty());
      if (j > 0) {
        EXPECT_LT(t.transmittance[c][j], t.transmittance[c][j - 1]);
      }
    }
  }
  for (double d : t.omitted_thickness) EXPECT_LT(d, 2 * medium.reduced(0).ell + 1e-12);
  for (const auto& why : t.omitted_reason) EXPECT_NE(why.find("slab"), std::string::npos) << why;
}

TEST(TransmissionTable, ReferenceFillsInvalidThicknesses) {
  const auto medium = skin();
  TransmissionTableOptions o;
  o.reference = true;
  o.photons = 4000;
  const std::vector<double> d = {0.3, 1.0, 4.0};
  const auto t = build_transmission_table(medium, d, o);
  ASSERT_EQ(t.size(), 3u);
  EXPECT_TRUE(t.omitted_thickness.empty());
  EXPECT_EQ(t.source[0], TransmissionSource::monte_carlo);
  EXPECT_EQ(t.source[2], TransmissionSource::multipole);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_GT(t.transmittance[c][0], 0);
    EXPECT_LT(t.transmittance[c][0], 1);
    EXPECT_GT(t.standard_error[c][0], 0);
    EXPECT_LT(t.standard_error[c][0], 0.2 * t.transmittance[c][0]);
  }
}

// With adding-doubling the table records the solver's own accuracy per channel (the change of T when
// the angles are halved, largest over the thicknesses), and it bounds the actual error against a
// solve with far more angles; the multipole's table records none.
TEST(TransmissionTable, AddingDoublingRecordsItsOwnAccuracy) {
  const auto medium = skin();
  const std::vector<double> d{0.2, 1.0, 5.0};
  TransmissionTableOptions o;
  o.model = "adding-doubling";
  const auto t = build_transmission_table(medium, d, o);
  ASSERT_EQ(t.adding_doubling_error.size(), medium.channels());
  for (std::size_t c = 0; c < medium.channels(); ++c) {
    const double estimate = t.adding_doubling_error[c];
    EXPECT_GT(estimate, 0) << c;
    EXPECT_LT(estimate, 2e-4) << c;  // the solver's tolerance, 1e-4 of the incident flux
    adding_doubling::Options fine;
    fine.points = 128;
    double worst = 0;
    for (std::size_t j = 0; j < d.size(); ++j) {
      const auto a = adding_doubling::solve(adding_doubling::slab_of(LayerStack::slab(medium, d[j]), c),
                                            adding_doubling::Incidence::collimated, fine);
      const double reference = (a.total_transmittance - a.unscattered_transmittance) * a.entered_scale();
      worst = std::max(worst, std::abs(t.transmittance[c][j] - reference));
    }
    std::printf("  channel %zu: estimate %.3g, actual error against 128 angles %.3g\n", c, estimate, worst);
    EXPECT_LE(worst, estimate) << c;
  }
  o.model = "multipole";
  EXPECT_TRUE(build_transmission_table(medium, {3.0, 6.0}, o).adding_doubling_error.empty());
}

TEST(TransmissionTable, ExrJsonCsvCarryValuesAndAttributes) {
  const auto exr = temp("t.exr"), json = temp("t.json"), csv = temp("t.csv");
  for (const auto& path : {exr, json, csv}) {
    const auto r = test_cli::run(
        "lut --material Skin1 --kind transmission --model multipole --thickness 0.5,3,6,12 -q -o " + path.string());
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const auto t = test_exr::read_exr(exr);
  EXPECT_EQ(t.width, 3);  // 0.5 mm is omitted
  EXPECT_EQ(t.height, 1);
  EXPECT_EQ(t.channels.size(), 4u);
  EXPECT_EQ(t.strings.at("bssrdf:kind"), "transmission");
  EXPECT_EQ(t.strings.at("bssrdf:unit"), "mm");
  EXPECT_EQ(t.strings.at("bssrdf:ballistic_included"), "no");
  EXPECT_EQ(t.ints.at("bssrdf:omitted_count"), 1);
  EXPECT_NE(t.strings.at("bssrdf:omitted").find("0.5 mm"), std::string::npos);
  const auto medium = skin();
  for (int j = 0; j < 3; ++j) {
    const double d = t.channels.at("thickness")[j];
    EXPECT_FLOAT_EQ(d, (std::vector<float>{3, 6, 12}[j]));
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_FLOAT_EQ(t.channels.at(medium.channel_names[c])[j],
                      static_cast<float>(multipole::Model(d).total_transmittance(medium.reduced(c))));
  }
  const auto doc = nlohmann::json::parse(test_cli::slurp(json));
  EXPECT_EQ(doc["kind"], "transmission");
  EXPECT_EQ(doc["width"], 3);
  EXPECT_EQ(doc["attributes"]["bssrdf:omitted_count"], 1);
  const std::string text = test_cli::slurp(csv);  // "# model: multipole", then the header and rows
  EXPECT_EQ(text.substr(0, text.find('\n')), "# model: multipole");
  EXPECT_EQ(text.substr(text.find('\n') + 1, 17), "thickness,R,G,B\n3");
  // cm: thicknesses and the unit attribute follow --unit.
  const auto r =
      test_cli::run("lut --material Skin1 --kind transmission --unit cm --thickness 0.3,0.6 -q -o " + exr.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(test_exr::read_exr(exr).strings.at("bssrdf:unit"), "cm");
  EXPECT_FLOAT_EQ(test_exr::read_exr(exr).channels.at("thickness")[1], 0.6f);
}

TEST(TransmissionTable, BadInputIsOneLineExitTwoAndNoFile) {
  const auto out = temp("bad.exr");
  for (const std::string args :
       {"--thickness 0,1", "--thickness -1", "--thickness 0.1,0.2", "--d-min 2 --d-max 1", "--samples 1", "--model pbd",
        "--thickness 1 --d-min 1", "--reference --photons 10 --thickness 0.2"}) {
    std::filesystem::remove(out);
    const auto r =
        test_cli::run("lut --material Skin1 --kind transmission --model multipole " + args + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(test_cli::count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}
