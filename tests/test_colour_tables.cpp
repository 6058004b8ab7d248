// The colour of the lookup tables that are not profiles: a spectral slab's transmittance in colour
// (spectral/colour_transmission.hpp) against the test's own colour weights (1 nm summation of the CIE tables over the
// linearly joined samples) applied to the tool's own per-wavelength table, the totals check of one thickness against
// an independent adding-doubling solve per wavelength; the colour preview's swatch against the colour of the totals;
// and the kinds that take no colour saying why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"
#include "bssrdf/io/png_image.hpp"
#include "bssrdf/layers.hpp"
#include "bssrdf/lut/material_preview.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/spectral/cie.hpp"
#include "bssrdf/spectral/colour.hpp"
#include "bssrdf/spectral/colour_medium.hpp"
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop
#include "cli_runner.hpp"
#include "spectral_medium.hpp"

namespace bssrdf::spectral {
namespace {

// Each sample's weight in X, Y, Z, computed here: the sample's hat function (1 at its wavelength, falling linearly to
// the neighbours, held at the end values beyond the first and last samples) summed every 1 nm over 360-830 nm against
// S(lambda) cbar(lambda), divided by the sum of S(lambda) ybar(lambda). XYZ -> RGB by the space's matrix after the
// Bradford adaptation (checked against the published matrices in tests/test_colour.cpp).
std::vector<Vec3> own_rgb_weights(const std::vector<double>& nm, Illuminant illuminant, ColourSpace space) {
  const auto hat = [&](std::size_t i, double x) {
    if (x <= nm.front()) return i == 0 ? 1.0 : 0.0;
    if (x >= nm.back()) return i + 1 == nm.size() ? 1.0 : 0.0;
    if (i > 0 && x > nm[i - 1] && x <= nm[i]) return (x - nm[i - 1]) / (nm[i] - nm[i - 1]);
    if (i + 1 < nm.size() && x >= nm[i] && x < nm[i + 1]) return (nm[i + 1] - x) / (nm[i + 1] - nm[i]);
    return 0.0;
  };
  double norm = 0;
  std::vector<Vec3> xyz(nm.size(), Vec3{});
  for (int l = 360; l <= 830; ++l) {
    const auto c = observer(l);
    const double S = illuminant_power(illuminant, l);
    norm += S * c[1];
    for (std::size_t i = 0; i < nm.size(); ++i)
      for (int k = 0; k < 3; ++k) xyz[i][k] += S * c[k] * hat(i, l);
  }
  Vec3 white{};
  for (int l = 360; l <= 830; ++l)
    for (int k = 0; k < 3; ++k) white[k] += illuminant_power(illuminant, l) * observer(l)[k] / norm;
  const auto matrix = xyz_to_rgb_matrix(space, white);
  std::vector<Vec3> out;
  for (auto& w : xyz) {
    for (auto& v : w) v /= norm;
    out.push_back(matrix * w);
  }
  return out;
}

nlohmann::json channel(const nlohmann::json& table, const std::string& name) {
  for (const auto& c : table["channels"])
    if (c["name"] == name) return c["values"];
  ADD_FAILURE() << "no channel " << name;
  return nlohmann::json::array();
}

std::string attribute(const nlohmann::json& table, const std::string& key) {
  return table["attributes"].contains(key) ? table["attributes"][key].get<std::string>() : std::string();
}

// The skin-like medium of tests/spectral_medium.hpp as command-line options.
std::string skin_like_options(double step) {
  const auto m = test_spectral::skin_like_medium(step);
  std::string nm = "--wavelengths ", sa = " --sigma-a ", ss = " --sigma-s ";
  for (std::size_t i = 0; i < m.channels(); ++i) {
    const std::string comma = i ? "," : "";
    nm += comma + format_number(m.wavelength_nm[i]);
    sa += comma + format_number(m.sigma_a[i]);
    ss += comma + format_number(m.sigma_s[i]);
  }
  return nm + sa + ss + " --g 0.8 --eta 1.4";
}

// The tool's colour table is the tool's own per-wavelength table integrated with weights computed here, thickness by
// thickness; and it records the colour.
TEST(ColourTransmission, IsEachWavelengthsTableIntegrated) {
  const std::string medium = test_spectral::kTintOptions + " --thickness 0.05,0.5,2,8";
  const auto spectral_path = test_cli::temp("spectral.json"), colour_path = test_cli::temp("colour.json");
  const auto spectral = test_cli::run("lut --kind transmission " + medium + " -q -o " + spectral_path.string());
  const auto colour = test_cli::run("lut --kind transmission " + medium + " --colour rec2020 --illuminant d50 -o " +
                                    colour_path.string());
  ASSERT_EQ(spectral.status, 0) << spectral.err;
  ASSERT_EQ(colour.status, 0) << colour.err;
  EXPECT_NE(colour.out.find("colour: Rec.2020 under D50"), std::string::npos) << colour.out;
  const auto s = nlohmann::json::parse(test_cli::slurp(spectral_path));
  const auto c = nlohmann::json::parse(test_cli::slurp(colour_path));
  const std::vector<double> nm{450, 500, 550, 600, 650};
  const auto w = own_rgb_weights(nm, Illuminant::d50, ColourSpace::rec2020);
  ASSERT_EQ(channel(c, "thickness"), channel(s, "thickness"));
  for (std::size_t j = 0; j < 4; ++j)
    for (int k = 0; k < 3; ++k) {
      double expected = 0;
      for (std::size_t i = 0; i < nm.size(); ++i)
        expected += w[i][k] * channel(s, format_number(nm[i]) + "nm")[j].get<double>();
      EXPECT_NEAR(channel(c, std::string(1, "RGB"[k]))[j].get<double>(), expected, 1e-9) << "RGB"[k] << " " << j;
    }
  EXPECT_EQ(attribute(c, "bssrdf:colour_space"), "Rec.2020");
  EXPECT_EQ(attribute(c, "bssrdf:colour_illuminant"), "D50");
  EXPECT_EQ(attribute(c, "bssrdf:colour_observer"), "CIE 1931 2-degree");
  EXPECT_EQ(attribute(c, "bssrdf:colour_wavelength_nm"), "450,500,550,600,650");
  EXPECT_EQ(attribute(c, "bssrdf:channels"), "R,G,B");
  EXPECT_NE(attribute(c, "bssrdf:colour").find("each wavelength's own slab (adding-doubling)"), std::string::npos);
  // The coefficients recorded are the medium's, per wavelength; not laid out as a spectral image (its channels are
  // colours).
  EXPECT_EQ(attribute(c, "bssrdf:wavelength_nm"), "");
  EXPECT_EQ(attribute(s, "bssrdf:wavelength_nm"), "450,500,550,600,650");
  // CSV: the colour line first after the model's.
  const auto csv_path = test_cli::temp("colour.csv");
  ASSERT_EQ(test_cli::run("lut --kind transmission " + medium + " --colour srgb -q -o " + csv_path.string()).status, 0);
  EXPECT_NE(test_cli::slurp(csv_path).find("\n# colour: linear sRGB under D65"), std::string::npos);
}

// Totals check: at one thickness, the colour table's R, G, B are the colour of each wavelength's diffuse transmittance
// solved here by adding-doubling (per entered flux, the unscattered beam removed), to 1e-4.
TEST(ColourTransmission, OneThicknessIsTheColourOfTheSpectralTotals) {
  const auto m = test_spectral::skin_like_medium(30);
  const double d = 1.5;
  const auto path = test_cli::temp("one.json");
  const auto run = test_cli::run("lut --kind transmission " + skin_like_options(30) + " --thickness " +
                                 format_number(d) + " --colour acescg -q -o " + path.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto table = nlohmann::json::parse(test_cli::slurp(path));
  std::vector<double> T;
  for (std::size_t i = 0; i < m.channels(); ++i) {
    adding_doubling::Options tight;
    tight.tolerance = 1e-6;
    const auto a = adding_doubling::solve(adding_doubling::slab_of(LayerStack::slab(m, d), i),
                                          adding_doubling::Incidence::collimated, tight);
    T.push_back((a.total_transmittance - a.unscattered_transmittance) * a.entered_scale());
  }
  const ColourIntegrator colour(m.wavelength_nm, {Illuminant::d65, ColourSpace::acescg});
  const auto rgb = colour.rgb(T);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(channel(table, std::string(1, "RGB"[k]))[0].get<double>(), rgb[k], 1e-4) << "RGB"[k];
    EXPECT_GT(rgb[k], 0.01);  // a real transmittance, not a vanishing one
  }
}

// Monte Carlo rows: the colour run is the same seed's spectral run integrated, errors as sqrt(sum w^2 se^2).
TEST(ColourTransmission, MonteCarloRowsAndErrorsCombine) {
  const std::string medium =
      test_spectral::kTintOptions + " --thickness 1 --model multipole --reference-everywhere --photons 2000";
  const auto spectral_path = test_cli::temp("mc.json"), colour_path = test_cli::temp("mc-colour.json");
  ASSERT_EQ(test_cli::run("lut --kind transmission " + medium + " -q -o " + spectral_path.string()).status, 0);
  ASSERT_EQ(test_cli::run("lut --kind transmission " + medium + " --colour srgb -q -o " + colour_path.string()).status,
            0);
  const auto s = nlohmann::json::parse(test_cli::slurp(spectral_path));
  const auto c = nlohmann::json::parse(test_cli::slurp(colour_path));
  const std::vector<double> nm{450, 500, 550, 600, 650};
  const auto w = own_rgb_weights(nm, Illuminant::d65, ColourSpace::srgb);
  for (int k = 0; k < 3; ++k) {
    double value = 0, variance = 0;
    for (std::size_t i = 0; i < nm.size(); ++i) {
      const std::string name = format_number(nm[i]) + "nm";
      value += w[i][k] * channel(s, name)[0].get<double>();
      variance += std::pow(w[i][k] * channel(s, "stderr." + name)[0].get<double>(), 2);
    }
    const std::string rgb(1, "RGB"[k]);
    EXPECT_NEAR(channel(c, rgb)[0].get<double>(), value, 1e-9) << rgb;
    EXPECT_NEAR(channel(c, "stderr." + rgb)[0].get<double>(), std::sqrt(variance), 1e-9) << rgb;
    EXPECT_GT(std::sqrt(variance), 0.0);
  }
}

// Thick slabs pass mostly deep red, outside linear sRGB: blue turns negative, recorded, not clipped.
TEST(ColourTransmission, NegativeColourIsRecordedNotClipped) {
  const auto path = test_cli::temp("thick.json");
  const auto run = test_cli::run("lut --kind transmission " + test_spectral::kTintOptions +
                                 " --thickness 1,20 --colour srgb -o " + path.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto table = nlohmann::json::parse(test_cli::slurp(path));
  EXPECT_LT(channel(table, "B")[1].get<double>(), 0.0);
  EXPECT_GT(channel(table, "B")[0].get<double>(), 0.0);
  EXPECT_NE(attribute(table, "bssrdf:colour").find("B < 0 from 20 mm"), std::string::npos)
      << attribute(table, "bssrdf:colour");
}

TEST(ColourTables, KindsWithoutColourSayWhyInOneLine) {
  for (const std::string& args :
       std::vector<std::string>{"lut --kind albedo-radius " + test_spectral::kTintOptions + " --colour srgb -o a.json",
                                "lut --kind transmission --sigma-a 0.1 --sigma-s 10 --colour srgb -o t.json"}) {
    const auto run = test_cli::run(args);
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_EQ(test_cli::count_lines(run.err), 1) << run.err;
    EXPECT_TRUE(run.out.empty()) << run.out;
  }
  EXPECT_NE(test_cli::run("lut --kind albedo-radius " + test_spectral::kTintOptions + " --colour srgb -o a.json")
                .err.find("one (g, eta) in no colour"),
            std::string::npos);
}

// The Monte Carlo radial table in colour: the same seed's per-wavelength bins integrated with the test's own weights,
// standard errors as sqrt(sum w^2 se^2), totals likewise; and a layer stack named by wavelength (skin --layers-out).
TEST(ColourReferenceTable, IsEachWavelengthsRunIntegrated) {
  const std::string args = "lut --kind radial --reference " + test_spectral::kTintOptions + " --photons 4000 -q -o ";
  const auto spectral_path = test_cli::temp("ref.json"), colour_path = test_cli::temp("ref-colour.json");
  ASSERT_EQ(test_cli::run(args + spectral_path.string()).status, 0);
  const auto run = test_cli::run(args + colour_path.string() + " --colour acescg --illuminant a");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto s = nlohmann::json::parse(test_cli::slurp(spectral_path));
  const auto c = nlohmann::json::parse(test_cli::slurp(colour_path));
  const std::vector<double> nm{450, 500, 550, 600, 650};
  const auto w = own_rgb_weights(nm, Illuminant::a, ColourSpace::acescg);
  const auto bins = channel(c, "radius").size();
  ASSERT_GT(bins, 10u);
  for (int k = 0; k < 3; ++k) {
    const std::string rgb(1, "RGB"[k]);
    for (std::size_t j = 0; j < bins; ++j) {
      double value = 0, variance = 0;
      for (std::size_t i = 0; i < nm.size(); ++i) {
        const std::string name = format_number(nm[i]) + "nm";
        value += w[i][k] * channel(s, name)[j].get<double>();
        variance += std::pow(w[i][k] * channel(s, "stderr." + name)[j].get<double>(), 2);
      }
      EXPECT_NEAR(channel(c, rgb)[j].get<double>(), value, 1e-9 * std::max(1.0, std::abs(value))) << rgb << j;
      EXPECT_NEAR(channel(c, "stderr." + rgb)[j].get<double>(), std::sqrt(variance), 1e-9 * std::max(1.0, value));
    }
    double total = 0;
    for (std::size_t i = 0; i < nm.size(); ++i)
      total += w[i][k] * s["attributes"]["bssrdf:total_reflectance." + format_number(nm[i]) + "nm"].get<double>();
    EXPECT_NEAR(c["attributes"]["bssrdf:total_reflectance." + rgb].get<double>(), total, 1e-9) << rgb;
  }
  EXPECT_EQ(attribute(c, "bssrdf:colour_space"), "ACEScg");
  EXPECT_EQ(attribute(c, "bssrdf:colour_illuminant"), "A");
  EXPECT_EQ(attribute(c, "bssrdf:channels"), "R,G,B");
  EXPECT_NE(attribute(c, "bssrdf:colour").find("each wavelength's own Monte Carlo run"), std::string::npos);

  // Far out, the skin-like medium's light is deep red: blue significantly negative in linear sRGB (from 2.05 mm, where
  // the integrated exact profiles turn negative too: ColourMedium::negative_from), named in the colour line.
  const auto far = test_cli::temp("skin-far.json");
  ASSERT_EQ(test_cli::run("lut --kind radial --reference " + skin_like_options(20) +
                          " --photons 20000 --colour srgb -q -o " + far.string())
                .status,
            0);
  const auto line = attribute(nlohmann::json::parse(test_cli::slurp(far)), "bssrdf:colour");
  EXPECT_NE(line.find("B < 0 beyond 2 standard errors"), std::string::npos) << line;
  EXPECT_EQ(line.find("R < 0"), std::string::npos) << line;

  const auto layers = test_cli::temp("skin-layers.json"), table = test_cli::temp("skin-ref.json");
  ASSERT_EQ(test_cli::run("skin --melanin 0.05 --wavelengths 450,550,650 --layers-out " + layers.string()).status, 0);
  const auto stack = test_cli::run("lut --kind radial --reference --layers " + layers.string() +
                                   " --photons 2000 --colour srgb -q -o " + table.string());
  ASSERT_EQ(stack.status, 0) << stack.err;
  const auto t = nlohmann::json::parse(test_cli::slurp(table));
  EXPECT_EQ(channel(t, "B").size(), channel(t, "radius").size());
  EXPECT_EQ(attribute(t, "bssrdf:colour_wavelength_nm"), "450,550,650");
  EXPECT_NE(attribute(t, "bssrdf:layers").find("(2 layers)"), std::string::npos);
}

// --pixel: a colour table's image error is judged against its colour model (each wavelength's profile integrated), so
// an interpolated radial table is within a fraction of a code value of it.
TEST(ColourTables, ImageErrorAgainstTheColourModel) {
  const auto path = test_cli::temp("pixel.json");
  const auto run =
      test_cli::run("lut " + test_spectral::kTintOptions + " --colour acescg --pixel 0.05 -q -o " + path.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto table = nlohmann::json::parse(test_cli::slurp(path));
  const double error = table["attributes"]["bssrdf:image_error"].get<double>();
  EXPECT_GT(error, 0.0);
  EXPECT_LT(error, 1.0);  // code values; measured 0.29
  EXPECT_EQ(attribute(table, "bssrdf:colour_space"), "ACEScg");
}

// The preview of a spectral medium: its colour in sRGB (each wavelength's profile summed with the colour weights).
struct Decoded {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;
  const unsigned char* at(int x, int y) const { return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 3; }
};

Decoded decode_png(const std::string& bytes) {
  Decoded out;
  int channels = 0;
  unsigned char* data = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                              static_cast<int>(bytes.size()), &out.width, &out.height, &channels, 3);
  if (!data) {
    ADD_FAILURE() << "not a PNG";
    return out;
  }
  out.pixels.assign(data, data + static_cast<std::size_t>(out.width) * out.height * 3);
  stbi_image_free(data);
  return out;
}

// A nearly grey medium: its colour profile stays inside linear sRGB over the preview's width.
const std::string kPaleOptions = "--wavelengths 450,550,650 --sigma-a 0.012,0.01,0.008 --sigma-s 10 --g 0.8 --eta 1.4";

TEST(ColourPreview, SwatchShowsTheColourOfTheTotals) {
  const auto png = test_cli::temp("pale.png");
  const auto run = test_cli::run("lut " + kPaleOptions + " --colour srgb --preview " + png.string());
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;  // nothing clipped
  const auto image = decode_png(test_cli::slurp(png));
  ASSERT_EQ(image.width, 512);
  // Far into the light, the surface shows the colour of the wavelengths' total reflectances (the model the preview
  // names: the registry's default for this medium).
  Medium m;
  m.wavelength_nm = {450, 550, 650};
  m.sigma_a = {0.012, 0.01, 0.008};
  m.sigma_s.assign(3, 10.0);
  m.g.assign(3, 0.8);
  m.eta = 1.4;
  m.channel_names = wavelength_channel_names(m.wavelength_nm);
  const auto model = make_model(default_model(m).name);
  std::vector<double> totals;
  for (std::size_t i = 0; i < 3; ++i) totals.push_back(model->total_reflectance(m.reduced(i)));
  const auto rgb = ColourIntegrator(m.wavelength_nm, {Illuminant::d65, ColourSpace::srgb}).rgb(totals);
  for (int k = 0; k < 3; ++k) {
    ASSERT_GT(rgb[k], 0.05);
    ASSERT_LT(rgb[k], 1.0);
    EXPECT_NEAR(image.at(0, 10)[k], to_srgb8(rgb[k]), 1) << "RGB"[k];
  }
  // The table's --colour does not change the preview: a preview is an sRGB image.
  const auto other = test_cli::temp("pale-acescg.png");
  ASSERT_EQ(test_cli::run("lut " + kPaleOptions + " --colour acescg --preview " + other.string()).status, 0);
  EXPECT_EQ(decode_png(test_cli::slurp(other)).pixels, image.pixels);
}

// Far from the edge a skin-like medium leaves deep red, outside linear sRGB: clipped in the image only, said in one
// stderr line and in the PNG's text.
TEST(ColourPreview, ClippingIsSaidOnStderrAndInThePng) {
  const auto png = test_cli::temp("skin.png"), table = test_cli::temp("skin.json");
  const auto run = test_cli::run("lut " + skin_like_options(20) + " --colour srgb --preview " + png.string() + " -o " +
                                 table.string() + " -q");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(test_cli::count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("clipped to [0, 1] in the image only"), std::string::npos) << run.err;
  const auto bytes = test_cli::slurp(png);
  EXPECT_NE(bytes.find(std::string("tEXtWarning\0preview: B outside linear sRGB", 41)), std::string::npos);
  EXPECT_NE(bytes.find("colour: linear sRGB under D65"), std::string::npos);
  EXPECT_EQ(decode_png(bytes).width, 512);
  // The table keeps the negative values: its colour line says so.
  EXPECT_NE(test_cli::slurp(table).find("B < 0 from"), std::string::npos);
}

// The library: display weights sum channels; the identity weights are the plain RGB preview.
TEST(ColourPreview, DisplayWeightsSumChannels) {
  const auto model = make_model("pbd");
  const auto m = test_spectral::tint_medium();
  const auto three = [&] {
    Medium rgb = m;
    rgb.wavelength_nm.clear();
    rgb.sigma_a.resize(3), rgb.sigma_s.resize(3), rgb.g.resize(3);
    rgb.channel_names = {"R", "G", "B"};
    return rgb;
  }();
  PreviewOptions o;
  const auto plain = render_material_preview(three, *model, o);
  o.display_weights = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_EQ(render_material_preview(three, *model, o).image.pixels, plain.image.pixels);
  EXPECT_THROW(render_material_preview(m, *model, o), InvalidInput);  // 5 channels, 3 weights
  EXPECT_THROW(render_material_preview(m, *model), InvalidInput);     // 5 channels, no weights
}

}  // namespace
}  // namespace bssrdf::spectral
