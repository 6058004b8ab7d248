// Oblique incidence in adding-doubling (Options::incidence_cosine, iad's -i): a clear absorbing
// slab against Fresnel's and Beer's laws at the refracted angle (exact), scattering slabs against
// Prahl's ad 4-0-0 at 96 quadrature points (its 5 decimals), and normal incidence unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bssrdf/adding_doubling/slab.hpp"
#include "bssrdf/error.hpp"

using namespace bssrdf;
using namespace bssrdf::adding_doubling;

namespace {

// Unpolarised Fresnel reflectance from index n1 into n2 at the cosine c1 in n1.
double fresnel(double n1, double n2, double c1) {
  const double s2 = n1 / n2 * std::sqrt(1 - c1 * c1);
  if (s2 >= 1) return 1;
  const double c2 = std::sqrt(1 - s2 * s2);
  const double rs = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2);
  const double rp = (n1 * c2 - n2 * c1) / (n1 * c2 + n2 * c1);
  return (rs * rs + rp * rp) / 2;
}

Slab slab_of(double a, double b, double g, double n, double slide_n) {
  Slab slab;
  slab.layers = {{(1 - a) * b, a * b, g, std::isinf(b) ? kSemiInfinite : 1.0}};
  if (std::isinf(b)) slab.layers[0] = {1 - a, a, g, kSemiInfinite};
  slab.n = n;
  if (slide_n != 1) slab.above = slab.below = {{slide_n, 1.0, 0.0}};
  return slab;
}

}  // namespace

TEST(AddingDoublingOblique, ClearSlabFollowsFresnelAndBeerAtTheRefractedAngle) {
  const double n = 1.4, tau = 0.7;
  for (double degrees : {10.0, 45.0, 70.0}) {
    const double c = std::cos(degrees * M_PI / 180);
    Slab slab;
    slab.layers = {{tau, 0.0, 0.0, 1.0}};
    slab.n = n;
    Options options;
    options.points = 24;
    options.incidence_cosine = c;
    const auto t = solve(slab, Incidence::collimated, options);
    const double mu = std::sqrt(1 - (1 - c * c) / (n * n));
    const double r = fresnel(1, n, c), e = std::exp(-tau / mu);
    const double bounce = 1 - r * r * e * e;
    EXPECT_NEAR(t.specular_reflectance, r, 1e-14) << degrees;
    EXPECT_NEAR(t.total_transmittance, (1 - r) * (1 - r) * e / bounce, 1e-14) << degrees;
    EXPECT_NEAR(t.unscattered_transmittance, t.total_transmittance, 1e-14) << degrees;
    EXPECT_NEAR(t.specular_reflectance + t.diffuse_reflectance, r + (1 - r) * (1 - r) * r * e * e / bounce, 1e-14)
        << degrees;
  }
}

TEST(AddingDoublingOblique, AgreesWithPrahlsAdAtNinetySixPoints) {
  // ad -a A -b B -g G -n N [-s S] -i DEG -q 96 -m (ad 4-0-0, Prahl): UR1, UT1, URU, UTU.
  struct Case {
    double a, b, g, n, slide, degrees, ur1, ut1, uru, utu;
  };
  const Case cases[] = {
      {0.9, 2, 0.5, 1.4, 1, 30, 0.18586, 0.38618, 0.23462, 0.34241},
      {0.99, 1, 0.8, 1.4, 1.5, 60, 0.29057, 0.66600, 0.25742, 0.70634},
      {0.5, 0.5, 0, 1.0, 1, 45, 0.09540, 0.57893, 0.10768, 0.53499},
      {0.95, INFINITY, 0.7, 1.33, 1, 20, 0.22018, 0.0, 0.26947, 0.0},
      {0.8, 3, -0.3, 1.5, 1.5, 75, 0.39314, 0.04473, 0.26111, 0.07067},
  };
  double worst = 0;
  for (const auto& k : cases) {
    Options options;
    options.points = 96;
    options.incidence_cosine = std::cos(k.degrees * M_PI / 180);
    const auto both = solve(slab_of(k.a, k.b, k.g, k.n, k.slide), {Incidence::collimated, Incidence::diffuse}, options);
    const auto& c = both[0];
    const auto& d = both[1];
    // ad's 5 decimals, and its own change from 48 to 96 points (up to 4e-5 in URU).
    EXPECT_NEAR(c.specular_reflectance + c.diffuse_reflectance, k.ur1, 3e-5) << k.degrees << " degrees";
    EXPECT_NEAR(c.total_transmittance, k.ut1, 3e-5) << k.degrees << " degrees";
    EXPECT_NEAR(d.specular_reflectance + d.diffuse_reflectance, k.uru, 5e-5) << k.degrees << " degrees";
    EXPECT_NEAR(d.total_transmittance, k.utu, 5e-5) << k.degrees << " degrees";
    worst = std::max({worst, std::abs(c.specular_reflectance + c.diffuse_reflectance - k.ur1),
                      std::abs(c.total_transmittance - k.ut1)});
    // And the angle matters: at normal incidence UR1 differs by more than the tolerance.
    Options normal = options;
    normal.incidence_cosine = 1;
    const auto n = solve(slab_of(k.a, k.b, k.g, k.n, k.slide), Incidence::collimated, normal);
    EXPECT_GT(std::abs(n.specular_reflectance + n.diffuse_reflectance - k.ur1), 3e-4) << k.degrees << " degrees";
  }
  std::printf("  oblique UR1, UT1 against Prahl's ad (5 decimals): worst |difference| %.1e\n", worst);
}

TEST(AddingDoublingOblique, ConservesEnergyAndRefusesGrazingBeams) {
  Options options;
  options.incidence_cosine = std::cos(40 * M_PI / 180);
  const auto t = solve(slab_of(1.0, 3, 0.8, 1.4, 1.5), Incidence::collimated, options);
  EXPECT_NEAR(t.absorbed(), 0, 1e-12);
  EXPECT_GE(t.points, 32);
  for (double bad : {0.0, -0.5, 1.5, double(NAN)}) {
    options.incidence_cosine = bad;
    EXPECT_THROW(solve(slab_of(0.9, 1, 0, 1.4, 1), Incidence::collimated, options), InvalidInput) << bad;
  }
}
