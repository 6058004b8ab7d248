// Fresnel reflectance and its angular moments C_n = int_0^1 F(mu) mu^n dmu: the exact moments by
// quadrature of the unpolarised Fresnel formula, to five decimals, and d'Eon & Irving's (2011,
// "A quantized-diffusion model for rendering translucent materials", Appendix) polynomial fits of
// 2C1 and 3C2 in eta, tabulated below.
#include <gtest/gtest.h>

#include <cmath>

#include "bssrdf/fresnel.hpp"

using namespace bssrdf;

TEST(Fresnel, NormalIncidenceIsTheSpecularFormula) {
  for (double eta : {1.0, 1.33, 1.4, 1.5, 2.0, 0.75}) {
    const double rsp = std::pow((eta - 1) / (eta + 1), 2);
    EXPECT_NEAR(fresnel_reflectance(1.0, eta), rsp, 1e-15) << eta;
  }
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
  const double eta = 1.5, mu_c = std::sqrt(1 - 1 / (eta * eta));
  EXPECT_EQ(fresnel_reflectance(mu_c * 0.999, eta), 1.0);
  EXPECT_LT(fresnel_reflectance(mu_c * 1.001 + 0.001, eta), 1.0);
  // From the outside (x < 1) there is no total internal reflection; grazing incidence reflects all.
  EXPECT_LT(fresnel_reflectance(0.2, 1 / eta), 1.0);
  EXPECT_NEAR(fresnel_reflectance(1e-9, 1 / eta), 1.0, 1e-6);
}

struct MomentRow {
  double eta, two_c1_internal, fit_two_c1, two_c1_external, three_c2_internal, fit_three_c2;
};
// Exact moments by adaptive quadrature of the Fresnel formula (five decimals) and the polynomial
// fits at the same eta: 2C1 inside (eta) and outside (1/eta), 3C2 inside.
const MomentRow kMoments[] = {
    {1.3, 0.44446, 0.44529, 0.06113, 0.30027, 0.29745},
    {1.4, 0.52899, 0.52988, 0.07681, 0.38878, 0.38635},
    {1.5, 0.59635, 0.59654, 0.09178, 0.46443, 0.46261},
};

TEST(Fresnel, ExactMomentsMatchThePublishedTable) {
  for (const auto& row : kMoments) {
    EXPECT_NEAR(2 * fresnel_moment(1, row.eta), row.two_c1_internal, 6e-6) << row.eta;
    EXPECT_NEAR(2 * fresnel_moment(1, 1 / row.eta), row.two_c1_external, 6e-6) << row.eta;
    EXPECT_NEAR(3 * fresnel_moment(2, row.eta), row.three_c2_internal, 6e-6) << row.eta;
  }
}

TEST(Fresnel, MomentsAtMatchedIndexVanish) {
  EXPECT_NEAR(fresnel_moment(1, 1.0), 0.0, 1e-15);
  EXPECT_NEAR(fresnel_moment(2, 1.0), 0.0, 1e-15);
}

TEST(Fresnel, MomentQuadratureIsConverged) {
  // The exact moment by an independent adaptive rule on the raw integrand, split at mu_c.
  for (double x : {0.5, 0.77, 1.1, 1.3, 1.5, 2.5}) {
    for (int n : {0, 1, 2}) {
      const double mu_c = x > 1 ? std::sqrt(1 - 1 / (x * x)) : 0.0;
      const auto f = [&](double mu) { return fresnel_reflectance(mu, x) * std::pow(mu, n); };
      const double reference = std::pow(mu_c, n + 1) / (n + 1) + integrate_adaptive(f, mu_c, 1.0, 1e-13).value;
      EXPECT_NEAR(fresnel_moment(n, x), reference, 1e-11) << "x=" << x << " n=" << n;
    }
  }
}

TEST(Fresnel, DEonIrvingFitsReproduceThePublishedFitValues) {
  for (const auto& row : kMoments) {
    EXPECT_NEAR(fresnel_2c1_fit(row.eta), row.fit_two_c1, 6e-6) << row.eta;
    EXPECT_NEAR(fresnel_3c2_fit(row.eta), row.fit_three_c2, 6e-6) << row.eta;
  }
}

// Documented error of the fits against the exact moments (fresnel.hpp): measured over
// eta in [1, 2] (internal) and its reciprocal range (external).
TEST(Fresnel, FitsStayWithinTheirDocumentedError) {
  double worst_c1 = 0, worst_c2 = 0, worst_eh = 0;
  for (double eta = 1.0; eta <= 2.0001; eta += 0.01) {
    for (double x : {eta, 1 / eta}) {
      worst_c1 = std::max(worst_c1, std::abs(fresnel_2c1_fit(x) - 2 * fresnel_moment(1, x)));
      worst_c2 = std::max(worst_c2, std::abs(fresnel_3c2_fit(x) - 3 * fresnel_moment(2, x)));
    }
    worst_eh = std::max(worst_eh, std::abs(diffuse_reflectance_egan_hilgeman(eta) - 2 * fresnel_moment(1, eta)));
  }
  std::printf(
      "max |fit - exact| over eta in [1, 2] and [0.5, 1]: 2C1 %.5f, 3C2 %.5f; "
      "Egan-Hilgeman F_dr vs 2C1 (eta >= 1): %.5f\n",
      worst_c1, worst_c2, worst_eh);
  EXPECT_LT(worst_c1, kFitErrorTwoC1);
  EXPECT_LT(worst_c2, kFitErrorThreeC2);
  EXPECT_LT(worst_eh, kFitErrorEganHilgeman);
}

TEST(Fresnel, BoundaryParameterMatchesThePublishedValues) {
  // A = 2.602 (classical) and 2.341 (improved) at eta = 1.3 (Jensen et al. 2001; d'Eon 2012;
  // tests/data/REFERENCE_CHECKS.md).
  EXPECT_NEAR(boundary_A_classical(1.3), 2.602, 5e-4);
  EXPECT_NEAR(improved_boundary(1.3).A, 2.341, 5e-4);
  const auto b = improved_boundary(1.0);
  EXPECT_NEAR(b.A, 1.0, 1e-12);
  EXPECT_NEAR(b.C_phi, 0.25, 1e-12);
  EXPECT_NEAR(b.C_E, 0.5, 1e-12);
}
