// The reference `bssrdf advise --reference auto` judges against, chosen per channel so that every
// material of the database is advised in well under a second:
//  - inside the exact model's table: the exact model (its band: the registry's measured accuracy);
//  - near-conservative channels above the table (alpha' > 0.9999: Cream's red, Spectralon), where a
//    Monte Carlo walk is long (Spectralon: 2000 photons took 5.5 s on 2 cores, 2.5 code values of
//    noise): the radiative-transfer total (transport_total.hpp: adding-doubling, band 1e-3, above its
//    measured agreement with Monte Carlo; 1 without absorption) with the shape of the model measured most accurate
//    there against Monte Carlo (model_choice.hpp's table; band: that measured profile error);
//  - elsewhere (alpha' below the table: clear beverages; g or eta outside it): a Monte Carlo run of
//    those channels alone, at the photons given (short walks: a few milliseconds below the table).
// Every channel says which it got (ReferenceSources), and reference_uncertainty.hpp turns the bands
// and the noise into the image error the reference may itself be off by.
//
//   AutoReference reference({.photons = 200'000});
//   Advice a = advise(cream, reference, options);   // a.reference names "exact" / "pbd+AD" / "montecarlo" per channel
#pragma once

#include <map>
#include <memory>
#include <string>

#include "bssrdf/image/reference_profile.hpp"
#include "bssrdf/model.hpp"

namespace bssrdf {

// Band of the adding-doubling total: its agreement with 1e7-photon Monte Carlo is within 2.4e-4
// absolute over 16 cases (tools/validation/adding_doubling_vs_montecarlo.txt); 1e-3 relative covers it.
inline constexpr double kAddingDoublingTotalBand = 1e-3;

// The source `auto` gives one channel: "exact", "montecarlo" or the shape model's name.
std::string auto_reference_source(const Reduced<double>& m);

class AutoReference : public ReferenceProfile {
 public:
  explicit AutoReference(MonteCarloReferenceOptions monte_carlo);
  ReferenceProfiles profiles(const Medium& medium) const override;

 private:
  MonteCarloReferenceOptions monte_carlo_;
  std::map<std::string, std::unique_ptr<Model>> models_;  // exact and the shape models, alive as long as this
};

}  // namespace bssrdf
