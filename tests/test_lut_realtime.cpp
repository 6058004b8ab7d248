// Real-time forms: pre-integrated skin LUT, separable kernel, Gaussian mixtures, and the profile
// projections they rest on. Conservation is measured against independent integrals.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <set>

#include "bssrdf/error.hpp"
#include "bssrdf/exp_array.hpp"
#include "bssrdf/lut/gaussian_mixture_table.hpp"
#include "bssrdf/lut/penumbra_table.hpp"
#include "bssrdf/lut/preintegrated_table.hpp"
#include "bssrdf/lut/projected_profile.hpp"
#include "bssrdf/lut/separable_kernel.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model_choice.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/quantized_diffusion.hpp"
#include "cli_runner.hpp"
#include "exr_reader.hpp"

using namespace bssrdf;

namespace {

const Medium& material(const std::string& name) {
  static const auto db = MaterialDatabase::load(default_materials_dir());
  return db.find(name).medium;
}

using test_cli::temp;

// Light of a point source inside the band |X| < a, integrated directly in 2D: int 2 pi r R(r) P(r) dr
// with P the fraction of the circle of radius r inside the band (independent of the projections).
double band_energy(const Model& model, const Reduced<double>& m, double a) {
  double sum = 0;
  const double h = std::log(10.0) / 400;
  for (double u = std::log(1e-7 * m.ell); u < std::log(1e4 * m.ell); u += h) {
    const double r = std::exp(u);
    const double inside = r <= a ? 1.0 : 2 / std::numbers::pi * std::asin(a / r);
    sum += h * 2 * std::numbers::pi * r * r * model.reflectance(m, r) * inside;
  }
  return sum;
}

// The largest distance in ulps of y from the library's function at x; every one over 1 is a failure of its own.
template <class Library>
std::int64_t worst_ulps(const std::vector<double>& x, const std::vector<double>& y, Library library) {
  std::int64_t worst = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double e = library(x[k]);
    const auto ulps = std::abs(std::bit_cast<std::int64_t>(y[k]) - std::bit_cast<std::int64_t>(e));
    worst = std::max(worst, ulps);
    if (ulps > 1) ADD_FAILURE() << "x = " << x[k] << ": " << y[k] << " against " << e;
  }
  return worst;
}

}  // namespace

TEST(ProjectedProfile, ConservesTheTotalAndMatchesGaussianProjection) {
  for (const char* name : {"pbd", "better-dipole", "burley"}) {
    const auto model = make_model(name);
    for (std::size_t c = 0; c < 3; ++c) {
      const auto m = material("Skin1").reduced(c);
      const ProjectedProfile p(*model, m);
      EXPECT_NEAR(p.total(), model->total_reflectance(m), 2e-3 * p.total()) << name << c;
      EXPECT_LT(std::abs(p.conservation_error()), 1e-3) << name << c;
      EXPECT_NEAR(p.half_plane(-1e3), p.total(), 1e-9);
      // half_plane(x) against the direct 2D integral over the band.
      for (double a : {0.3, 1.0, 3.0})
        EXPECT_NEAR(p.strip(-a, a), band_energy(*model, m, a), 2e-3 * p.total()) << name << c << " a " << a;
    }
  }
  // Quantized diffusion is a sum of 2D Gaussians: its line projection is the sum of 1D Gaussians.
  const quantized_diffusion::Model q;
  const auto m = material("Skin1").reduced(0);
  const ProjectedProfile p(q, m);
  const auto mix = q.gaussians(m);
  for (double x : {0.01, 0.1, 1.0, 5.0}) {
    double expected = 0;
    for (std::size_t k = 0; k < mix.weight.size(); ++k)
      expected +=
          mix.weight[k] * std::exp(-x * x / (2 * mix.variance[k])) / std::sqrt(2 * std::numbers::pi * mix.variance[k]);
    EXPECT_NEAR(p.line(x), expected, 3e-3 * expected) << x;
  }
}

// The line projection against an exact one: quantized diffusion is a sum of 2D Gaussians, whose
// projections are 1D Gaussians. Inside five transport mfp, where the tables read it, line() holds to
// a few parts per million (measured 4.3e-6 at Ketchup's blue): the split of its integral into a rule
// in s near the line and a shared-weight rule in ln r beyond it costs no accuracy.
TEST(ProjectedProfile, LineMatchesAGaussianMixturesExactProjection) {
  const quantized_diffusion::Model q;
  for (const char* name : {"Skin1", "Marble", "Ketchup", "Apple"})
    for (std::size_t c = 0; c < 3; ++c) {
      const auto m = material(name).reduced(c);
      const ProjectedProfile p(q, m);
      const auto mix = q.gaussians(m);
      for (double x = 1e-3 * m.ell; x < 5 * m.ell; x *= 1.07) {
        double expected = 0;
        for (std::size_t k = 0; k < mix.weight.size(); ++k)
          expected += mix.weight[k] * std::exp(-x * x / (2 * mix.variance[k])) /
                      std::sqrt(2 * std::numbers::pi * mix.variance[k]);
        EXPECT_NEAR(p.line(x) / expected, 1.0, 1e-5) << name << " " << c << " x/ell " << x / m.ell;
      }
    }
}

TEST(PreintegratedTable, InUnitRangeAndFlatRowsTendToNDotL) {
  const auto model = make_model("pbd");
  PreintegratedOptions o;
  o.width = 64;
  o.height = 32;
  const auto t = build_preintegrated_table(material("Skin1"), *model, o);
  for (const auto& channel : t.value)
    for (double v : channel) {
      EXPECT_GE(v, 0);
      EXPECT_LE(v, 1);
    }
  // Flattest row (curvature c_max / 64): close to max(0, N.L); the difference grows with curvature.
  double flat = 0, curved = 0;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < o.width; ++i) {
      flat = std::max(flat, std::abs(t.value[c][i] - std::max(0.0, t.n_dot_l[i])));
      curved = std::max(curved, std::abs(t.value[c][(o.height - 1) * o.width + i] - std::max(0.0, t.n_dot_l[i])));
    }
  EXPECT_LT(flat, 5e-3);  // measured 3.1e-3 at the kink N.L = 0
  EXPECT_GT(curved, 0.05);
  // Rows increase with N.L; red (widest) wraps furthest into the shadow.
  for (std::size_t i = 1; i < o.width; ++i) EXPECT_GE(t.value[0][16 * o.width + i], t.value[0][16 * o.width + i - 1]);
  EXPECT_GT(t.value[0][31 * o.width + 10], t.value[2][31 * o.width + 10]);
  // A much smaller curvature range: every row close to max(0, N.L).
  o.curvature_max = 1e-3;
  const auto nearly_flat = build_preintegrated_table(material("Skin1"), *model, o);
  for (std::size_t i = 0; i < o.width; ++i)
    EXPECT_NEAR(nearly_flat.value[1][(o.height - 1) * o.width + i], std::max(0.0, t.n_dot_l[i]), 2e-3);
}

// Light at distance p from the centre of a penumbra of width w (a linear ramp of incident light),
// integrated directly in 2D from the model: int 2 pi r R(r) <L(p + r cos phi)>_phi dr / total.
double ramp_exitance(const Model& model, const Reduced<double>& m, double p, double w) {
  const auto light = [&](double X) { return std::clamp(X / w + 0.5, 0.0, 1.0); };
  double sum = 0, total = 0;
  const double h = std::log(10.0) / 200;
  for (double u = std::log(1e-7 * m.ell); u < std::log(1e4 * m.ell); u += h) {
    const double r = std::exp(u), ring = h * 2 * std::numbers::pi * r * r * model.reflectance(m, r);
    double mean = 0;
    for (int k = 0; k < 128; ++k) mean += light(p + r * std::cos(std::numbers::pi * (k + 0.5) / 128)) / 128;
    sum += ring * mean;
    total += ring;
  }
  return sum / total;
}

TEST(PenumbraTable, MatchesTheDirectConvolutionAndItsLimits) {
  const auto model = make_model("pbd");
  const auto& skin = material("Skin1");
  PenumbraOptions o;
  o.width = 33;  // column 16 is s = 1/2
  o.height = 16;
  const auto t = build_penumbra_table(skin, *model, o);
  EXPECT_NEAR(t.options.width_max, 8 * t.widest_r50, 1e-12);
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t j = 0; j < o.height; ++j) {
      EXPECT_NEAR(t.value[c][j * o.width + 16], 0.5, 1e-6) << c << ' ' << j;  // symmetry
      for (std::size_t i = 1; i < o.width; ++i) EXPECT_GE(t.value[c][j * o.width + i], t.value[c][j * o.width + i - 1]);
    }
    // Against the direct 2D integral at a few texels, narrow and wide penumbrae.
    for (std::size_t j : {0u, 5u, 15u})
      for (std::size_t i : {2u, 10u, 27u}) {
        const double w = t.penumbra_width[j], p = (t.shadow[i] - 0.5) * w;
        EXPECT_NEAR(t.value[c][j * o.width + i], ramp_exitance(*model, skin.reduced(c), p, w), 1e-4)
            << c << ' ' << i << ' ' << j;
      }
  }
  // Light scatters into the umbra side, red (widest) most; far wider penumbrae tend to D = s.
  EXPECT_GT(t.value[0][5 * o.width + 3], t.shadow[3]);
  EXPECT_GT(t.value[0][5 * o.width + 3], t.value[2][5 * o.width + 3]);
  o.width_max = 1e4;
  const auto wide = build_penumbra_table(skin, *model, o);
  for (std::size_t i = 0; i < o.width; ++i)
    EXPECT_NEAR(wide.value[1][(o.height - 1) * o.width + i], wide.shadow[i], 1e-3);
  // A channel without scattering passes the light ramp through: D = s.
  const auto coke = build_penumbra_table(material("Coke"), *model, o);
  for (std::size_t i = 0; i < o.width; ++i) EXPECT_EQ(coke.value[2][3 * o.width + i], coke.shadow[i]);
}

// The batch evaluations the tables use give the single evaluations' values, bitwise.
TEST(ProjectedProfile, BatchEvaluationsEqualSingleOnes) {
  const auto model = make_model("exact");
  const ProjectedProfile p(*model, material("Skin1").reduced(0));
  std::vector<double> x, ln_x;
  for (double v = 0.1 * p.r_min(); v < 10 * p.r_max(); v *= 1.37) {
    x.push_back(v);
    ln_x.push_back(std::log(v));
  }
  std::vector<double> line(x.size()), integral(x.size());
  p.lines(x.data(), ln_x.data(), line.data(), x.size());
  p.half_plane_integrals(x.data(), ln_x.data(), integral.data(), x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(line[k], p.line(x[k], ln_x[k])) << x[k];
    EXPECT_EQ(integral[k], p.half_plane_integral(x[k], ln_x[k])) << x[k];
  }
}

// Penner's ring integral evaluated directly at a few texels (a fine trapezoid over x in (-pi, pi) with the clamp
// applied pointwise): the table's prefix sums over node ranges must give the same D.
TEST(PreintegratedTable, MatchesTheDirectRingIntegral) {
  const auto model = make_model("exact");
  const auto& skin = material("Skin1");
  PreintegratedOptions o;
  o.width = 64;
  o.height = 16;
  const auto t = build_preintegrated_table(skin, *model, o);
  for (std::size_t c = 0; c < 3; ++c) {
    const ProjectedProfile p(*model, skin.reduced(c));
    for (std::size_t j : {0u, 7u, 15u}) {
      const double radius = 1 / t.curvature[j];
      for (std::size_t i : {3u, 20u, 31u, 32u, 45u, 63u}) {
        const double theta = std::acos(t.n_dot_l[i]);
        // Symmetric in x: integrate over (0, pi) with both clamps, geometric steps near 0 where the profile varies.
        double sum = 0, norm = 0;
        const auto add = [&](double x, double dx) {
          const double w = dx * p.line(2 * radius * std::sin(0.5 * x));
          sum += w * (std::max(0.0, std::cos(theta + x)) + std::max(0.0, std::cos(theta - x)));
          norm += 2 * w;
        };
        add(0.5e-9, 1e-9);
        for (double x = 1e-9; x < 0.05;) {  // midpoints of geometric cells up to 0.05, then uniform ones
          const double next = std::min(1.005 * x, 0.05);
          add(0.5 * (x + next), next - x);
          x = next;
        }
        const int n = 50000;
        for (int k = 0; k < n; ++k)
          add(0.05 + (std::numbers::pi - 0.05) * (k + 0.5) / n, (std::numbers::pi - 0.05) / n);
        EXPECT_NEAR(t.value[c][j * o.width + i], sum / norm, 1e-4) << c << ' ' << i << ' ' << j;
      }
    }
  }
}

// The ring integral's default quadrature against one 4x finer in both parts of x.
TEST(PreintegratedTable, QuadratureIsConverged) {
  const auto model = make_model("pbd");
  for (const char* name : {"Skin1", "Ketchup"}) {
    PreintegratedOptions o;
    o.width = 64;
    o.height = 32;
    const auto coarse = build_preintegrated_table(material(name), *model, o);
    o.ring_nodes_per_decade *= 4;
    o.ring_step /= 4;
    const auto fine = build_preintegrated_table(material(name), *model, o);
    double worst = 0;
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < coarse.value[c].size(); ++i)
        worst = std::max(worst, std::abs(coarse.value[c][i] - fine.value[c][i]));
    EXPECT_LT(worst, 5e-5) << name;
  }
  PreintegratedOptions bad;
  bad.ring_step = 0;
  EXPECT_THROW(bad.validate(), InvalidInput);
}

TEST(SeparableKernel, ConservesTheBandEnergyAndFollowsJimenez) {
  const auto model = make_model("pbd");
  const auto& medium = material("Skin1");
  EXPECT_EQ(jimenez_range(17), 2.0);
  EXPECT_EQ(jimenez_range(25), 3.0);
  for (int taps : {11, 17, 25}) {
    const auto k = build_separable_kernel(medium, *model, {taps, jimenez_range(taps)});
    EXPECT_FALSE(k.range_from_band);
    ASSERT_EQ(k.offset.size(), static_cast<std::size_t>(taps));
    EXPECT_EQ(k.offset[0], 0);
    EXPECT_EQ(k.offset[1], -1);
    EXPECT_EQ(k.offset.back(), 1);
    EXPECT_NEAR(k.offset[2], -std::pow(1 - 2.0 / (taps - 1), 2), 1e-12);  // quadratic warp
    for (std::size_t c = 0; c < 3; ++c) {
      double sum = 0, strip = 0;
      for (int i = 0; i < taps; ++i) sum += k.weight[c][i], strip += k.strip[c][i];
      EXPECT_NEAR(sum, 1, 1e-12);
      // Before normalisation: the light inside |x| < range, against the direct 2D integral.
      const double direct = band_energy(*model, medium.reduced(c), k.options.range);
      EXPECT_NEAR(strip / direct, 1, 2e-3) << taps << " " << c;
    }
  }
  // By default the range holds 95 % of the widest channel's light (red for skin), checked against
  // the direct 2D integral; the narrower channels hold more.
  const auto fitted = build_separable_kernel(medium, *model, {});
  EXPECT_TRUE(fitted.range_from_band);
  EXPECT_NEAR(
      band_energy(*model, medium.reduced(0), fitted.options.range) / model->total_reflectance(medium.reduced(0)), 0.95,
      2e-3);
  EXPECT_NEAR(fitted.captured[0], 0.95, 2e-3);
  EXPECT_GT(fitted.captured[1], 0.95);
  EXPECT_GT(fitted.captured[2], fitted.captured[1]);
  const auto tight = build_separable_kernel(medium, *model, {17, 0, 0.99});
  EXPECT_NEAR(tight.captured[0], 0.99, 2e-3);
  EXPECT_GT(tight.options.range, fitted.options.range);
  // A range far wider than the profile captures the whole total reflectance.
  const auto wide = build_separable_kernel(medium, *model, {25, 500});
  for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(wide.captured[c], 1, 2e-3);
}

// A channel without scattering (Coke's blue, sigma_s = 0) gets the identity kernel; the others are
// built as usual and the range comes from them.
TEST(SeparableKernel, ChannelWithoutScatteringGetsTheIdentity) {
  const auto model = make_model("pbd");
  const auto& coke = material("Coke");
  ASSERT_EQ(coke.reduced(2).sigma_s, 0);
  const auto k = build_separable_kernel(coke, *model, {});
  EXPECT_EQ(k.weight[2][0], 1);
  for (std::size_t i = 1; i < k.weight[2].size(); ++i) EXPECT_EQ(k.weight[2][i], 0);
  EXPECT_EQ(k.total_reflectance[2], 0);
  EXPECT_NEAR(k.captured[0], 0.95, 2e-3);
  double sum = 0;
  for (double w : k.weight[1]) sum += w;
  EXPECT_NEAR(sum, 1, 1e-12);
  Medium absorbing = coke;
  absorbing.sigma_s = {0, 0, 0};
  EXPECT_THROW(build_separable_kernel(absorbing, *model, {}), InvalidInput);
}

// The same limit in the other real-time forms: D = max(0, N.L) and zero weights for Coke's blue.
TEST(PreintegratedAndGaussians, ChannelWithoutScatteringTakesTheLimit) {
  const auto model = make_model("pbd");
  const auto& coke = material("Coke");
  PreintegratedOptions o;
  o.width = 32;
  o.height = 8;
  const auto t = build_preintegrated_table(coke, *model, o);
  for (std::size_t j = 0; j < o.height; ++j)
    for (std::size_t i = 0; i < o.width; ++i) EXPECT_EQ(t.value[2][j * o.width + i], std::max(0.0, t.n_dot_l[i]));
  EXPECT_GT(t.value[0][(o.height - 1) * o.width + 10], 0.01);  // red still wraps into the shadow
  const auto g = fitted_mixture_table(coke, *model, 4);
  for (double w : g.weight[2]) EXPECT_EQ(w, 0);
  EXPECT_LT(std::abs(g.conservation_error[0]), 1e-3);
  EXPECT_LT(g.relative_l2_error[0], 0.05);
}

TEST(GaussianMixtures, ConserveTheTotal) {
  const auto& medium = material("Skin1");
  const quantized_diffusion::Model q;
  const auto own = quantized_mixture_table(medium, q);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_LT(std::abs(own.conservation_error[c]), 1e-12);
    // Against an independent quadrature of its R(r).
    const ProjectedProfile p(q, medium.reduced(c));
    EXPECT_NEAR(p.total() / own.total_reflectance[c], 1, 1e-3);
  }
  const auto dipole = make_model("better-dipole");
  const auto fit = fitted_mixture_table(medium, *dipole, 6);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_LT(std::abs(fit.conservation_error[c]), 1e-4) << c;  // held to the model's total: measured < 1e-6
    EXPECT_LT(fit.relative_l2_error[c], 0.01) << c;
  }
  const auto pbd = make_model("pbd");
  const auto singular = fitted_mixture_table(medium, *pbd, 6);
  for (std::size_t c = 0; c < 3; ++c) {
    // Singular at r = 0: the sampled radii miss part of the energy, the total constraint restores it.
    EXPECT_LT(std::abs(singular.conservation_error[c]), 1e-4) << c;
    EXPECT_LT(singular.relative_l2_error[c], 0.02) << c;  // measured 1.5-1.9 %
  }
}

TEST(CliLutRealtime, FilesCarryValuesAndAttributes) {
  const auto pre = temp("pre.exr"), ker = temp("k.exr"), glsl = temp("k.glsl"), hlsl = temp("k.hlsl"),
             gauss = temp("g.exr"), gauss_json = temp("g.json");
  auto r = test_cli::run("lut --material Skin1 --kind preintegrated --size 32x8 -q -o " + pre.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto p = test_exr::read_exr(pre);
  EXPECT_EQ(p.width, 32);
  EXPECT_EQ(p.height, 8);
  EXPECT_EQ(p.channel_order, (std::vector<std::string>{"B", "G", "R"}));
  EXPECT_EQ(p.strings.at("bssrdf:kind"), "preintegrated");
  EXPECT_GT(p.doubles.at("bssrdf:curvature_max"), 0);
  PreintegratedOptions o;
  o.width = 32;
  o.height = 8;
  // The command's default model (the registry's: exact for Skin1).
  const auto t = build_preintegrated_table(material("Skin1"), *make_model(default_model(material("Skin1")).name), o);
  for (std::size_t i = 0; i < 256; ++i) EXPECT_FLOAT_EQ(p.channels.at("G")[i], static_cast<float>(t.value[1][i]));

  r = test_cli::run("lut --material Skin1 --kind separable --taps 11 --range jimenez -q -o " + ker.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto k = test_exr::read_exr(ker);
  EXPECT_EQ(k.width, 11);
  EXPECT_DOUBLE_EQ(k.doubles.at("bssrdf:range"), 2.0);
  EXPECT_EQ(k.strings.at("bssrdf:range_rule"), "given");
  EXPECT_EQ(k.ints.at("bssrdf:taps"), 11);
  EXPECT_EQ(k.channels.at("offset")[0], 0.0f);
  float sum = 0;
  for (float w : k.channels.at("R")) sum += w;
  EXPECT_NEAR(sum, 1, 1e-6);
  r = test_cli::run("lut --material Skin1 --kind separable --taps 11 --range 0.2 --unit cm -q -o " + glsl.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto g = test_cli::slurp(glsl);
  EXPECT_NE(g.find("const vec4 kernel[11] = vec4[11]("), std::string::npos) << g;
  EXPECT_NE(g.find("const float kernelRange = 0.2;  // cm"), std::string::npos) << g;
  r = test_cli::run("lut --material Skin1 --kind separable --taps 25 -q -o " + hlsl.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto h = test_cli::slurp(hlsl);
  EXPECT_NE(h.find("static const float4 kernel[25] = {"), std::string::npos) << h;
  EXPECT_NE(h.find(", -1.0)"), std::string::npos) << h;  // no bare integers

  r = test_cli::run("lut --material Skin1 --kind gaussians --model quantized -q -o " + gauss.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto q = test_exr::read_exr(gauss);
  EXPECT_EQ(q.channels.size(), 6u);  // variance.<c> and <c> per channel
  const quantized_diffusion::Model model;
  const auto mix = model.gaussians(material("Skin1").reduced(2));
  EXPECT_EQ(q.ints.at("bssrdf:count.B"), static_cast<int>(mix.weight.size()));
  EXPECT_FLOAT_EQ(q.channels.at("variance.B")[3], static_cast<float>(mix.variance[3]));
  EXPECT_FLOAT_EQ(q.channels.at("B")[3], static_cast<float>(mix.weight[3]));
  r = test_cli::run("lut --material Skin1 --kind gaussians --model better-dipole --count 4 -q -o " +
                    gauss_json.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto doc = nlohmann::json::parse(test_cli::slurp(gauss_json));
  EXPECT_EQ(doc["width"], 4);
  EXPECT_EQ(doc["channels"][0]["name"], "variance");
  EXPECT_LT(std::abs(doc["attributes"]["bssrdf:conservation_error.R"].get<double>()), 0.05);
}

TEST(CliLutRealtime, PenumbraExrReadsBack) {
  const auto file = temp("pen.exr");
  const auto r =
      test_cli::run("lut --material Skin1 --kind penumbra --size 32x8 --width-max 1 --unit cm -q -o " + file.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto p = test_exr::read_exr(file);
  EXPECT_EQ(p.width, 32);
  EXPECT_EQ(p.height, 8);
  EXPECT_EQ(p.strings.at("bssrdf:kind"), "penumbra");
  EXPECT_DOUBLE_EQ(p.doubles.at("bssrdf:width_max"), 1.0);  // in the output unit, cm
  PenumbraOptions o;
  o.width = 32;
  o.height = 8;
  o.width_max = 10;  // mm
  const auto t = build_penumbra_table(material("Skin1"), *make_model(default_model(material("Skin1")).name), o);
  for (std::size_t i = 0; i < 256; ++i) EXPECT_FLOAT_EQ(p.channels.at("R")[i], static_cast<float>(t.value[0][i]));
  // CSV for plots carries both axes: row, column, w (cm), s, then the channels.
  const auto csv = temp("pen.csv");
  ASSERT_EQ(
      test_cli::run("lut --material Skin1 --kind penumbra --size 32x8 --width-max 1 --unit cm -q -o " + csv.string())
          .status,
      0);
  const auto file_text = test_cli::slurp(csv);
  EXPECT_EQ(file_text.substr(0, file_text.find('\n')), "# model: exact");  // which model made it, first
  const std::string text = file_text.substr(file_text.find('\n') + 1);
  EXPECT_EQ(text.substr(0, text.find('\n')), "row,column,penumbra_width (cm),shadow,R,G,B");
  EXPECT_EQ(test_cli::count_lines(text), 1 + 256);
  EXPECT_NE(text.find("\n7,31,0.9375,0.984375,"), std::string::npos);  // w_7 = 1 cm * 7.5/8, s_31 = 31.5/32
}

TEST(CliLutRealtime, BadInputIsOneLineExitTwoAndNoFile) {
  const auto out = temp("bad.exr");
  for (const std::string args :
       {"--kind separable --taps 2", "--kind separable --taps 1", "--kind separable --taps 12",
        "--kind separable --range 0", "--kind separable --range wide", "--kind separable --band 1",
        "--kind preintegrated --size 0x0", "--kind preintegrated --size 0x16", "--kind preintegrated --size 16x0",
        "--kind preintegrated --size 16", "--kind preintegrated --curvature-max -1", "--kind penumbra --width-max -1",
        "--kind penumbra --size 1x16", "--kind gaussians --count -1", "--kind gaussians --count 40", "--kind unknown",
        "--kind radial --format glsl"}) {
    std::filesystem::remove(out);
    const auto r = test_cli::run("lut --material Skin1 " + args + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(test_cli::count_lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const auto r = test_cli::run("lut --material Skin1 --kind separable -o /nonexistent-dir/k.glsl");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(test_cli::count_lines(r.err), 1);
}

TEST(CliLutRealtime, PreviewIsAPngAndBadPathsWriteNothing) {
  const auto png = temp("skin.png");
  auto r = test_cli::run("lut --material Skin1 --preview " + png.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto bytes = test_cli::slurp(png);
  ASSERT_GT(bytes.size(), 100u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  for (const std::string& args :
       std::vector<std::string>{"--preview " + temp("x.jpg").string(), "--preview /nonexistent-dir/x.png",
                                "--sigma-a 0.1,0.2 --sigma-s 1,1 --preview " + temp("two.png").string()}) {
    r = test_cli::run("lut " + std::string(args.find("sigma") == std::string::npos ? "--material Skin1 " : "") + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(test_cli::count_lines(r.err), 1) << args;
  }
  EXPECT_FALSE(std::filesystem::exists(temp("x.jpg")));
  EXPECT_FALSE(std::filesystem::exists(temp("two.png")));
}

TEST(CliLutRealtime, BatchWritesEveryMaterialReproducibly) {
  // Coke and four others have a channel that does not scatter: it gets the identity kernel, and
  // every material is written.
  const auto dir = temp("batch");
  std::filesystem::create_directories(dir);
  const auto r = test_cli::run("lut --all --kind separable --taps 11 -f json -q --output-dir " + dir.string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 47u);
  EXPECT_TRUE(std::filesystem::exists(dir / "skin1-separable.json"));
  const auto coke = nlohmann::json::parse(test_cli::slurp(dir / "coke-separable.json"));
  EXPECT_EQ(coke["channels"][2]["name"], "B");
  EXPECT_EQ(coke["channels"][2]["values"][0], 1.0);
  // Built in parallel, the files are the same bytes.
  const auto parallel = temp("batch2");
  std::filesystem::create_directories(parallel);
  const auto r2 =
      test_cli::run("lut --all --kind separable --taps 11 -f json -q --threads 2 --output-dir " + parallel.string());
  EXPECT_EQ(r2.status, 0) << r2.err;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(test_cli::slurp(entry.path()), test_cli::slurp(parallel / entry.path().filename())) << entry.path();
}

TEST(CliLutRealtime, BatchStopsAtTheFirstFileItCannotWriteWhateverTheThreads) {
  // Files are written in database order while later materials are still being built: a file that
  // cannot be written (here a directory stands at Coke's name) stops the batch with one line, exit 2,
  // and leaves the same files at one thread and at two (those before Coke, nothing after it).
  std::vector<std::set<std::string>> written;
  for (const char* threads : {"1", "2"}) {
    const auto dir = temp(std::string("batch-stop") + threads);
    std::filesystem::create_directories(dir / "coke-separable.json");
    const auto r = test_cli::run("lut --all --kind separable --taps 11 -f json -q --threads " + std::string(threads) +
                                 " --output-dir " + dir.string());
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(test_cli::count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("coke-separable.json: cannot write: it is a directory"), std::string::npos) << r.err;
    auto& names = written.emplace_back();
    for (const auto& entry : std::filesystem::directory_iterator(dir)) names.insert(entry.path().filename().string());
  }
  EXPECT_EQ(written[0], written[1]);
  EXPECT_TRUE(written[0].count("apple-separable.json"));        // before Coke in the database
  EXPECT_FALSE(written[0].count("chardonnay-separable.json"));  // after Coke: the batch stopped there
}

TEST(CliLutRealtime, BatchSkipsWhatCannotBeTabulatedAndWritesTheRest) {
  // Spectralon's transport mfp is so short that every default thickness is a slab the multipole
  // refuses: the batch names it on stderr, one line, and still writes every other material.
  const auto dir = temp("batch-t");
  std::filesystem::create_directories(dir);
  const auto r =
      test_cli::run("lut --all --kind transmission --model multipole --samples 8 -f json -q --threads 2 --output-dir " +
                    dir.string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("bssrdf: skipped Spectralon: "), std::string::npos) << r.err;
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files + static_cast<std::size_t>(test_cli::count_lines(r.err)), 47u);
  EXPECT_GE(files, 45u);
  EXPECT_FALSE(std::filesystem::exists(dir / "spectralon-transmission.json"));
}

TEST(ExpArray, WithinOneUlpOfTheLibraryAndZeroBelowTheSmallestDouble) {
  // The projections' vectorised exponential against std::exp over its whole range, subnormal results
  // included; the ends as std::exp has them (0 at or below -745 by definition, where std::exp gives at
  // most the smallest subnormal).
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-744.9, 709.7);
  std::vector<double> x(1'000'000);
  for (auto& v : x) v = uniform(random);
  for (double v : {0.0, -0.0, 1e-300, -1e-17, 1.0, -1.0, 709.78, -708.4, -744.4, -744.99}) x.push_back(v);
  std::vector<double> y(x.size());
  exp_array(x.data(), y.data(), x.size());
  EXPECT_LE(worst_ulps(x, y, [](double v) { return std::exp(v); }), 1);
  const std::vector<double> ends{-745.0, -800.0, -INFINITY, 710.0, INFINITY, NAN};
  std::vector<double> end_values(ends.size());
  exp_array(ends.data(), end_values.data(), ends.size());
  EXPECT_EQ(end_values[0], 0.0);
  EXPECT_EQ(end_values[1], 0.0);
  EXPECT_EQ(end_values[2], 0.0);
  EXPECT_EQ(end_values[3], INFINITY);
  EXPECT_EQ(end_values[4], INFINITY);
  EXPECT_TRUE(std::isnan(end_values[5]));
}

TEST(LogArray, WithinOneUlpOfTheLibraryOverEveryExponentAndNearOne) {
  // The exact model's vectorised logarithm against std::log: log-uniform over the whole range (subnormal
  // arguments included), uniform near 1 (where ln x -> 0 and a careless split loses digits), the
  // significands either side of sqrt(2) (where the reduction switches exponent), and the ends.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> exponent(-1074.0, 1023.99), near_one(0.9, 1.1), unit(0.0, 1.0);
  std::vector<double> x;
  for (int k = 0; k < 500'000; ++k) x.push_back(std::exp2(exponent(random)));
  for (int k = 0; k < 400'000; ++k) x.push_back(near_one(random));
  for (int k = 0; k < 100'000; ++k)
    x.push_back(std::ldexp(std::sqrt(2.0) * (1 + 1e-6 * (unit(random) - 0.5)), k % 60 - 30));
  for (double v : {1.0, 2.0, 0.5, std::sqrt(2.0), std::sqrt(0.5), 4.9e-324, 2.2250738585072014e-308,
                   2.2250738585072009e-308, 1.7976931348623157e308, 1 + 0x1p-52, 1 - 0x1p-53})
    x.push_back(v);
  std::vector<double> y(x.size());
  log_array(x.data(), y.data(), x.size());
  EXPECT_LE(worst_ulps(x, y, [](double v) { return std::log(v); }), 1);
  const std::vector<double> ends{0.0, -0.0, -1.0, -INFINITY, INFINITY, NAN};
  std::vector<double> end_values(ends.size());
  log_array(ends.data(), end_values.data(), ends.size());
  EXPECT_EQ(end_values[0], -INFINITY);
  EXPECT_EQ(end_values[1], -INFINITY);
  EXPECT_TRUE(std::isnan(end_values[2]));
  EXPECT_TRUE(std::isnan(end_values[3]));
  EXPECT_EQ(end_values[4], INFINITY);
  EXPECT_TRUE(std::isnan(end_values[5]));
}
