// The surface albedo of `materials show/export` (derived_quantities.hpp) is the exact model's
// total inside its domain and stays <= 1 for all 47 bundled materials; outside the domain it keeps
// the physical model's total (or adding-doubling where that exceeds 1).
#include <gtest/gtest.h>

#include "bssrdf/derived_quantities.hpp"
#include "bssrdf/materials.hpp"
#include "bssrdf/model.hpp"
#include "bssrdf/model_registry.hpp"
#include "bssrdf/models/exact.hpp"

using namespace bssrdf;

TEST(SurfaceAlbedoExact, TiedToTheExactTotalInsideTheDomainAndNeverAboveOne) {
  const auto db = MaterialDatabase::load(default_materials_dir());
  ASSERT_EQ(db.all().size(), 47u);
  const auto pbd = make_model("pbd");
  std::size_t inside = 0, outside = 0;
  for (const auto& material : db.all()) {
    const auto q = derive_quantities(material.medium);
    for (std::size_t c = 0; c < q.channels.size(); ++c) {
      const auto m = material.medium.reduced(c);
      const auto& ch = q.channels[c];
      EXPECT_LE(ch.surface_albedo, 1.0) << material.name << " " << ch.name;
      EXPECT_GE(ch.surface_albedo, 0.0) << material.name << " " << ch.name;  // 0 where nothing scatters (sigma_s' = 0)
      if (exact_domain(bundled_exact_table(), m.albedo_prime, m.g, m.eta).empty()) {
        ++inside;
        EXPECT_EQ(ch.surface_albedo > 0, m.sigma_s_prime > 0) << material.name << " " << ch.name;
        EXPECT_EQ(ch.surface_albedo, exact_total(bundled_exact_table(), m.albedo_prime, m.g, m.eta)) << material.name;
      } else {
        ++outside;
        const double model_total = pbd->total_reflectance(m);
        if (model_total <= 1) {
          EXPECT_EQ(ch.surface_albedo, model_total) << material.name << " " << ch.name;
        }
      }
    }
  }
  std::printf("[ measured ] %zu channels inside the exact domain, %zu outside\n", inside, outside);
  EXPECT_GT(inside, 100u);  // 35 materials fully inside
}
