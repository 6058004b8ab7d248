// Classical and better dipole: closed forms against numerical integrals, published values,
// albedo inversion, stability at the edges of the parameter space, and autodiff.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bssrdf/error.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/better_dipole.hpp"
#include "bssrdf/models/dipole.hpp"
#include "bssrdf/quadrature.hpp"

using namespace bssrdf;

namespace {
const double kAlbedos[] = {0.01, 0.1, 0.3, 0.5, 0.8, 0.9, 0.99, 0.999, 1.0};
const double kEtas[] = {1.0, 1.3, 1.5, 0.8};
}  // namespace

class EachModel : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<Model> model = make_model(GetParam());
};

TEST_P(EachModel, ClosedFormTotalEqualsTheNumericalIntegral) {
  for (double eta : kEtas)
    for (double a : kAlbedos) {
      if (a == 1.0) continue;  // the 1/r^3 tail makes the numerical integral slow; checked below
      // A physical scale other than 1 checks the units: sigma_t' = 2.5 / mm.
      const auto m = reduce_prime(2.5 * (1 - a), 2.5 * a, eta);
      const auto numeric = integrate_radial([&](double r) { return model->reflectance(m, r); }, 0.0,
                                            std::numeric_limits<double>::infinity(), m.ell, 1e-10);
      const double closed = model->total_reflectance(m);
      EXPECT_NEAR(numeric.value / closed, 1.0, 1e-6) << "alpha'=" << a << " eta=" << eta;
    }
}

TEST_P(EachModel, ClosedFormCumulativeEqualsTheNumericalIntegral) {
  const auto m = reduce_prime(0.05, 1.2, 1.4);
  for (double r : {1e-3, 0.1, 0.8, 3.0, 20.0}) {
    const double numeric =
        integrate_radial([&](double x) { return model->reflectance(m, x); }, 0.0, r, m.ell, 1e-11).value;
    EXPECT_NEAR(model->cumulative_reflectance(m, r) / numeric, 1.0, 1e-8) << r;
  }
}

TEST_P(EachModel, NonAbsorbingMediumReflectsEverything) {
  // sigma_a = 0: diffusion theory conserves energy, total reflectance 1 (closed form and integral).
  for (double eta : kEtas) {
    const auto m = reduce_prime(0.0, 1.0, eta);
    EXPECT_NEAR(model->total_reflectance(m), 1.0, 1e-12) << eta;
    EXPECT_NEAR(model->cumulative_reflectance(m, 1e6), 1.0, 1e-5) << eta;
  }
}

TEST_P(EachModel, AlbedoInversionRoundTrips) {
  for (double eta : kEtas)
    for (double a : kAlbedos) {
      const double total = model->total_reflectance(reduced_optical(a, eta));
      EXPECT_NEAR(model->albedo_prime_from_total(total, eta, 0.0), a, 1e-12) << "alpha'=" << a << " eta=" << eta;
    }
}

TEST_P(EachModel, AlbedoInversionRejectsUnreachableTotals) {
  EXPECT_THROW(model->albedo_prime_from_total(1.2, 1.3, 0.0), InvalidInput);
  EXPECT_THROW(model->albedo_prime_from_total(-0.1, 1.3, 0.0), InvalidInput);
  EXPECT_THROW(model->albedo_prime_from_total(std::nan(""), 1.3, 0.0), InvalidInput);
}

TEST_P(EachModel, EnergyRadiusHoldsTheRequestedFraction) {
  const auto m = reduce_prime(0.032, 0.74, 1.3);  // Jensen skin, red
  for (double f : {0.5, 0.9, 0.99, 0.999}) {
    const double r = model->radius_for_fraction(m, f);
    EXPECT_NEAR(model->cumulative_reflectance(m, r) / model->total_reflectance(m), f, 1e-9) << f;
  }
  EXPECT_LT(model->radius_for_fraction(m, 0.5), model->radius_for_fraction(m, 0.9));
}

TEST_P(EachModel, StableAtTheEdges) {
  for (double eta : kEtas)
    for (double a : {0.0, 1e-9, 0.5, 1.0 - 1e-12, 1.0}) {
      const auto m = reduced_optical(a, eta);
      for (double r : {0.0, 1e-300, 1e-12, 1.0, 1e3, 1e12}) {
        const double R = model->reflectance(m, r);
        EXPECT_TRUE(std::isfinite(R) && R >= 0) << "alpha'=" << a << " eta=" << eta << " r=" << r << " R=" << R;
      }
      const double total = model->total_reflectance(m);
      EXPECT_TRUE(std::isfinite(total) && total >= 0 && total <= 1 + 1e-12) << total;
    }
  // The profile decays: far away it vanishes, and at r -> 0 it is finite (not a singularity).
  const auto m = reduced_optical(0.9, 1.3);
  EXPECT_LT(model->reflectance(m, 1e3), 1e-30);
  EXPECT_NEAR(model->reflectance(m, 1e-12), model->reflectance(m, 0.0), 1e-12);
}

TEST_P(EachModel, ProfileScalesWithTheTransportMeanFreePath) {
  // R(r) in physical units = sigma_t'^2 R_optical(r sigma_t'): the model has no hidden length.
  const double s = 7.0;
  const auto optical = reduced_optical(0.9, 1.3);
  const auto physical = reduce_prime(s * 0.1, s * 0.9, 1.3);
  for (double r : {0.01, 0.3, 2.0})
    EXPECT_NEAR(model->reflectance(physical, r / s), s * s * model->reflectance(optical, r),
                1e-12 * s * s * model->reflectance(optical, r));
}

TEST_P(EachModel, ValidityReportsLowAlbedoAndKnownLimits) {
  const auto worst = [&](double a, double eta, double g = 0) {
    return bssrdf::worst(model->validity(reduce(1 - a, a / (1 - g), g, eta)));
  };
  EXPECT_EQ(worst(0.05, 1.3), Severity::invalid);
  EXPECT_EQ(worst(0.3, 1.0), Severity::invalid);
  EXPECT_EQ(worst(0.92, 1.3), Severity::warning);
  EXPECT_EQ(worst(0.995, 1.3), Severity::note);
  EXPECT_EQ(worst(0.995, 2.5), Severity::warning);  // eta outside the measured range
  bool near_field = false, similarity = false;
  for (const auto& n : model->validity(reduce(0.01, 10.0, 0.9, 1.3))) {
    near_field |= n.code == "near_field";
    similarity |= n.code == "similarity";
  }
  EXPECT_TRUE(near_field);
  EXPECT_TRUE(similarity);
  // The classical dipole's total reproduces the full total, single scattering included (measured:
  // test_single_scattering_composition.cpp); the better dipole's omits it.
  EXPECT_EQ(model->includes_single_scattering(), model->name() == "dipole");
}

INSTANTIATE_TEST_SUITE_P(Dipoles, EachModel, ::testing::Values("dipole", "better-dipole"), [](const auto& info) {
  std::string n = info.param;
  for (auto& c : n)
    if (c == '-') c = '_';
  return n;
});

TEST(Models, PublishedReferenceChecks) {
  // tests/data/REFERENCE_CHECKS.md: semi-infinite, eta = 1.3, g = 0, alpha = 0.99, per entered flux.
  EXPECT_NEAR(classical_dipole::total_reflectance(0.99, 1.3), 0.645, 5e-4);
  EXPECT_NEAR(better_dipole::total_reflectance(0.99, 1.3), 0.642, 5e-4);
}

TEST(Models, ClassicalTotalFormulaByHand) {
  // alpha' = 0.9, eta = 1: A from Egan-Hilgeman (F_dr = 0.0016).
  const double A = (1 + 0.0016) / (1 - 0.0016), s = std::sqrt(3 * 0.1);
  EXPECT_NEAR(classical_dipole::total_reflectance(0.9, 1.0), 0.45 * (1 + std::exp(-4.0 / 3 * A * s)) * std::exp(-s),
              1e-12);
}

TEST(Models, UnknownModelNamesTheKnownOnes) {
  try {
    make_model("tripole");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("better-dipole"), std::string::npos) << e.what();
  }
}

TEST(Models, ProfilesDifferentiateUnderCeresJet) {
  // The templated math runs under ceres::Jet; derivatives match central differences.
  using Jet = ceres::Jet<double, 2>;
  const double sa = 0.05, ssp = 1.1, eta = 1.3, r = 0.7, h = 1e-6;
  const auto m = reduce_prime(Jet(sa, 0), Jet(ssp, 1), Jet(eta));
  const Jet R_classical = classical_dipole::reflectance(m, Jet(r));
  const Jet R_better = better_dipole::reflectance(m, Jet(r));
  const auto fd = [&](auto f) {
    return std::pair{(f(sa + h, ssp) - f(sa - h, ssp)) / (2 * h), (f(sa, ssp + h) - f(sa, ssp - h)) / (2 * h)};
  };
  const auto [c0, c1] =
      fd([&](double a, double s) { return classical_dipole::reflectance(reduce_prime(a, s, eta), r); });
  const auto [b0, b1] = fd([&](double a, double s) { return better_dipole::reflectance(reduce_prime(a, s, eta), r); });
  EXPECT_NEAR(R_classical.v[0], c0, 1e-6 * std::abs(c0));
  EXPECT_NEAR(R_classical.v[1], c1, 1e-6 * std::abs(c1));
  EXPECT_NEAR(R_better.v[0], b0, 1e-6 * std::abs(b0));
  EXPECT_NEAR(R_better.v[1], b1, 1e-6 * std::abs(b1));
  // The closed-form totals too (alpha' and eta derivatives).
  const Jet total = better_dipole::total_reflectance(Jet(0.9, 0), Jet(1.3, 1));
  const double dt_da =
      (better_dipole::total_reflectance(0.9 + h, 1.3) - better_dipole::total_reflectance(0.9 - h, 1.3)) / (2 * h);
  const double dt_de =
      (better_dipole::total_reflectance(0.9, 1.3 + h) - better_dipole::total_reflectance(0.9, 1.3 - h)) / (2 * h);
  EXPECT_NEAR(total.v[0], dt_da, 1e-6 * std::abs(dt_da));
  EXPECT_NEAR(total.v[1], dt_de, 1e-5 * std::abs(dt_de));
}
