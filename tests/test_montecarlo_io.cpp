// The inputs of the Monte Carlo reference: layer stacks, the layer-stack JSON file and MCML .mci
// files. Malformed files must fail with FileError naming the file and the line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bssrdf/error.hpp"
#include "bssrdf/io/layers_json.hpp"
#include "bssrdf/io/mci.hpp"
#include "bssrdf/layers.hpp"

using namespace bssrdf;

namespace {

// Runs f, expects a FileError, returns it.
template <class F>
FileError file_error(F&& f) {
  try {
    f();
  } catch (const FileError& e) {
    return e;
  }
  ADD_FAILURE() << "no FileError thrown";
  return FileError("none", 0, "none");
}

LayerStack one_layer() {
  LayerStack s;
  s.channel_names = {"R", "G"};
  Layer l;
  l.sigma_a = {0.1, 0.2};
  l.sigma_s = {1, 2};
  l.g = {0, 0.5};
  l.n = 1.4;
  s.layers.push_back(l);
  return s;
}

const char* kGoodLayers = R"({
  "format": "bssrdf-layers",
  "version": 1,
  "unit": "cm",
  "ambient_above": 1.0,
  "ambient_below": 1.33,
  "channels": ["R", "G", "B"],
  "layers": [
    {"name": "epidermis", "thickness": 0.01, "n": 1.4,
     "sigma_a": [1, 2, 3], "sigma_s": 100, "g": [0.8]},
    {"name": "dermis", "thickness": null, "eta": 1.38,
     "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [50, 60, 70], "g": 0.9}
  ]
}
)";

}  // namespace

TEST(MonteCarloLayers, ValidStackPassesAndConvenienceBuildersMatchTheMedium) {
  EXPECT_NO_THROW(one_layer().validate());
  Medium m;
  m.channel_names = {"c0"};
  m.sigma_a = {0.5};
  m.sigma_s = {2};
  m.g = {0.3};
  m.eta = 1.3;
  const auto slab = LayerStack::slab(m, 2.0);
  EXPECT_EQ(slab.layers.size(), 1u);
  EXPECT_DOUBLE_EQ(slab.layers[0].n, 1.3);
  EXPECT_DOUBLE_EQ(slab.depth(), 2.0);
  EXPECT_FALSE(slab.semi_infinite());
  EXPECT_TRUE(LayerStack::half_space(m).semi_infinite());
}

TEST(MonteCarloLayers, ValidationNamesTheField) {
  auto s = one_layer();
  s.layers[0].sigma_a[1] = -1;
  try {
    s.validate();
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("layers[0].sigma_a[G]"), std::string::npos) << e.what();
  }
  s = one_layer();
  s.layers[0].g[0] = 1;
  EXPECT_THROW(s.validate(), InvalidInput);
  s = one_layer();
  s.layers.push_back(s.layers[0]);  // a semi-infinite layer that is not the last
  EXPECT_THROW(s.validate(), InvalidInput);
  s = one_layer();
  s.layers[0].sigma_a = {0, 0};
  s.layers[0].sigma_s = {0, 0};  // clear and semi-infinite: light would never stop
  EXPECT_THROW(s.validate(), InvalidInput);
  s.layers[0].thickness = 1;  // a clear finite layer (a glass slide) is fine
  EXPECT_NO_THROW(s.validate());
  s = one_layer();
  s.layers[0].sigma_s = {1};
  EXPECT_THROW(s.validate(), InvalidInput);
  s = one_layer();
  s.ambient_above = 0;
  EXPECT_THROW(s.validate(), InvalidInput);
}

TEST(MonteCarloLayersJson, ReadsAStackAndConvertsUnits) {
  const auto file = parse_layers_json(kGoodLayers, "skin.json");
  const auto& s = file.stack;
  EXPECT_EQ(file.unit, LengthUnit::centimetre);
  ASSERT_EQ(s.layers.size(), 2u);
  EXPECT_EQ(s.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_DOUBLE_EQ(s.ambient_below, 1.33);
  EXPECT_EQ(s.layers[0].name, "epidermis");
  EXPECT_DOUBLE_EQ(s.layers[0].thickness, 0.1);    // mm
  EXPECT_DOUBLE_EQ(s.layers[0].sigma_a[2], 0.3);   // 1/mm
  EXPECT_DOUBLE_EQ(s.layers[0].sigma_s[1], 10.0);  // one value for all channels
  EXPECT_DOUBLE_EQ(s.layers[0].g[2], 0.8);
  EXPECT_DOUBLE_EQ(s.layers[1].n, 1.38);  // "eta" is a synonym of "n"
  EXPECT_TRUE(s.semi_infinite());
}

// A layer without "n" gets soft tissue's index, not air's: a scattering layer at n = 1 would be
// index-matched to the ambient and reflect nothing at its surface.
TEST(MonteCarloLayersJson, IndexDefaultsToTissue) {
  const auto file = parse_layers_json(R"({"format": "bssrdf-layers", "version": 1, "unit": "mm",
    "layers": [{"thickness": 0.1, "sigma_a": 0.1, "sigma_s": 10}, {"n": 1.33, "sigma_a": 0.1, "sigma_s": 5}]})",
                                      "default.json");
  EXPECT_DOUBLE_EQ(file.stack.layers[0].n, 1.4);
  EXPECT_DOUBLE_EQ(file.stack.layers[1].n, 1.33);
  EXPECT_DOUBLE_EQ(file.stack.ambient_above, 1.0);
}

TEST(MonteCarloLayersJson, SyntaxErrorsNameFileAndLine) {
  std::string text = kGoodLayers;
  text.replace(text.find("\"sigma_s\": 100,"), 15, "\"sigma_s\": 100 ");  // missing comma, line 10
  const auto e = file_error([&] { parse_layers_json(text, "skin.json"); });
  EXPECT_EQ(e.file(), "skin.json");
  EXPECT_EQ(e.line(), 10) << e.what();
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
}

TEST(MonteCarloLayersJson, ValueErrorsNameFileLineAndField) {
  std::string text = kGoodLayers;
  text.replace(text.find("[0.1, 0.2, 0.3]"), 15, "[0.1, -0.2, 0.3]");  // line 12
  auto e = file_error([&] { parse_layers_json(text, "skin.json"); });
  EXPECT_EQ(e.line(), 12) << e.what();
  EXPECT_NE(std::string(e.what()).find("layers[1].sigma_a[G]"), std::string::npos) << e.what();

  text = kGoodLayers;
  text.replace(text.find("\"thickness\": 0.01"), 17, "\"thickness\": -1");  // line 9
  e = file_error([&] { parse_layers_json(text, "skin.json"); });
  EXPECT_EQ(e.line(), 9) << e.what();

  text = kGoodLayers;
  text.replace(text.find("\"g\": 0.9"), 8, "\"gg\": 0.9");  // unknown key (a typo), line 12
  e = file_error([&] { parse_layers_json(text, "skin.json"); });
  EXPECT_EQ(e.line(), 12) << e.what();
  EXPECT_NE(std::string(e.what()).find("unknown key 'gg'"), std::string::npos) << e.what();

  text = kGoodLayers;
  text.replace(text.find("[1, 2, 3]"), 9, "[1, 2]");  // wrong channel count, line 10
  e = file_error([&] { parse_layers_json(text, "skin.json"); });
  EXPECT_EQ(e.line(), 10) << e.what();

  text = kGoodLayers;
  text.replace(text.find("\"thickness\": 0.01"), 17, "\"thickness\": null");  // semi-infinite, not last
  e = file_error([&] { parse_layers_json(text, "skin.json"); });
  EXPECT_EQ(e.line(), 9) << e.what();

  e = file_error([&] { parse_layers_json(R"({"format": "other", "version": 1})", "x.json"); });
  EXPECT_EQ(e.line(), 1);
  e = file_error([&] { read_layers_json("/nonexistent/layers.json"); });
  EXPECT_EQ(e.line(), 0);
}

TEST(MonteCarloMci, ReadsTheReferenceFileInMillimetres) {
  const auto file = read_mci(std::string(BSSRDF_TEST_DATA) + "/mcml_semi_infinite_n1.4_g0.9.mci");
  ASSERT_EQ(file.runs.size(), 1u);
  const auto& run = file.runs[0];
  EXPECT_EQ(run.output_file, "caseD_semiinf_n14_g09.mco");
  EXPECT_EQ(run.photons, 5000000u);
  EXPECT_DOUBLE_EQ(run.dr, 0.02);
  EXPECT_DOUBLE_EQ(run.dz, 0.1);
  EXPECT_EQ(run.nr, 500);
  EXPECT_EQ(run.nz, 100);
  ASSERT_EQ(run.stack.layers.size(), 1u);
  const auto& l = run.stack.layers[0];
  EXPECT_DOUBLE_EQ(l.n, 1.4);
  EXPECT_DOUBLE_EQ(l.sigma_a[0], 0.1);  // 1/cm -> 1/mm
  EXPECT_DOUBLE_EQ(l.sigma_s[0], 10.0);
  EXPECT_DOUBLE_EQ(l.g[0], 0.9);
  EXPECT_DOUBLE_EQ(l.thickness, 100.0);
}

TEST(MonteCarloMci, MalformedFilesNameFileAndLine) {
  const std::string good =
      "1.0   # version\n"         // 1
      "2\n"                       // 2
      "a.mco A\n"                 // 3
      "1000\n"                    // 4
      "0.01 0.01\n"               // 5
      "10 10 1\n"                 // 6
      "2\n"                       // 7
      "1.0\n"                     // 8
      "1.5 0 0 0 0.1  # glass\n"  // 9
      "1.4 1 100 0.9 1\n"         // 10
      "1.0\n"                     // 11
      "\n"                        // 12
      "b.mco A\n"                 // 13
      "1000\n"                    // 14
      "0.01 0.01\n"               // 15
      "10 10 1\n"                 // 16
      "1\n"                       // 17
      "1.0\n"                     // 18
      "1.4 1 100 0.9 1\n"         // 19
      "1.0\n";                    // 20
  const auto file = parse_mci(good, "two.mci");
  ASSERT_EQ(file.runs.size(), 2u);
  EXPECT_EQ(file.runs[0].stack.layers.size(), 2u);
  EXPECT_TRUE(file.runs[0].stack.layers[0].clear(0));
  EXPECT_EQ(file.runs[1].line, 13);

  const auto replace_line = [&](int line, const std::string& with) {
    std::string text = good;
    std::size_t start = 0;
    for (int i = 1; i < line; ++i) start = text.find('\n', start) + 1;
    text.replace(start, text.find('\n', start) - start, with);
    return text;
  };
  auto e = file_error([&] { parse_mci(replace_line(10, "1.4 1 abc 0.9 1"), "two.mci"); });
  EXPECT_EQ(e.line(), 10) << e.what();
  EXPECT_EQ(e.file(), "two.mci");
  e = file_error([&] { parse_mci(replace_line(10, "1.4 1 100 0.9"), "two.mci"); });  // a value missing
  EXPECT_EQ(e.line(), 10) << e.what();
  e = file_error([&] { parse_mci(replace_line(19, "1.4 -1 100 0.9 1"), "two.mci"); });
  EXPECT_EQ(e.line(), 19) << e.what();
  e = file_error([&] { parse_mci(replace_line(16, "10 0 1"), "two.mci"); });
  EXPECT_EQ(e.line(), 16) << e.what();
  e = file_error([&] { parse_mci(replace_line(14, "12.5"), "two.mci"); });  // photons not an integer
  EXPECT_EQ(e.line(), 14) << e.what();
  e = file_error([&] { parse_mci(good.substr(0, good.find("1.0\n", good.find("b.mco"))), "two.mci"); });
  EXPECT_EQ(e.line(), 17) << e.what();  // truncated after line 17: the last line read is named
  EXPECT_NE(std::string(e.what()).find("end of file"), std::string::npos);
  e = file_error([&] { parse_mci(good + "junk\n", "two.mci"); });
  EXPECT_EQ(e.line(), 21) << e.what();
  e = file_error([&] { read_mci("/nonexistent/file.mci"); });
  EXPECT_EQ(e.line(), 0);
}
