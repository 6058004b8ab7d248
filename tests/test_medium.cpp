// Medium validation, units and the reduced quantities (notation in tests/data/REFERENCE_CHECKS.md).
#include <gtest/gtest.h>

#include <cmath>

#include "bssrdf/error.hpp"
#include "bssrdf/medium.hpp"
#include "bssrdf/units.hpp"

using namespace bssrdf;

namespace {
Medium rgb() {
  Medium m;
  m.channel_names = {"R", "G", "B"};
  m.sigma_a = {0.032, 0.17, 0.48};
  m.sigma_s = {0.74, 0.88, 1.01};
  m.g = {0, 0, 0};
  m.eta = 1.3;
  return m;
}

std::string error_of(const Medium& m) {
  try {
    m.validate();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Medium, ValidMediumPasses) { EXPECT_EQ(error_of(rgb()), ""); }

TEST(Medium, EachRuleNamesFieldValueAndRange) {
  auto m = rgb();
  m.sigma_a[1] = -1;
  EXPECT_EQ(error_of(m),
            "sigma_a[G] = -1: accepted range is >= 0 and finite, at most 1e+06 (a 1 nm mean free path in mm)");
  m = rgb();
  m.sigma_s[2] = std::nan("");
  EXPECT_EQ(error_of(m),
            "sigma_s[B] = nan: accepted range is >= 0 and finite, at most 1e+06 (a 1 nm mean free path in mm)");
  m = rgb();
  m.sigma_a[0] = m.sigma_s[0] = 0;
  EXPECT_NE(error_of(m).find("sigma_a[R] + sigma_s[R]"), std::string::npos);
  m = rgb();
  m.g[0] = 1.0;
  EXPECT_EQ(error_of(m), "g[R] = 1: accepted range is -1 < g < 1");
  m.g[0] = -1.0;
  EXPECT_EQ(error_of(m), "g[R] = -1: accepted range is -1 < g < 1");
  m = rgb();
  m.eta = 0;
  EXPECT_NE(error_of(m).find("eta = 0"), std::string::npos);
  m.eta = INFINITY;
  EXPECT_NE(error_of(m).find("eta = inf"), std::string::npos);
  m = rgb();
  m.g.pop_back();
  EXPECT_NE(error_of(m).find("g: 2 channels given, but sigma_a has 3"), std::string::npos);
  m = rgb();
  m.channel_names[2] = "R";
  EXPECT_NE(error_of(m).find("'R'"), std::string::npos);
}

TEST(Medium, AnyChannelCount) {
  Medium m;
  m.channel_names = default_channel_names(5);
  EXPECT_EQ(m.channel_names[4], "c4");
  m.sigma_a.assign(5, 0.1);
  m.sigma_s.assign(5, 1.0);
  m.g.assign(5, 0.5);
  EXPECT_EQ(error_of(m), "");
  EXPECT_EQ(m.channels(), 5u);
}

TEST(Medium, ReducedQuantitiesByHand) {
  // sigma_a = 0.1, sigma_s = 2, g = 0.75 -> sigma_s' = 0.5, sigma_t' = 0.6.
  const auto r = reduce(0.1, 2.0, 0.75, 1.4);
  EXPECT_DOUBLE_EQ(r.sigma_s_prime, 0.5);
  EXPECT_DOUBLE_EQ(r.sigma_t_prime, 0.6);
  EXPECT_DOUBLE_EQ(r.albedo_prime, 0.5 / 0.6);
  EXPECT_DOUBLE_EQ(r.ell, 1 / 0.6);
  EXPECT_DOUBLE_EQ(r.D, 1 / 1.8);
  EXPECT_DOUBLE_EQ(r.D_G, (0.2 + 0.5) / (3 * 0.36));
  EXPECT_DOUBLE_EQ(r.sigma_tr, std::sqrt(3 * 0.1 * 0.6));
  EXPECT_DOUBLE_EQ(r.sigma_tr, std::sqrt(r.sigma_a / r.D));
  EXPECT_DOUBLE_EQ(r.sigma_tr_G, std::sqrt(0.1 / r.D_G));
  EXPECT_DOUBLE_EQ(r.ell_d, 1 / r.sigma_tr);
  EXPECT_DOUBLE_EQ(r.albedo(), 2.0 / 2.1);
  const auto zero = reduce(0.0, 1.0, 0.0, 1.0);
  EXPECT_EQ(zero.sigma_tr, 0.0);
  EXPECT_TRUE(std::isinf(zero.ell_d));
}

TEST(Units, ConversionsRoundTrip) {
  EXPECT_EQ(parse_length_unit("MM"), LengthUnit::millimetre);
  EXPECT_EQ(parse_length_unit("um"), LengthUnit::micrometre);
  EXPECT_EQ(parse_length_unit("\xc2\xb5m"), LengthUnit::micrometre);
  EXPECT_EQ(parse_length_unit("cm"), LengthUnit::centimetre);
  EXPECT_EQ(parse_length_unit("m"), LengthUnit::metre);
  EXPECT_THROW(parse_length_unit("inch"), InvalidInput);
  // 1/cm -> 1/mm: 10 /cm = 1 /mm; 2 cm = 20 mm.
  EXPECT_DOUBLE_EQ(coefficient_to_per_mm(10.0, LengthUnit::centimetre), 1.0);
  EXPECT_DOUBLE_EQ(to_mm(2.0, LengthUnit::centimetre), 20.0);
  for (auto u : {LengthUnit::micrometre, LengthUnit::millimetre, LengthUnit::centimetre, LengthUnit::metre}) {
    EXPECT_DOUBLE_EQ(from_mm(to_mm(3.7, u), u), 3.7);
    EXPECT_DOUBLE_EQ(coefficient_from_per_mm(coefficient_to_per_mm(0.37, u), u), 0.37);
    EXPECT_EQ(parse_length_unit(symbol(u)), u);
  }
}
