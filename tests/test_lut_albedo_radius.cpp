// The albedo-radius table: pbrt's layout reproduced exactly, degenerate cells finite, cells within
// the quadrature tolerance of the converged model, CDFs and effective albedos consistent, the
// albedo inversion round-trips, results independent of the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bssrdf/fresnel.hpp"
#include "bssrdf/lut/albedo_radius_table.hpp"
#include "bssrdf/lut/interpolation.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"
#include "bssrdf/models/photon_beam_diffusion.hpp"
#include "bssrdf/transport_total.hpp"

using namespace bssrdf;

TEST(AlbedoRadiusTable, PbrtLayoutIsExact) {
  const auto l = AlbedoRadiusLayout::pbrt();
  ASSERT_EQ(l.albedo.size(), 100u);
  ASSERT_EQ(l.radius.size(), 64u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(l.albedo[i], (1 - std::exp(-8.0 * i / 99.0)) / (1 - std::exp(-8.0)));
  EXPECT_EQ(l.albedo.front(), 0.0);
  EXPECT_DOUBLE_EQ(l.albedo.back(), 1.0);
  EXPECT_EQ(l.radius[0], 0.0);
  EXPECT_EQ(l.radius[1], 0.0025);
  for (int j = 2; j < 64; ++j) EXPECT_EQ(l.radius[j], l.radius[j - 1] * 1.2);
  EXPECT_NEAR(l.radius[63], 0.0025 * std::pow(1.2, 62), 1e-9);
}

TEST(AlbedoRadiusTable, CellsMatchTheConvergedModelAndAreFinite) {
  for (const auto& [g, eta] : {std::pair{0.0, 1.3}, std::pair{0.9, 1.4}, std::pair{0.0, 1.0}}) {
    AlbedoRadiusOptions options;
    options.tolerance = 1e-3;
    options.energy = RowEnergy::model;  // pbrt's construction: the cells are the model's
    const auto t = build_albedo_radius_table(AlbedoRadiusLayout::pbrt(), g, eta, options);
    const auto b = improved_boundary(eta);
    for (double v : t.profile) EXPECT_TRUE(std::isfinite(v));
    for (double v : t.cdf) EXPECT_TRUE(std::isfinite(v));
    for (std::size_t j = 0; j < t.columns(); ++j) EXPECT_EQ(t.profile[j], 0.0);             // albedo 0 row
    for (std::size_t i = 0; i < t.rows(); ++i) EXPECT_EQ(t.profile[i * t.columns()], 0.0);  // r = 0 column
    for (std::size_t i = 10; i < t.rows(); i += 11) {
      const double rho = t.layout.albedo[i];
      const auto m = reduce(1 - rho, rho, g, eta);
      double peak = 0;
      for (std::size_t j = 0; j < t.columns(); ++j) peak = std::max(peak, t.profile[i * t.columns() + j]);
      for (std::size_t j = 1; j < t.columns(); j += 3) {
        const double r = t.layout.radius[j];
        const double exact = 2 * std::numbers::pi * r * photon_beam_diffusion::reflectance(m, b, r, 512);
        if (exact < 1e-3 * peak) continue;
        EXPECT_NEAR(t.profile[i * t.columns() + j] / exact, 1.0, 1e-3) << g << ' ' << eta << ' ' << rho << ' ' << r;
      }
      EXPECT_NEAR(t.cdf[i * t.columns() + t.columns() - 1], 1.0, 1e-12);
      // rho_eff is the row's own Catmull-Rom integral (as pbrt's, consistent with the CDF): within
      // 2 % of the model's accurately integrated total (the grid ends at 203 mfp and is coarse there).
      const double total = photon_beam_diffusion::Model(1e-6).total_reflectance(m);
      // Above rho ~ 0.999 the profile reaches beyond the layout's 203 mfp and the row loses more.
      if (rho < 0.999) {
        EXPECT_NEAR(t.effective_albedo[i], total, 2e-2 * total + 1e-6) << rho;
      }
    }
    for (std::size_t i = 1; i < t.rows(); ++i) EXPECT_GT(t.effective_albedo[i], t.effective_albedo[i - 1]);
  }
}

// The default energy: each row's effective albedo is the radiative-transfer total (exact inside
// its domain, adding-doubling outside, 1 at rho = 1), never above 1 and increasing; pbd's single
// scattering (the exact integral) is left as it is, only its multiple scattering is scaled.
TEST(AlbedoRadiusTable, RowsCarryTheRadiativeTransferTotal) {
  for (const auto& [g, eta] : {std::pair{0.0, 1.3}, std::pair{0.9, 1.4}, std::pair{0.5, 1.0}}) {
    const auto t = build_albedo_radius_table(AlbedoRadiusLayout::pbrt(), g, eta, {});
    AlbedoRadiusOptions model_energy;
    model_energy.energy = RowEnergy::model;
    const auto model = build_albedo_radius_table(AlbedoRadiusLayout::pbrt(), g, eta, model_energy);
    EXPECT_EQ(t.rows_at_model_energy, 0u) << g << " " << eta;
    EXPECT_EQ(t.effective_albedo.back(), 1.0);  // rho = 1: no absorption
    // pbd's own (for contrast): 1.023 at g = 0, far below 1 at g = 0.9 (its tail passes 203 mfp).
    EXPECT_GT(std::abs(model.effective_albedo.back() - 1.0), 0.02) << g << " " << eta;
    for (std::size_t i = 1; i < t.rows(); ++i) {
      const auto total = transport_total(reduced_unit_extinction(t.layout.albedo[i], g, eta));
      EXPECT_NEAR(t.effective_albedo[i], total.value, 1e-9 * total.value) << g << " " << eta << " " << i;
      EXPECT_LE(t.effective_albedo[i], 1.0);
      EXPECT_GT(t.effective_albedo[i], t.effective_albedo[i - 1]) << i;
      EXPECT_NEAR(t.cdf[(i + 1) * t.columns() - 1], 1.0, 1e-12);
    }
    EXPECT_GT(std::max(1 - t.smallest_scale, t.largest_scale - 1), 0.05) << g << " " << eta;
    // At the smallest radius single scattering dominates: the cell changes far less than the row.
    const std::size_t mid = t.rows() / 2;
    EXPECT_NEAR(t.profile[mid * t.columns() + 1] / model.profile[mid * t.columns() + 1], 1.0, 0.05);
  }
}

// RowShape::exact: the rows inside the exact model's domain are its 2 pi r R, scaled so the row
// holds the row's total (the light beyond the table's last radius put back: up to ~1 % for the
// nearly conservative rows, whose tail decays as a power of r) within the Catmull-Rom truncation.
TEST(AlbedoRadiusTable, ExactRowsAreTheExactProfile) {
  AlbedoRadiusOptions options;
  options.shape = RowShape::exact;
  const double g = 0.6, eta = 1.33;
  const auto t = build_albedo_radius_table(AlbedoRadiusLayout::pbrt(), g, eta, options);
  const auto exact = make_model("exact");
  std::size_t inside = 0;
  const double r_max = t.layout.radius.back();
  for (std::size_t i = 1; i < t.rows(); ++i) {
    const auto m = reduced_unit_extinction(t.layout.albedo[i], g, eta);
    if (!exact_domain(bundled_exact_table(), m.albedo_prime, m.g, m.eta).empty()) continue;
    ++inside;
    const double put_back = exact->total_reflectance(m) / exact->cumulative_reflectance(m, r_max);
    for (std::size_t j = 1; j < t.columns(); j += 7) {
      const double r = t.layout.radius[j];
      const double want = 2 * std::numbers::pi * r * exact->reflectance(m, r) * put_back;
      if (r < 100) {
        EXPECT_NEAR(t.profile[i * t.columns() + j] / want, 1.0, 0.01) << i << " " << r;
      }
    }
  }
  EXPECT_EQ(t.exact_rows, inside);
  EXPECT_GE(inside, 98u);  // all but rho = 0 at g = 0.6 (the exact model continues to alpha' = 1)
}

TEST(AlbedoRadiusTable, AlbedoInversionRoundTrips) {
  const auto t = build_albedo_radius_table(AlbedoRadiusLayout::pbrt(), 0.0, 1.3, {});
  for (double rho : {0.05, 0.3, 0.5, 0.8, 0.95, 0.99, 0.999}) {
    const double rho_eff = interpolate(t.layout.albedo, t.effective_albedo, rho);
    EXPECT_NEAR(t.albedo_from_effective_albedo(rho_eff), rho, 1e-9) << rho;
  }
  EXPECT_EQ(t.albedo_from_effective_albedo(-1), 0.0);
  EXPECT_DOUBLE_EQ(t.albedo_from_effective_albedo(2), 1.0);
}

TEST(AlbedoRadiusTable, IndependentOfThreadsAndRejectsBadInput) {
  AlbedoRadiusOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const auto layout = AlbedoRadiusLayout::family(20, 16);
  EXPECT_EQ(build_albedo_radius_table(layout, 0.5, 1.4, one).profile,
            build_albedo_radius_table(layout, 0.5, 1.4, two).profile);
  AlbedoRadiusOptions bad;
  bad.tolerance = 0;
  EXPECT_ANY_THROW(build_albedo_radius_table(layout, 0.0, 1.3, bad));
  EXPECT_ANY_THROW(build_albedo_radius_table(layout, 1.0, 1.3, {}));
  EXPECT_ANY_THROW(AlbedoRadiusLayout::family(2, 16));
}
