// Colour from spectra (spectral/colour.hpp): the CIE tables' own checksums (illuminant white points of CIE 15:2004
// Table T.3), the colour spaces' published matrices, CIEDE2000 on the test pairs of Sharma, Wu and Dalal (2005),
// an independent colour summation, and the totals check of a colour-integrated profile.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bssrdf/error.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/spectral/colour.hpp"
#include "bssrdf/spectral/colour_profile.hpp"
#include "bssrdf/spectral/resample.hpp"
#include "cli_runner.hpp"
#include "exr_reader.hpp"
#include "spectral_medium.hpp"

namespace bssrdf::spectral {
namespace {

std::array<double, 2> chromaticity(const Vec3& xyz) {
  const double s = xyz[0] + xyz[1] + xyz[2];
  return {xyz[0] / s, xyz[1] / s};
}

TEST(Colour, IlluminantWhitePointsMatchCie15) {
  // CIE 15:2004 Table T.3, 2-degree observer (E by definition 1/3, 1/3 up to the tables' rounding).
  const struct {
    Illuminant illuminant;
    double x, y;
  } cases[] = {{Illuminant::d65, 0.31272, 0.32903},
               {Illuminant::d50, 0.34567, 0.35850},
               {Illuminant::a, 0.44757, 0.40745},
               {Illuminant::e, 1.0 / 3, 1.0 / 3}};
  for (const auto& c : cases) {
    const auto xy = chromaticity(white_xyz(c.illuminant));
    EXPECT_NEAR(xy[0], c.x, 5e-5) << to_string(c.illuminant);
    EXPECT_NEAR(xy[1], c.y, 5e-5) << to_string(c.illuminant);
  }
}

TEST(Colour, ObserverTableValues) {
  // CIE 15:2004 Table T.4 at 555 nm and 600 nm; between entries, linear.
  const auto at555 = observer(555);
  EXPECT_DOUBLE_EQ(at555[1], 1.0);
  EXPECT_NEAR(at555[0], 0.5120501, 1e-9);
  EXPECT_NEAR(observer(600)[0], 1.0622, 1e-9);
  EXPECT_NEAR(observer(555.5)[1], (1.0 + 0.9998567) / 2, 1e-9);
  EXPECT_EQ(observer(359)[1], 0.0);
  EXPECT_EQ(observer(831)[2], 0.0);
}

TEST(Colour, MatricesMatchPublishedOnes) {
  // IEC 61966-2-1 (sRGB: 4 decimals, derived from a rounded white, so within 4e-4 of the exact derivation), ACES
  // TB-2014-004 (AP1), ITU-R BT.2020 as published by their derivations.
  const Mat3 srgb{{{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}}};
  const Mat3 ap1{
      {{1.6410234, -0.3248033, -0.2364247}, {-0.6636629, 1.6153316, 0.0167563}, {0.0117219, -0.0082844, 0.9883949}}};
  const Mat3 bt2020{
      {{1.7166512, -0.3556708, -0.2533663}, {-0.6666844, 1.6164812, 0.0157685}, {0.0176399, -0.0427706, 0.9421031}}};
  const auto near = [](const Mat3& a, const Mat3& b, double tol, const char* what) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(a[i][j], b[i][j], tol) << what << " [" << i << "][" << j << "]";
  };
  near(xyz_to_rgb_matrix(ColourSpace::srgb), srgb, 4e-4, "sRGB");
  near(xyz_to_rgb_matrix(ColourSpace::acescg), ap1, 2e-6, "ACEScg");
  near(xyz_to_rgb_matrix(ColourSpace::rec2020), bt2020, 2e-6, "Rec.2020");
}

TEST(Colour, WhiteReflectorIsWhiteEverywhere) {
  const std::vector<double> grids[] = {{550}, {400, 500, 600, 700}, {380, 385, 390, 700, 780, 830}};
  for (const auto& grid : grids)
    for (auto illuminant : {Illuminant::d65, Illuminant::d50, Illuminant::a, Illuminant::e})
      for (auto space : {ColourSpace::srgb, ColourSpace::acescg, ColourSpace::rec2020}) {
        const ColourIntegrator colour(grid, {illuminant, space});
        const auto rgb = colour.rgb(std::vector<double>(grid.size(), 1.0));
        for (double v : rgb) EXPECT_NEAR(v, 1.0, 1e-12) << to_string(illuminant) << " " << to_string(space);
        EXPECT_NEAR(colour.xyz(std::vector<double>(grid.size(), 0.5))[1], 0.5, 1e-12);
      }
}

TEST(Colour, SampledSpectrumMatchesDirectSummation) {
  // A smooth reflectance sampled every 10 nm against the test's own 1 nm summation of the analytic spectrum: the
  // only difference is the linear interpolation between samples.
  const auto s = [](double nm) { return 0.2 + 0.5 * std::exp(-std::pow((nm - 600) / 60, 2)); };
  std::vector<double> grid, samples;
  for (double nm = 360; nm <= 830; nm += 10) grid.push_back(nm), samples.push_back(s(nm));
  const ColourIntegrator colour(grid, {Illuminant::d50, ColourSpace::srgb});
  Vec3 xyz{};
  double norm = 0;
  for (int nm = 360; nm <= 830; ++nm) {
    const auto c = observer(nm);
    const double S = illuminant_power(Illuminant::d50, nm);
    for (int k = 0; k < 3; ++k) xyz[k] += S * c[k] * s(nm);
    norm += S * c[1];
  }
  const auto ours = colour.xyz(samples);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(ours[k], xyz[k] / norm, 1e-3);
}

TEST(Colour, Ciede2000SharmaPairs) {
  // Sharma, Wu and Dalal (2005), Color Res. Appl. 30:21, Table 1: pairs 1, 2, 7, 17-20, 25.
  const struct {
    Vec3 a, b;
    double de;
  } pairs[] = {{{50, 2.6772, -79.7751}, {50, 0, -82.7485}, 2.0425},
               {{50, 3.1571, -77.2803}, {50, 0, -82.7485}, 2.8615},
               {{50, 0, 0}, {50, -1, 2}, 2.3669},
               {{50, 2.5, 0}, {73, 25, -18}, 27.1492},
               {{50, 2.5, 0}, {61, -5, 29}, 22.8977},
               {{50, 2.5, 0}, {56, -27, -3}, 31.9030},
               {{50, 2.5, 0}, {58, 24, 15}, 19.4535},
               {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644}};
  for (const auto& p : pairs) {
    EXPECT_NEAR(ciede2000(p.a, p.b), p.de, 1e-4);
    EXPECT_NEAR(ciede2000(p.b, p.a), p.de, 1e-4);
  }
}

TEST(Colour, SrgbTransferRoundTrips) {
  for (double v : {0.0, 0.02, 0.2, 0.5, 1.0}) EXPECT_NEAR(linear_to_srgb(srgb_to_linear(v)), v, 1e-12);
  EXPECT_NEAR(srgb_to_linear(0.5), 0.214041, 1e-6);
}

Medium spectral_medium(double step = 20) { return test_spectral::skin_like_medium(step); }

TEST(Colour, TotalsCheckOfTheIntegratedProfile) {
  // The RGB total of the integrated profile (2 pi r R_c(r) integrated over radius) equals the colour of the spectral
  // total reflectance, to 1e-4.
  const Medium m = spectral_medium();
  const auto model = make_model(default_model(m).name);
  std::vector<double> radii;
  for (int i = 0; i <= 6000; ++i) radii.push_back(1e-6 * std::pow(10.0, 8.0 * i / 6000));  // 1e-6 to 100 mm
  const auto spectral = compute_profile_report(m, *model, radii, LengthUnit::millimetre);
  const ColourSettings settings{Illuminant::d65, ColourSpace::srgb};
  const auto rgb = colour_profile(spectral, m.wavelength_nm, settings);
  ASSERT_EQ(rgb.channels.size(), 3u);
  std::vector<double> totals;
  for (const auto& ch : spectral.channels)
    totals.push_back(model->total_reflectance(m.reduced(&ch - &spectral.channels[0])));
  const auto expected = ColourIntegrator(m.wavelength_nm, settings).rgb(totals);
  for (int c = 0; c < 3; ++c) {
    const auto& p = rgb.channels[c].profile;
    double integral = 0;  // trapezoid in log r of 2 pi r^2 R(r), plus the disc below the first radius
    for (std::size_t i = 1; i < p.radius.size(); ++i)
      integral += 0.5 * (p.radius[i] * p.radius[i] * p.value[i] + p.radius[i - 1] * p.radius[i - 1] * p.value[i - 1]) *
                  std::log(p.radius[i] / p.radius[i - 1]) * 2 * M_PI;
    EXPECT_NEAR(integral, expected[c], 1e-4) << "RGB"[c];
    EXPECT_NEAR(rgb.channels[c].total_reflectance, expected[c], 1e-12) << "RGB"[c];
  }
  // Per radius, each wavelength's own profile: the red channel, made of the weakly absorbing long wavelengths, holds
  // less of its total within 1 mm than the blue one.
  const auto fraction_within = [&](int c, double r_max) {
    const auto& p = rgb.channels[c].profile;
    double sum = 0;
    for (std::size_t i = 1; i < p.radius.size() && p.radius[i] <= r_max; ++i)
      sum += 0.5 * (p.radius[i] * p.radius[i] * p.value[i] + p.radius[i - 1] * p.radius[i - 1] * p.value[i - 1]) *
             std::log(p.radius[i] / p.radius[i - 1]) * 2 * M_PI;
    return sum / rgb.channels[c].total_reflectance;
  };
  EXPECT_LT(fraction_within(0, 1.0), fraction_within(2, 1.0));
}

TEST(Colour, ResampleInterpolatesAndRefusesExtrapolation) {
  const Medium m = spectral_medium();
  const auto r = resample(m, {410, 700});
  EXPECT_NEAR(r.sigma_a[0], (m.sigma_a[0] + m.sigma_a[1]) / 2, 1e-12);
  EXPECT_EQ(r.channel_names[0], "410nm");
  EXPECT_THROW(resample(m, {390}), InvalidInput);
}

TEST(ColourCli, ProfileWritesColourChannelsAndMetadata) {
  const auto run = test_cli::run(
      "profile --wavelengths 450,550,650 --sigma-a 0.5,0.1,0.02 --sigma-s 10 --g 0.8 --eta 1.4 --colour acescg "
      "--illuminant d50 -f json --samples 8");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  ASSERT_EQ(doc["channels"].size(), 3u);
  EXPECT_EQ(doc["channels"][0]["name"], "R");
  EXPECT_EQ(doc["colour"]["illuminant"], "D50");
  EXPECT_EQ(doc["colour"]["space"], "ACEScg");
  EXPECT_EQ(doc["colour"]["wavelength_nm"].size(), 3u);
  EXPECT_FALSE(doc["channels"][0].contains("sigma_a"));
  // Without --colour the channels are the wavelengths.
  const auto plain = test_cli::run("profile --wavelengths 450,550,650 --sigma-a 0.5 --sigma-s 10 -f json --samples 8");
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(nlohmann::json::parse(plain.out)["channels"][2]["name"], "650nm");
}

TEST(ColourCli, BadInputIsOneLineAndStatusTwo) {
  for (const char* args : {"profile --wavelengths 450,550 --sigma-a 0.5 --sigma-s 10 --illuminant f2",
                           "profile --wavelengths 450,550 --sigma-a 0.5 --sigma-s 10 --colour xyz",
                           "profile --wavelengths 550,450 --sigma-a 0.5 --sigma-s 10",
                           "profile --wavelengths 450,550 --sigma-a 0.5,0.2,0.1 --sigma-s 10",
                           "profile --sigma-a 0.5 --sigma-s 10 --colour srgb", "profile -m Skin1 --wavelengths 500"}) {
    const auto run = test_cli::run(args);
    EXPECT_EQ(run.status, 2) << args << "\n" << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << "\n" << run.err;
    EXPECT_TRUE(run.out.empty()) << args;
  }
}

}  // namespace
}  // namespace bssrdf::spectral

namespace bssrdf::spectral {
namespace {

// A spectral materials file: read back, exported to pbrt-v4 as spectra, and round-tripped through the json export.
TEST(SpectralMaterials, LoadExportAndReload) {
  const auto dir = test_cli::scratch();
  const auto file = (dir / "spectral_materials.json").string();
  {
    std::ofstream out(file);
    out << R"({"format": "bssrdf-materials", "version": 1, "source": "test", "citation": "a test medium",
               "unit": "mm", "channels": ["450nm", "550nm", "650nm"], "wavelength_nm": [450, 550, 650],
               "materials": [{"name": "Tinted", "eta": 1.4, "sigma_a": [0.5, 0.1, 0.02],
                              "sigma_s": [12, 10, 8], "g": [0.8, 0.8, 0.8]}]})";
  }
  const auto pbrt = test_cli::run("materials export Tinted --db " + file + " --to pbrt-v4 --unit mm");
  ASSERT_EQ(pbrt.status, 0) << pbrt.err;
  EXPECT_NE(pbrt.out.find("\"spectrum sigma_a\" [ 450 0.5 550 0.1 650 0.02 ]"), std::string::npos) << pbrt.out;
  // sigma_s passes through single_g (one g per material), which may round in the last bit.
  EXPECT_NE(pbrt.out.find("\"spectrum sigma_s\" [ 450 12"), std::string::npos) << pbrt.out;
  const auto json = test_cli::run("materials export Tinted --db " + file + " --to json");
  ASSERT_EQ(json.status, 0) << json.err;
  const auto doc = nlohmann::json::parse(json.out);
  EXPECT_EQ(doc["wavelength_nm"], nlohmann::json({450, 550, 650}));
  // The material's colour profile: resampled to more wavelengths and integrated.
  const auto profile =
      test_cli::run("profile -m Tinted --db " + file + " --wavelengths 450,500,550,600,650 --colour srgb -f json");
  ASSERT_EQ(profile.status, 0) << profile.err;
  EXPECT_EQ(nlohmann::json::parse(profile.out)["colour"]["wavelength_nm"].size(), 5u);
}

}  // namespace
}  // namespace bssrdf::spectral

namespace bssrdf::spectral {
namespace {

// A spectral medium's radial table in OpenEXR: each wavelength's R(r) channel in the spectral layout of Fichet,
// Pacanowski and Wilkie (2021), "T.<nm with decimal comma>nm", with spectralLayoutVersion; read back by OpenEXR.
TEST(SpectralExr, RadialTableUsesTheSpectralLayout) {
  const auto file = (test_cli::scratch() / "spectral_radial.exr").string();
  const auto run = test_cli::run(
      "lut --wavelengths 450,550,650 --sigma-a 0.5,0.1,0.02 --sigma-s 10 --g 0.8 --eta 1.4 "
      "--kind radial -o " +
      file + " -q");
  ASSERT_EQ(run.status, 0) << run.err;
  const auto exr = test_exr::read_exr(file);
  std::vector<std::string> names;
  for (const auto& c : exr.channels) names.push_back(c.first);
  for (const char* expected : {"T.450,000000nm", "T.550,000000nm", "T.650,000000nm", "cdf.550nm"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  EXPECT_EQ(exr.strings.at("spectralLayoutVersion"), "1.0");
  EXPECT_EQ(exr.strings.at("bssrdf:wavelength_nm"), "450,550,650");
}

}  // namespace
}  // namespace bssrdf::spectral
